#include "cosmo/sim/path_network.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::sim {

int PathNetwork::addNode(const Eigen::Vector2d& p) {
  nodes.push_back(p);
  adjacency.emplace_back();
  return static_cast<int>(nodes.size()) - 1;
}

int PathNetwork::addEdge(int a, int b, bool street) {
  const int n = static_cast<int>(nodes.size());
  if (a < 0 || b < 0 || a >= n || b >= n || a == b)
    throw std::invalid_argument("PathNetwork::addEdge: bad nodes " + std::to_string(a) + ", " + std::to_string(b));
  edges.push_back({a, b, street});
  const int e = static_cast<int>(edges.size()) - 1;
  adjacency[a].emplace_back(b, e);
  adjacency[b].emplace_back(a, e);
  return e;
}

double PathNetwork::totalLength() const {
  double s = 0.0;
  for (std::size_t e = 0; e < edges.size(); ++e) s += edgeLength(static_cast<int>(e));
  return s;
}

}  // namespace cosmo::sim
