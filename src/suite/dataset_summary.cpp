#include "cosmo/suite/dataset_summary.hpp"

#include <filesystem>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {

DatasetSummary summariseDataset(const std::string& folder, const std::string& jrl, const std::string& name,
                                const std::string& comm) {
  const jrl::Dataset dataset = jrl::readJrl((fs::path(folder) / jrl).string());
  DatasetSummary d;
  d.name = name;
  d.comm = comm;
  d.jrl = jrl;
  const std::string stem = fs::path(jrl).stem().string();
  if (fs::exists(fs::path(folder) / (stem + ".trajectories.svg"))) d.figure = stem + ".trajectories.svg";
  const jrl::DatasetStats s = jrl::computeStats(dataset);
  d.duration_s = s.duration_s;
  d.length_m = s.length_m;
  d.lc = s.lc_count;
  d.lc_outliers = s.lc_outliers;
  d.irlc = s.irlc_count;
  d.irlc_outliers = s.irlc_outliers;
  d.labelled = s.has_outlier_labels;
  d.violations = jrl::validate(dataset).size();
  if (!dataset.outliers) {
    d.solve_note = "no outlier labels";
    return d;
  }
  try {
    const backend::DatasetCheck check = backend::checkDataset(dataset, {backend::FactorSelection::Inliers});
    d.inliers_ate_m = check.solves.front().error.overall.trans_m;
    d.init_ate_m = check.init.overall.trans_m;
  } catch (const std::exception& e) { d.solve_note = e.what(); }
  return d;
}

}  // namespace cosmo::suite
