// KITTI poses (12 numbers per line) with the stamps of `times.txt` beside them.
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "cosmo/common/file_stamp.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/trials/reference_file.hpp"

namespace cosmo::trials {

Trajectory readKittiReference(const std::string& path) {
  const auto poses = readKittiPoses(path);
  const std::string times_path = (std::filesystem::path(path).parent_path() / "times.txt").string();
  std::ifstream in(times_path);
  if (!in)
    throw std::runtime_error(path + ": KITTI poses carry no stamps and " + times_path +
                             " (one stamp in seconds per pose) does not exist");
  std::vector<StampedPose> stamped;
  double t = 0.0;
  while (stamped.size() < poses.size() && in >> t)
    stamped.push_back(
        {fileStamp(t, times_path + ": stamp " + std::to_string(stamped.size() + 1)), poses[stamped.size()]});
  if (stamped.size() != poses.size())
    throw std::runtime_error(times_path + ": " + std::to_string(stamped.size()) + " stamps for " +
                             std::to_string(poses.size()) + " poses in " + path);
  return Trajectory(std::move(stamped));
}

}  // namespace cosmo::trials
