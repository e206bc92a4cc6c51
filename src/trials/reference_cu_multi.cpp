// CU-Multi ground truth: `#` lines, an optional `timestamp,x,...` header, then timestamp,x,y,z,qx,qy,qz,qw.
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cosmo/common/file_stamp.hpp"
#include "cosmo/trials/reference_file.hpp"

namespace cosmo::trials {

Trajectory readCuMultiGroundTruth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the reference file");
  std::vector<StampedPose> poses;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    if (poses.empty() && line.rfind("timestamp", 0) == 0) continue;  // header
    std::vector<double> v;
    std::stringstream ss(line);
    std::string tok;
    try {
      while (std::getline(ss, tok, ',')) {
        std::size_t used = 0;
        v.push_back(std::stod(tok, &used));
        if (tok.find_first_not_of(" \t", used) != std::string::npos) throw std::invalid_argument(tok);
      }
    } catch (const std::exception&) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": '" + tok + "' is not a number");
    }
    if (v.size() != 8)
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": expected 8 columns (timestamp, x, y, z, qx, qy, qz, qw), got " +
                               std::to_string(v.size()));
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": quaternion is not unit (norm " +
                               std::to_string(q.norm()) + ")");
    const std::string where = path + ":" + std::to_string(n);
    StampNs stamp = fileStamp(v[0] > 1e12 ? v[0] * 1e-9 : v[0], where);  // checks the range
    if (v[0] > 1e12) stamp = static_cast<StampNs>(std::llround(v[0]));      // nanoseconds as written
    poses.push_back({stamp, makePose({v[1], v[2], v[3]}, q.normalized())});
  }
  if (poses.empty()) throw std::runtime_error(path + ": no poses");
  return Trajectory(std::move(poses));
}

}  // namespace cosmo::trials
