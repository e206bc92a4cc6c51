#include "cosmo/registration/pair_evaluation.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "cosmo/common/pose_io.hpp"

namespace cosmo::registration {

namespace fs = std::filesystem;

PoseError poseError(const Pose3& estimate, const Pose3& expected) {
  const Pose3 d = expected.inverse() * estimate;
  return {d.translation().norm(), rotationAngle(d) * 180.0 / M_PI};
}

Scan rotateScanYaw(const Scan& scan, double yaw_rad) {
  Scan out = scan;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(yaw_rad), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : out.points) p = R * p;
  return out;
}

std::vector<ScanPair> readPairList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open pair list");
  const fs::path dir = fs::path(path).parent_path();
  auto resolve = [&](const std::string& f) { return fs::path(f).is_absolute() ? f : (dir / f).string(); };
  std::vector<ScanPair> pairs;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::vector<std::string> tok;
    for (std::string t; ss >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_no);
    if (tok.size() < 2) throw std::runtime_error(where + ": expected 'source target [expected]'");
    ScanPair p;
    p.source = resolve(tok[0]);
    p.target = resolve(tok[1]);
    p.name = fs::path(tok[0]).stem().string() + "->" + fs::path(tok[1]).stem().string();
    if (tok.size() == 3) {
      p.T_target_source = readMatrixPose(resolve(tok[2]));
    } else if (tok.size() > 3) {
      std::vector<double> v;
      for (std::size_t i = 2; i < tok.size(); ++i) {
        try {
          v.push_back(std::stod(tok[i]));
        } catch (const std::exception&) { throw std::runtime_error(where + ": not a number: '" + tok[i] + "'"); }
      }
      p.T_target_source = parsePoseNumbers(v, where);
    }
    p.distance_m = p.T_target_source.translation().norm();
    pairs.push_back(p);
  }
  return pairs;
}

void writePairList(const std::string& path, const std::vector<ScanPair>& pairs) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write pair list");
  out << "# source target x y z qx qy qz qw  (T_target_source)\n" << std::setprecision(9);
  for (const auto& p : pairs) {
    const Eigen::Quaterniond q(p.T_target_source.linear());
    const Eigen::Vector3d t = p.T_target_source.translation();
    out << p.source << ' ' << p.target << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y()
        << ' ' << q.z() << ' ' << q.w() << "  # " << p.name << '\n';
  }
}

}  // namespace cosmo::registration
