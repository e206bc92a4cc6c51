// bench_features: CPU time of the per-scan feature stages (downsample, neighbour pairs, normals, SPFH, FPFH) and
// of the pairwise stages, on two scan files, repeated; prints the median per stage and the sizes involved.
//   bench_features SOURCE TARGET [--repeats N] [--config registration.yaml]
#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "cosmo/registration/neighbour_pairs.hpp"
#include "cosmo/bench/stage_timer.hpp"
#include "cosmo/common/voxel_grid.hpp"

using namespace cosmo;

int main(int argc, char** argv) {
  int repeats = 5;
  std::string source, target, config;
  cosmo::CommandLine app("bench_features",
                         "CPU time of the per-scan feature stages and of the pairwise stages on two scan files, "
                         "repeated; the median per stage and the sizes involved.");
  app.add_option("SOURCE", source, "the source scan")->required();
  app.add_option("TARGET", target, "the target scan")->required();
  app.add_option("--repeats", repeats, "runs")->capture_default_str();
  cosmo::addModuleConfig(app, config, "registration");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  registration::RegistrationParams params;
  if (!config.empty()) params = registration::RegistrationParams::fromConfig(cosmo::ConfigNode::load(config));
  const Scan src = cosmo::readScanFile(source), tgt = cosmo::readScanFile(target);
  const registration::GlobalRegistration reg(params);
  std::map<std::string, std::vector<double>> ms;
  registration::FeatureCloud fs, ft;
  registration::RegistrationResult r;
  for (int k = 0; k < repeats; ++k) {
    bench::StageTimer timer;
    timer.restart();
    fs = reg.prepare(src, &timer);
    ft = reg.prepare(tgt, &timer);
    r = reg.align(fs, ft, &timer);
    for (const auto& [name, v] : timer.milliseconds()) ms[name].push_back(v);
    ms["TOTAL"].push_back(timer.total());
  }
  const auto down = voxelDownsample(src.points, params.voxel_size, params.min_range, params.max_range);
  const double radius = std::max({params.normal_radius, params.fpfh_radius, params.spfh_radius});
  const registration::NeighbourPairs pairs = registration::findNeighbourPairs(down, static_cast<float>(radius));
  std::printf(
      "source: %zu points -> %zu downsampled -> %zu with normal, %zu keypoints; %zu neighbour pairs "
      "within %.2f m\n",
      src.size(), down.size(), fs.points.size(), fs.keypoints.size(), pairs.size(), radius);
  std::printf("target: %zu points -> %zu with normal, %zu keypoints\n", tgt.size(), ft.points.size(),
              ft.keypoints.size());
  std::printf("correspondences %zu, clique %zu, final %zu, overlap %.3f, %s\n", r.correspondences, r.pruned_inliers,
              r.final_inliers, r.overlap, r.valid ? "accepted" : "rejected");
  std::printf("CPU ms over %d repeats (both clouds' features): median, min\n", repeats);
  auto med = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  auto lowest = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
  for (const char* s : bench::kRegistrationStages)
    if (ms.count(s)) std::printf("  %-11s %7.1f %7.1f\n", s, med(ms[s]), lowest(ms[s]));
  std::printf("  %-11s %7.1f %7.1f\n", "TOTAL", med(ms["TOTAL"]), lowest(ms["TOTAL"]));
  return 0;
}
