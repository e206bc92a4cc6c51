#pragma once
// The three LAMP 2.0 messages a Nebula dataset's bags carry on /<robot>/lamp/pose_graph_incremental
// (pose_graph_msgs/PoseGraph, PoseGraphNode, PoseGraphEdge; ../shared/docs/real_data_formats.md §4), as plain
// data: cosmo decodes them itself (nebula/ros1_serialization.hpp), so pose_graph_msgs need not be installed.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::nebula {

/// PoseGraphEdge.type values (the message's constants).
enum EdgeType : std::int32_t {
  kOdom = 0,
  kPrior = 1,
  kImu = 2,
  kLoopClose = 3,
  kArtifact = 4,
  kUwbRange = 5,
  kUwbBetween = 6,
  kInterRobotRange = 7,
  kInterRobotBetween = 8,
};
/// "ODOM", "PRIOR", ..., "INTERROB_BETW"; "unknown type N" otherwise.
std::string edgeTypeName(std::int32_t type);

/// std_msgs/Header.
struct Header {
  std::uint32_t seq = 0;
  std::uint32_t sec = 0;
  std::uint32_t nsec = 0;
  std::string frame_id;
  StampNs stampNs() const { return StampNs{sec} * 1'000'000'000ull + nsec; }
};

/// geometry_msgs/Pose: position (x, y, z) and orientation (x, y, z, w) as in the message.
struct PoseMsg {
  std::array<double, 3> position{0.0, 0.0, 0.0};
  std::array<double, 4> orientation{0.0, 0.0, 0.0, 1.0};

  /// The pose (quaternion normalised); throws std::invalid_argument on a non-finite number or a quaternion
  /// whose norm is not within 1e-3 of 1.
  Pose3 toPose() const;
  static PoseMsg fromPose(const Pose3& pose);
};

/// pose_graph_msgs/PoseGraphNode. `covariance` row by row in the message's order (x, y, z, rx, ry, rz).
struct PoseGraphNode {
  Header header;
  std::uint64_t key = 0;  ///< gtsam Symbol: robot character in the top byte, index below
  std::string id;         ///< "ID": artifact / UWB identifier
  PoseMsg pose;
  std::array<double, 36> covariance{};
};

/// pose_graph_msgs/PoseGraphEdge. The pose is T_from^-1 * T_to (a gtsam BetweenFactor's measurement).
struct PoseGraphEdge {
  std::uint64_t key_from = 0;
  std::uint64_t key_to = 0;
  std::int32_t type = kOdom;
  PoseMsg pose;
  std::array<double, 36> covariance{};
  double range = 0.0;
  double range_error = 0.0;
};

/// pose_graph_msgs/PoseGraph.
struct PoseGraph {
  Header header;
  bool incremental = true;
  std::vector<PoseGraphNode> nodes;
  std::vector<PoseGraphEdge> edges;
};

}  // namespace cosmo::nebula
