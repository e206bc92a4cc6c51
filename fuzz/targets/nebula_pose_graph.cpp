// A Nebula robot's messages (pose_graph_msgs/PoseGraph in ROS 1's serialization, nebula/ros1_serialization.hpp),
// each preceded by its uint32 length as a bag's message data record holds it: decoded, merged into a team graph
// (nebula/graph_builder.hpp) and, when the graph builds, assembled into a JRL against a reference made of its own
// odometry (nebula/jrl_assembly.hpp).
#include <algorithm>
#include <cstring>

#include "../fuzz_target.hpp"
#include "cosmo/nebula/graph_builder.hpp"
#include "cosmo/nebula/jrl_assembly.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(nebula_pose_graph) {
  nebula::GraphBuilder builder;
  for (std::size_t at = 0, k = 0; size - at >= 4; ++k) {
    std::uint32_t n;
    std::memcpy(&n, data + at, 4);
    at += 4;
    n = static_cast<std::uint32_t>(std::min<std::size_t>(n, size - at));
    builder.addMessage(nebula::decodePoseGraph(data + at, n), "husky1", "input #" + std::to_string(k));
    at += n;
  }
  const nebula::NebulaGraph team = builder.build();
  std::map<jrl::Key, Pose3> reference;
  for (const auto& [c, robot] : team.robots) {
    Pose3 pose = Pose3::Identity();
    reference[jrl::symbol(c, 0)] = pose;
    for (std::size_t i = 0; i < robot.odometry.size(); ++i) {
      pose = pose * robot.odometry[i].measurement;
      reference[jrl::symbol(c, i + 1)] = pose;
    }
  }
  nebula::assembleJrl(team, reference, nebula::ConversionParams{});
}
