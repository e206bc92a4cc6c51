// bench_closure_errors: how a dataset's loop closures compare with its ground truth, and how its outlier labels
// treat them. Per kind (intra-robot LC, inter-robot IRLC): count, labelled outliers, the "good" closures (error
// under the noise-model thresholds, spec section 6) with their median / p90 errors and the share labelled
// inliers, the closures off by more than 2 m and how many of them are labelled outliers, and the median error of
// the good closures by the distance between the two poses (error growing with distance).
//   bench_closure_errors FILE.jrl... [--relabel NOISE.yaml] [--good-translation M] [--good-rotation RAD]
// --relabel labels with that noise-model file (fidelity rule) instead of the file's own labels.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/jrl/io.hpp"

using namespace cosmo;

namespace {

struct Closure {
  double translation_error = 0, rotation_error = 0, distance = 0;
  bool outlier = false;
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

void report(const char* kind, const std::vector<Closure>& cs, double good_t, double good_r) {
  std::size_t outliers = 0, gross = 0, gross_outliers = 0, good_inliers = 0;
  std::vector<double> te, re;
  const double bins[] = {0, 5, 10, 20, 1e9};
  std::vector<double> by_bin[4];
  for (const auto& c : cs) {
    outliers += c.outlier;
    if (c.translation_error > 2.0) {
      ++gross;
      gross_outliers += c.outlier;
    }
    if (c.translation_error < good_t && c.rotation_error < good_r) {
      te.push_back(c.translation_error);
      re.push_back(c.rotation_error * 180.0 / M_PI);
      good_inliers += !c.outlier;
      for (int b = 0; b < 4; ++b)
        if (c.distance >= bins[b] && c.distance < bins[b + 1]) by_bin[b].push_back(c.translation_error);
    }
  }
  const double n = std::max<double>(1, static_cast<double>(cs.size()));
  std::printf(
      "  %-4s %4zu, outliers %3zu (%.1f %%); good %zu, labelled inliers %.1f %%, error median %.1f cm / %.2f deg,"
      " p90 %.1f cm / %.2f deg; > 2 m: %zu (%zu labelled outliers)\n",
      kind, cs.size(), outliers, 100.0 * static_cast<double>(outliers) / n, te.size(),
      te.empty() ? 0.0 : 100.0 * static_cast<double>(good_inliers) / static_cast<double>(te.size()),
      100 * quantile(te, 0.5), quantile(re, 0.5), 100 * quantile(te, 0.9), quantile(re, 0.9), gross, gross_outliers);
  std::printf(
      "       good-closure median error by pose distance: <5 m %.1f cm (%zu), 5-10 m %.1f cm (%zu), 10-20 m %.1f cm "
      "(%zu), >20 m %.1f cm (%zu)\n",
      100 * quantile(by_bin[0], 0.5), by_bin[0].size(), 100 * quantile(by_bin[1], 0.5), by_bin[1].size(),
      100 * quantile(by_bin[2], 0.5), by_bin[2].size(), 100 * quantile(by_bin[3], 0.5), by_bin[3].size());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::optional<dataset::NoiseModels> relabel;
  std::string relabel_file;
  double good_t = 0.5, good_r = 0.05;
  cosmo::CommandLine app("bench_closure_errors",
                         "How a dataset's loop closures compare with its ground truth, and how its outlier labels "
                         "treat them, per kind (LC, IRLC).");
  app.add_option("FILE.jrl", files, "datasets with ground truth")->required();
  app.add_option("--relabel", relabel_file,
                 "label with this noise-model file (fidelity rule) instead of the file's own labels")
      ->type_name("NOISE.yaml");
  cosmo::addClosureThresholds(app, "good", good_t, good_r);
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  try {
    if (!relabel_file.empty()) relabel = dataset::NoiseModels::load(relabel_file);
    for (const auto& file : files) {
      const jrl::Dataset d = jrl::readJrl(file);
      if (!d.groundtruth) throw std::runtime_error(file + ": no groundtruth");
      std::vector<Closure> intra, inter;
      for (const char r : d.robots) {
        const auto it = d.measurements.find(r);
        if (it == d.measurements.end()) continue;
        const auto& gt = d.groundtruth->at(r);
        const std::set<jrl::FactorId>* labels = nullptr;
        if (d.outliers && d.outliers->count(r)) labels = &d.outliers->at(r);
        for (std::size_t e = 0; e < it->second.size(); ++e)
          for (std::size_t m = 0; m < it->second[e].factors.size(); ++m) {
            const jrl::Factor& f = it->second[e].factors[m];
            if (!f.isBetweenPose3() || f.keys.size() != 2) continue;
            const jrl::Key k1 = f.keys[0], k2 = f.keys[1];
            const bool same = jrl::robotOf(k1) == jrl::robotOf(k2);
            if (same && jrl::indexOf(k2) == jrl::indexOf(k1) + 1) continue;  // odometry
            const Pose3 truth = jrl::pose3At(gt, k1).inverse(Eigen::Isometry) * jrl::pose3At(gt, k2);
            const Pose3 meas = f.pose3();
            const Pose3 err = meas.inverse(Eigen::Isometry) * truth;
            Closure c;
            c.translation_error = err.translation().norm();
            c.rotation_error = rotationAngle(err);
            c.distance = truth.translation().norm();
            c.outlier = relabel ? dataset::isOutlier(meas, truth, relabel->loop_closure)
                                : (labels && labels->count(jrl::FactorId{e, m}));
            (same ? intra : inter).push_back(c);
          }
      }
      std::printf("%s%s\n", file.c_str(), relabel ? (" (labels from " + relabel->source + ")").c_str() : "");
      report("LC", intra, good_t, good_r);
      report("IRLC", inter, good_t, good_r);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_closure_errors: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
