#pragma once
// The paths a robot may follow through the synthetic world: junctions joined by streets and footpaths.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace cosmo::sim {

struct PathNetwork {
  struct Edge {
    int a = 0, b = 0;
    bool street = true;  ///< street (vehicles and people) or footpath (people and small ATVs)
  };
  std::vector<Eigen::Vector2d> nodes;
  std::vector<Edge> edges;
  /// Per node: (neighbour node, edge index).
  std::vector<std::vector<std::pair<int, int>>> adjacency;

  int addNode(const Eigen::Vector2d& p);
  int addEdge(int a, int b, bool street);
  double edgeLength(int e) const { return (nodes[edges[e].a] - nodes[edges[e].b]).norm(); }
  double totalLength() const;
};

}  // namespace cosmo::sim
