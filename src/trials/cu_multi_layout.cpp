#include "cosmo/trials/cu_multi_layout.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "cosmo/trials/cdr_point_cloud.hpp"

namespace cosmo::trials {

std::string cuMultiTopic(int robot_number) { return "robot" + std::to_string(robot_number) + "/ouster/points"; }

Pose3 cuMultiImuTLidar() { return makePose({-0.058038, 0.015573, 0.049603}, Eigen::Quaterniond(0.0, 0.0, 0.0, 1.0)); }

OusterSweep cuMultiSweep(int beams, int columns, double rate_hz) {
  return OusterSweep{beams, columns, rate_hz, /*stamp_at_end=*/false, /*ring_uint16=*/true};
}

void writeCuMultiGroundTruth(const std::string& path, const std::vector<StampedPose>& body) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "# ground truth (UTM)\n# timestamp,x,y,z,qx,qy,qz,qw\n";
  char buf[256];
  for (const auto& p : body) {
    const Eigen::Quaterniond q(p.pose.linear());
    const auto& t = p.pose.translation();
    std::snprintf(buf, sizeof buf, "%llu.%09llu,%.9f,%.9f,%.9f,%.12f,%.12f,%.12f,%.12f\n",
                  static_cast<unsigned long long>(p.stamp / 1000000000ULL),
                  static_cast<unsigned long long>(p.stamp % 1000000000ULL), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(),
                  q.w());
    out << buf;
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

CuMultiBagWriter::CuMultiBagWriter(const std::string& folder, int robot_number)
    : bag_(folder), topic_(bag_.addTopic(cuMultiTopic(robot_number), "sensor_msgs/msg/PointCloud2")) {}

void CuMultiBagWriter::write(const RawCloud& cloud) {
  bag_.write(topic_, cloud.layout.stamp, encodeCdrPointCloud2(cloud));
}

}  // namespace cosmo::trials
