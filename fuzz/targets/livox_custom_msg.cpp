// A serialized Livox livox_ros_driver/CustomMsg (what FAST-LIO users record in ROS 1 bags) parsed and decoded into
// a Scan, with either stamp convention (trials::decodeRos1Cloud -> trials::parseLivoxCustomMsg ->
// trials::decodeCloud).
#include "../fuzz_target.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(livox_custom_msg) {
  Scan scan;
  trials::CloudLayout layout;
  trials::decodeRos1Cloud(trials::Ros1CloudType::LivoxCustomMsg, data, size, true, "input", scan, layout);
  trials::decodeRos1Cloud(trials::Ros1CloudType::LivoxCustomMsg, data, size, false, "input", scan, layout);
}
