#pragma once
// Assembling one team graph from LAMP pose-graph messages (or g2o graphs): nodes and edges are merged over
// every message of every robot (incremental messages, full re-publications and repeated nodes alike; the first
// copy of a node or edge wins), then sorted into what a JRL needs:
// - robots: every character that has an ODOM edge between two of its own poses; its poses are the keys
//   Symbol(c, 0..n-1), chained by ODOM edges c(i-1) -> c(i), each with a node (whose header stamp is the pose's);
// - loop closures: LOOPCLOSE and INTERROB_BETW edges between two robot poses;
// - everything else is counted: PRIOR, IMU, ARTIFACT, UWB and INTERROB_RANGE edges per type, nodes of other
//   characters (artifacts, UWB anchors, the base station) per character.
// Problems that leave the result usable are counted warnings with examples (unknown edge types, a loop closure
// touching a key without a node, a node re-published with another stamp, ...); problems that do not (a broken
// odometry chain, decreasing stamps along a chain, two robot names for one character) throw GraphError.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/covariance_order.hpp"
#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/nebula/pose_graph_msg.hpp"

namespace cosmo::nebula {

class GraphError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A relative-pose measurement T_key1^-1 * T_key2 as the source graph holds it (keys unchanged).
struct Between {
  jrl::Key key1 = 0, key2 = 0;
  std::int32_t type = kOdom;
  Pose3 measurement = Pose3::Identity();
  Matrix6 covariance = Matrix6::Identity();  ///< recorded, rotation first
  std::string source;                        ///< where it was first read
  bool typed = true;                         ///< false for g2o edges (their type is inferred)
};

struct RobotGraph {
  char character = 'a';
  std::string name;               ///< the topic namespace that carries its odometry ("husky3"); empty if none
  std::vector<StampNs> stamps;    ///< stamps[i] of pose Symbol(character, i)
  std::vector<Between> odometry;  ///< odometry[i - 1] links pose i - 1 to pose i
};

/// Counted problems: per kind, how many and the first few places.
struct Warnings {
  std::map<std::string, std::size_t> counts;
  std::map<std::string, std::vector<std::string>> examples;  ///< up to 3 per kind
  void add(const std::string& kind, const std::string& example);
  std::size_t total() const;
  /// One line per kind: "  <count> <kind>, e.g. <example>".
  std::string str() const;
};

struct NebulaGraph {
  std::map<char, RobotGraph> robots;
  std::vector<Between> loop_closures;                ///< sorted by (key1, key2, type)
  std::map<std::string, std::size_t> ignored_edges;  ///< per type name
  std::map<char, std::size_t> other_nodes;           ///< nodes whose character is no robot's
  Warnings warnings;
  std::size_t messages = 0, nodes_read = 0, edges_read = 0, repeated_nodes = 0, repeated_edges = 0;
};

class GraphBuilder {
 public:
  /// One PoseGraph message of topic namespace `robot_name` ("" when the topic names no robot), read from
  /// `source` (e.g. "rosbag/husky3.bag /husky3/lamp/pose_graph_incremental #12").
  void addMessage(const PoseGraph& msg, const std::string& robot_name, const std::string& source,
                  CovarianceOrder order = CovarianceOrder::TranslationFirst);
  /// A g2o graph (no types, no stamps): an edge between consecutive poses of one character is ODOM, any other
  /// edge LOOPCLOSE (or, when it touches a key that is no robot's pose, an ignored "g2o edge to another key");
  /// a vertex Symbol(c, i) is stamped i seconds (g2o files carry no time).
  void addG2o(const G2oGraph& graph, const std::string& source);

  /// The merged graph (see the file comment). Throws GraphError naming robot, keys and sources.
  NebulaGraph build() const;

 private:
  struct Node {
    StampNs stamp = 0;
    std::string source;
  };
  struct Edge {
    std::optional<Between> between;  ///< ODOM / loop closures with a valid pose; empty for ignored types
    std::string source;
  };
  void addNode(jrl::Key key, StampNs stamp, const std::string& source);
  void addEdge(const PoseGraphEdge& edge, const std::string& source, CovarianceOrder order);
  void addBetween(Between between);
  /// build()'s steps. Per robot: index i -> its odometry link (i-1 -> i).
  using OdometryLinks = std::map<std::uint64_t, const Between*>;
  /// Robots: characters with odometry between their own consecutive poses, and those links.
  std::map<char, OdometryLinks> odometryLinks(Warnings& warnings) const;
  /// Names: the topic namespace whose odometry is that one robot's.
  std::map<char, std::string> robotNames(Warnings& warnings) const;
  /// Robot c's chain 0..n-1: every pose has a node and a link from its predecessor.
  RobotGraph chainRobot(char c, const OdometryLinks& links, const std::map<char, std::string>& names,
                        Warnings& warnings) const;
  /// Loop closures between two chained robot poses; every other edge and node counted.
  void collectLoopClosures(NebulaGraph& g) const;

  std::map<jrl::Key, Node> nodes_;
  std::map<std::tuple<jrl::Key, jrl::Key, std::int32_t>, Edge> edges_;
  std::map<std::string, std::set<char>> odometry_characters_;  ///< per robot name: characters of its ODOM edges
  std::map<std::string, std::string> name_sources_;            ///< per robot name: where it was first read
  Warnings warnings_;
  std::size_t messages_ = 0, nodes_read_ = 0, edges_read_ = 0, repeated_nodes_ = 0, repeated_edges_ = 0;
};

}  // namespace cosmo::nebula
