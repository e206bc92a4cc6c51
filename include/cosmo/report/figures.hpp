#pragma once
// The two figures of a dataset, in the style of the COSMO-Bench paper, as SVG text:
//   trajectories (Fig. 1): one colour per robot, the ground-truth trajectories, every loop closure as a line
//     between its two ground-truth poses (intra-robot in the owner's colour, inter-robot in grey; inliers solid,
//     outliers red and dashed), and the metadata table (jrl/stats.hpp);
//   frontend (Fig. 2): (a) the odometry (the dataset's dead-reckoned initialization) against the reference,
//     with a dot per keyframe; (b) the measurements: each loop closure drawn from the ground truth of key1 to
//     where it places key2 (an inlier ends on key2's reference pose, an outlier elsewhere);
//   connectivity (of the radio run, comm/connectivity.hpp): per robot pair the intervals its link was up and its
//     throughput per window against time, and the robots in range (connected pairs) below.
// Top view (x, y in metres), equal aspect, a scale bar. Deterministic: the same dataset gives the same bytes.
#include <string>
#include <vector>

#include "cosmo/comm/connectivity.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::report {

struct FigureOptions {
  std::string source;  ///< the table's "source" row (e.g. the JRL file name); omitted when empty
};

/// Throws std::runtime_error when the dataset has no ground truth or a factor is not a Pose3 factor.
std::string trajectoriesSvg(const jrl::Dataset& dataset, const FigureOptions& options = {});
/// Throws std::runtime_error when the dataset has no ground truth or no initialization.
std::string frontendSvg(const jrl::Dataset& dataset);
/// `title`: the dataset's name.
std::string connectivitySvg(const comm::Connectivity& connectivity, const std::string& title);

/// The figures of the dataset read from / written to `jrl_path`, as <dir>/<stem>.trajectories.svg and
/// <dir>/<stem>.frontend.svg, and <dir>/<stem>.connectivity.svg when the radio run's <stem>_connectivity.json is
/// beside the JRL (comm::datasetConnectivityPath), dir = `out_dir` or the JRL's folder; each also as .png when
/// `png` is set and ImageMagick's `convert` is on the PATH. Returns the paths written. Throws std::runtime_error naming
/// a file that cannot be written (or the dataset's problem, as above).
std::vector<std::string> writeDatasetFigures(const jrl::Dataset& dataset, const std::string& jrl_path,
                                             const std::string& out_dir = "", bool png = true);

/// writeDatasetFigures() beside the JRL for the drivers (offline driver, recorder node), as one line to print:
/// "figures: <dir>/<stem>.trajectories.svg/.png, <dir>/<stem>.frontend.svg/.png", or "figures not written: <why>".
/// Never throws: a figure problem never costs the dataset.
std::string writeFiguresBesideJrl(const jrl::Dataset& dataset, const std::string& jrl_path);

}  // namespace cosmo::report
