#include "cosmo/common/pose_io.hpp"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "cosmo/common/file_stamp.hpp"

namespace cosmo {

namespace {
std::vector<double> numbersOf(std::string line) {
  for (char& c : line)
    if (c == ',' || c == ':') c = ' ';
  std::istringstream ss(line);
  std::vector<double> v;
  std::string tok;
  while (ss >> tok) {
    try {
      std::size_t used = 0;
      const double d = std::stod(tok, &used);
      if (used != tok.size()) return {};
      v.push_back(d);
    } catch (const std::exception&) {
      return {};  // not a numeric line (header, label)
    }
  }
  return v;
}

std::ifstream openOrThrow(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  return in;
}
}  // namespace

Pose3 parsePoseNumbers(const std::vector<double>& v, const std::string& where) {
  Pose3 T = Pose3::Identity();
  if (v.size() == 7) return makePose({v[0], v[1], v[2]}, Eigen::Quaterniond(v[6], v[3], v[4], v[5]));
  if (v.size() != 12 && v.size() != 16)
    throw std::runtime_error(where + ": expected 7, 12 or 16 numbers, got " + std::to_string(v.size()));
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = v[r * 4 + c];
  T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[3], v[7], v[11]);
  return T;
}

std::vector<Pose3> readKittiPoses(const std::string& path) {
  auto in = openOrThrow(path);
  std::vector<Pose3> poses;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto v = numbersOf(line);
    if (v.size() != 12)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected 12 numbers (KITTI pose), got " +
                               std::to_string(v.size()));
    poses.push_back(parsePoseNumbers(v, path + ":" + std::to_string(n)));
  }
  return poses;
}

void writeKittiPoses(const std::string& path, const std::vector<Pose3>& poses) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << std::setprecision(9) << std::scientific;
  for (const auto& T : poses) {
    const auto M = T.matrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) out << M(r, c) << ((r == 2 && c == 3) ? '\n' : ' ');
  }
}

void writeTumTrajectory(const std::string& path, const Trajectory& trajectory) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << std::fixed;
  for (const auto& p : trajectory.poses()) {
    const Eigen::Quaterniond q(p.pose.linear());
    const auto& t = p.pose.translation();
    out << std::setprecision(9) << toSeconds(p.stamp) << ' ' << std::setprecision(6) << t.x() << ' ' << t.y() << ' '
        << t.z() << ' ' << std::setprecision(9) << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
}

Trajectory readTumTrajectory(const std::string& path) {
  auto in = openOrThrow(path);
  std::vector<StampedPose> poses;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    const auto v = numbersOf(line);
    if (v.size() != 8)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected 8 numbers (t x y z qx qy qz qw)");
    poses.push_back({fileStamp(v[0], path + ":" + std::to_string(n)),
                     makePose({v[1], v[2], v[3]}, Eigen::Quaterniond(v[7], v[4], v[5], v[6]))});
  }
  return Trajectory(std::move(poses));
}

Trajectory readMcdPoseCsv(const std::string& path) {
  auto in = openOrThrow(path);
  std::vector<StampedPose> poses;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto v = numbersOf(line);
    if (v.empty() && n == 1) continue;  // header
    if (v.size() != 9)
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": expected 9 columns (num, sec, x, y, z, qx, qy, qz, qw), got " +
                               std::to_string(v.size()));
    const Eigen::Quaterniond q(v[8], v[5], v[6], v[7]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": quaternion is not unit (norm " +
                               std::to_string(q.norm()) + ")");
    poses.push_back({fileStamp(v[1], path + ":" + std::to_string(n)), makePose({v[2], v[3], v[4]}, q)});
  }
  if (poses.empty()) throw std::runtime_error(path + ": no poses");
  return Trajectory(std::move(poses));
}

void writeMcdPoseCsv(const std::string& path, const Trajectory& trajectory) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "num,sec,x,y,z,qx,qy,qz,qw\n";
  std::size_t n = 0;
  char buf[256];
  for (const auto& p : trajectory.poses()) {
    const Eigen::Quaterniond q(p.pose.linear());
    const auto& t = p.pose.translation();
    std::snprintf(buf, sizeof(buf), "%zu,%llu.%09llu,%.6f,%.6f,%.6f,%.9f,%.9f,%.9f,%.9f\n", n++,
                  static_cast<unsigned long long>(p.stamp / 1000000000ULL),
                  static_cast<unsigned long long>(p.stamp % 1000000000ULL), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(),
                  q.w());
    out << buf;
  }
}

Pose3 readKittiCalibTr(const std::string& path) {
  auto in = openOrThrow(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("Tr:", 0) == 0) return parsePoseNumbers(numbersOf(line.substr(3)), path + " Tr");
  }
  throw std::runtime_error(path + ": no 'Tr:' line");
}

std::vector<Pose3> kittiPosesToLidar(const std::vector<Pose3>& cam_poses, const Pose3& Tr) {
  std::vector<Pose3> out;
  out.reserve(cam_poses.size());
  for (const auto& P : cam_poses) out.push_back(Tr.inverse() * P * Tr);
  return out;
}

Pose3 readMatrixPose(const std::string& path) {
  auto in = openOrThrow(path);
  std::vector<double> all;
  std::string line;
  while (std::getline(in, line)) {
    const auto v = numbersOf(line);
    all.insert(all.end(), v.begin(), v.end());
  }
  return parsePoseNumbers(all, path);
}

}  // namespace cosmo
