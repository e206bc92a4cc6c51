#pragma once
// g2o files of a Nebula dataset: `ground_truth/result.g2o` (the reference solution) and the graphs in
// `g2o_pcd/`, as gtsam::writeG2o writes them: "VERTEX_SE3:QUAT key x y z qx qy qz qw" and
// "EDGE_SE3:QUAT key1 key2 x y z qx qy qz qw" + the 21 upper-triangle entries of the information matrix in
// g2o's translation-first order. Keys are gtsam keys (Symbol(robot, index) as an unsigned integer). Other tags
// are skipped and counted.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"

namespace cosmo::nebula {

struct G2oEdge {
  std::uint64_t key1 = 0, key2 = 0;
  Pose3 measurement = Pose3::Identity();     ///< T_key1^-1 * T_key2
  Matrix6 covariance = Matrix6::Identity();  ///< rotation first (the inverse information, blocks swapped)
  std::size_t line = 0;
};

struct G2oGraph {
  std::map<std::uint64_t, Pose3> vertices;
  std::vector<G2oEdge> edges;
  std::map<std::string, std::size_t> skipped;  ///< other tags and their line counts
};

/// Parse g2o text; `source` names it in errors: "<source>:<line>: <problem>" (a missing or non-numeric
/// field, a non-unit quaternion, a duplicate vertex, an information matrix that is not positive definite).
G2oGraph parseG2o(std::istream& in, const std::string& source);
/// Read a g2o file; throws std::runtime_error naming the path when it cannot be opened.
G2oGraph readG2o(const std::string& path);

/// g2o text of vertices (and edges), as gtsam::writeG2o lays it out (17 significant digits).
std::string g2oText(const std::map<std::uint64_t, Pose3>& vertices, const std::vector<G2oEdge>& edges = {});

}  // namespace cosmo::nebula
