// A serialized ROS 1 sensor_msgs/PointCloud2 (what a ROS 1 bag stores) parsed and decoded into a Scan, with either
// stamp convention (trials::decodeRos1PointCloud2 -> trials::decodeCloud).
#include "../fuzz_target.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(ros1_point_cloud) {
  Scan scan;
  trials::CloudLayout layout;
  trials::decodeRos1PointCloud2(data, size, true, "input", scan, layout);
  trials::decodeRos1PointCloud2(data, size, false, "input", scan, layout);
}
