#pragma once
// Dataset metadata of the paper's Fig. 1 (issue 2, `cosmo_jrl stats`).
//   duration = last minus first entry stamp over all robots; length = sum over robots of the ground-truth
//   trajectory length of that robot's own poses (in index order); odometry = BetweenFactorPose3 <r>i -> <r>(i+1);
//   LC = any other BetweenFactorPose3 within one robot; IRLC = BetweenFactorPose3 between two robots;
//   outliers = factors listed in outlier_factors.
#include <cstddef>
#include <string>
#include <vector>

#include "cosmo/common/time.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

struct DatasetStats {
  std::string name;
  std::vector<char> robots;
  std::size_t entries = 0, factors = 0, priors = 0, odometry = 0;
  StampNs first_stamp = 0, last_stamp = 0;  ///< over all robots (0 when there are no entries)
  double duration_s = 0.0;                  ///< exact, seconds
  double length_m = 0.0;                    ///< 0 without ground truth
  bool has_groundtruth = false, has_outlier_labels = false;
  std::size_t lc_count = 0, lc_outliers = 0, irlc_count = 0, irlc_outliers = 0;

  double lcOutlierPercent() const { return lc_count ? 100.0 * double(lc_outliers) / double(lc_count) : 0.0; }
  double irlcOutlierPercent() const { return irlc_count ? 100.0 * double(irlc_outliers) / double(irlc_count) : 0.0; }
  long durationRoundedS() const;  ///< rounded to the second
};

DatasetStats computeStats(const Dataset& dataset);
/// "MM:SS" of a duration rounded to the second (minutes may exceed 59), e.g. 725.87 -> "12:06".
std::string formatDuration(double seconds);
/// Human-readable block, e.g.
///   tuhh_r3_01_night_wifi
///     robots    a b c
///     duration  12:06
///     length    2.13 km
///     LC        356 (13.5 %), 48 outliers
///     IRLC      280 (9.6 %), 27 outliers
///     entries   1057, factors 1661 (3 priors, 1022 odometry)
std::string formatStats(const DatasetStats& stats);
/// One compact JSON object: name, robots (["a","b"]), entries, factors, odometry, duration_s (rounded to the
/// second), duration ("MM:SS"), duration_exact_s, length_m, lc_count, lc_outliers, lc_outlier_pct, irlc_count,
/// irlc_outliers, irlc_outlier_pct, has_outlier_labels.
std::string statsJson(const DatasetStats& stats);

}  // namespace cosmo::jrl
