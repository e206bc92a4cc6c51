#pragma once
// Routes over the path network: a coverage-seeking random walk (no U-turns, unvisited edges preferred),
// then the shortest way back to the start (a guaranteed revisit, often along streets already driven, in
// either direction), then more random walk until the requested length.
#include <cstdint>
#include <random>
#include <vector>

#include "cosmo/sim/path_network.hpp"

namespace cosmo::sim {

struct RouteParams {
  double length = 600.0;         ///< m along the network
  int start_node = -1;           ///< -1: random
  bool streets_only = false;     ///< cars stay on streets
  double return_fraction = 0.5;  ///< fraction of the length after which the route heads back to its start
};

/// Node sequence of the route (consecutive nodes are joined by an edge). Throws on an empty network.
std::vector<int> planRoute(const PathNetwork& network, const RouteParams& params, std::mt19937_64& rng);

}  // namespace cosmo::sim
