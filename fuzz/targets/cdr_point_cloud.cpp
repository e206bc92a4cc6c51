// A ROS 2 CDR sensor_msgs/msg/PointCloud2 (what a ROS 2 bag stores) parsed and decoded into a Scan, with either
// stamp convention (trials::decodeCdrPointCloud2 -> trials::decodeCloud).
#include "../fuzz_target.hpp"
#include "cosmo/trials/cdr_point_cloud.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(cdr_point_cloud) {
  Scan scan;
  trials::decodeCdrPointCloud2(data, size, true, "input", scan);
  trials::decodeCdrPointCloud2(data, size, false, "input", scan);
}
