#pragma once
// Routes over the path network. Either a coverage-seeking random walk (no U-turns, unvisited edges
// preferred), then the shortest way back to the start (a guaranteed revisit, often along streets already
// driven, in either direction), then more random walk until the requested length; or, when waypoints are
// given, the shortest paths through those junctions in order (laps around a shared area, planned meetings).
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
  /// Junctions to pass in order, joined by shortest paths (from start_node when >= 0, else from the first
  /// waypoint). Non-empty: length and return_fraction are not used and no randomness is drawn.
  std::vector<int> waypoints;
};

/// Node sequence of the route (consecutive nodes are joined by an edge). Throws on an empty network, and on
/// a waypoint that is not a junction or cannot be reached (e.g. streets_only and only footpaths lead there).
std::vector<int> planRoute(const PathNetwork& network, const RouteParams& params, std::mt19937_64& rng);

/// Shortest path from `from` to `to` as a node sequence (both included); empty when `to` is unreachable.
std::vector<int> shortestPath(const PathNetwork& network, int from, int to, bool streets_only);

}  // namespace cosmo::sim
