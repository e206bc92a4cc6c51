#include "cosmo/trials/mcd_layout.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace cosmo::trials {

namespace {
Pose3 fromRows(const double (&m)[12]) {
  Pose3 T = Pose3::Identity();
  Eigen::Matrix3d R;
  R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
  T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(m[3], m[7], m[11]);
  return T;
}
}  // namespace

Pose3 mcdHandheldExtrinsic() {
  static const double m[12] = {0.9999135040741837,   -0.011166365511073898, -0.006949579221822984,
                               -0.04894521120494695, -0.011356389542502144, -0.9995453006865824,
                               -0.02793249526856565, -0.03126929060348084,  -0.006634514801117132,
                               0.02800900135032654,  -0.999585653686922,    -0.01755515794222565};
  return fromRows(m);
}

Pose3 mcdAtvExtrinsic() {
  static const double m[12] = {0.9999346552051229,    0.003477624535771754,  -0.010889970036688295,
                               -0.060649229060416594, 0.003587143302461965,  -0.9999430279821171,
                               0.010053516443599904,  -0.012837544242408117, -0.010854387257665576,
                               -0.01009192338171122,  -0.999890161647627,    -0.020492606896077407};
  return fromRows(m);
}

OusterSweep mcdSweep(int beams, int columns, double rate_hz) {
  return OusterSweep{beams, columns, rate_hz, /*stamp_at_end=*/true, /*ring_uint16=*/false};
}

void writeMcdPoseCsv(const std::string& path, const std::vector<StampedPose>& body, int first_num) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "num,t,x,y,z,qx,qy,qz,qw\n";
  char buf[256];
  int num = first_num;
  for (const auto& p : body) {
    const Eigen::Quaterniond q(p.pose.linear());
    const auto& t = p.pose.translation();
    std::snprintf(buf, sizeof buf, "%d,%llu.%09llu,%.9f,%.9f,%.9f,%.12f,%.12f,%.12f,%.12f\n", num++,
                  static_cast<unsigned long long>(p.stamp / 1000000000ULL),
                  static_cast<unsigned long long>(p.stamp % 1000000000ULL), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(),
                  q.w());
    out << buf;
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

void writeMcdCalibration(const std::string& path, const Pose3& T_body_lidar) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  const Eigen::Matrix4d M = T_body_lidar.matrix();
  char buf[512];
  out << "body:\n  os_sensor:\n    T:\n";
  for (int r = 0; r < 4; ++r) {
    std::snprintf(buf, sizeof buf, "      - [%.17g, %.17g, %.17g, %.17g]\n", M(r, 0), M(r, 1), M(r, 2), M(r, 3));
    out << buf;
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace cosmo::trials
