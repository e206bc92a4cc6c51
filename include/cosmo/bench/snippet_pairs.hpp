#pragma once
// The real registration pairs of ../shared/data/scan_snippets with their known answers, for the benchmarks and
// tests that score registration on real scans (this is evaluation data, so it lives with them, not in the
// registration library).
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/registration/pair_evaluation.hpp"

namespace cosmo::bench {

namespace snippet_detail {
inline std::string need(const std::filesystem::path& p) {
  namespace fs = std::filesystem;
  if (!fs::exists(p)) throw std::runtime_error(p.string() + ": missing scan snippet file");
  return p.string();
}
}  // namespace snippet_detail

/// KITTI 00 0-1, 0-2, 94-95, 198-199, 0-20, 20-40, the hdl32 pair, and consecutive MulRan KAIST03 keyframes
/// 0..20 when `all_mulran` (else 0-1 and 5-6), for the snippets folder `root`. Missing files throw naming the file.
inline std::vector<registration::ScanPair> snippetPairs(const std::string& root_str, bool all_mulran = true) {
  using snippet_detail::need;
  namespace fs = std::filesystem;
  const fs::path root(root_str);
  std::vector<registration::ScanPair> pairs;
  // KITTI 00: LiDAR poses from the camera ground truth and Tr.
  {
    const fs::path k = root / "kitti00";
    const auto lidar =
        kittiPosesToLidar(readKittiPoses(need(k / "poses.txt")), readKittiCalibTr(need(k / "calib.txt")));
    auto bin = [&](int i) {
      std::ostringstream s;
      s << std::setw(6) << std::setfill('0') << i << ".bin";
      return need(k / "velodyne" / s.str());
    };
    const int kitti[][2] = {{0, 1}, {0, 2}, {94, 95}, {198, 199}, {0, 20}, {20, 40}};
    for (const auto& ij : kitti) {
      registration::ScanPair p;
      p.name = "kitti00_" + std::to_string(ij[0]) + "-" + std::to_string(ij[1]);
      // source = the later frame j, target = frame i: T_target_source = T_i^-1 T_j.
      p.source = bin(ij[1]);
      p.target = bin(ij[0]);
      p.T_target_source =
          lidar.at(static_cast<std::size_t>(ij[0])).inverse() * lidar.at(static_cast<std::size_t>(ij[1]));
      pairs.push_back(p);
    }
  }
  {
    const fs::path h = root / "hdl32_pair";
    registration::ScanPair p;
    p.name = "hdl32";
    p.source = need(h / "251371071.pcd");
    p.target = need(h / "251370668.pcd");
    p.T_target_source = readMatrixPose(need(h / "relative.txt"));
    pairs.push_back(p);
  }
  {
    const fs::path m = root / "mulran_kaist03_keyframes";
    const auto poses = readKittiPoses(need(m / "optimized_poses.txt"));
    auto pcd = [&](int i) {
      std::ostringstream s;
      s << std::setw(6) << std::setfill('0') << i << ".pcd";
      return need(m / "Scans" / s.str());
    };
    std::vector<int> starts;
    if (all_mulran)
      for (int i = 0; i < 20; ++i) starts.push_back(i);
    else
      starts = {0, 5};
    for (const int i : starts) {
      registration::ScanPair p;
      p.name = "kaist03_" + std::to_string(i) + "-" + std::to_string(i + 1);
      p.source = pcd(i + 1);
      p.target = pcd(i);
      p.T_target_source = poses.at(static_cast<std::size_t>(i)).inverse() * poses.at(static_cast<std::size_t>(i + 1));
      pairs.push_back(p);
    }
  }
  for (auto& p : pairs) p.distance_m = p.T_target_source.translation().norm();
  return pairs;
}

}  // namespace cosmo::bench
