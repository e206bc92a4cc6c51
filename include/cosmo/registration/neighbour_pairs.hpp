#pragma once
// Every unordered pair of points closer than a radius, each pair once, found on a hash grid whose cells are
// one radius wide (a point's neighbours lie in its own cell and the 26 around it; each cell is paired with
// itself and its 13 "forward" neighbours, so no pair is tested twice). A flat list, so that per-pair work
// (normal moments, pair features, FPFH sums) runs as plain loops over it.
// The order is a function of the input only: deterministic.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cosmo::registration {

struct NeighbourPair {
  std::uint32_t first;     ///< index of one point of the pair (input order)
  std::uint32_t second;    ///< index of the other point
  float squared_distance;  ///< |p_first - p_second|^2
  /// Left uninitialised (the search sizes its output generously before filling it: no zeroing pass).
  NeighbourPair() {}
  NeighbourPair(std::uint32_t a, std::uint32_t b, float d2) : first(a), second(b), squared_distance(d2) {}
};
using NeighbourPairs = std::vector<NeighbourPair>;

/// Pairs {i, j}, i != j, with |p_i - p_j|^2 < radius^2 (float, computed as ((dx^2 + dy^2) + dz^2)).
NeighbourPairs findNeighbourPairs(const std::vector<Eigen::Vector3f>& points, float radius);

/// The same pairs in the same order, but numbered by position in the grid's cell-sorted order: order[s] is the
/// input index of position s (points that are not finite or beyond the grid's range have no position). Per-point
/// work indexed by position touches memory locally (a cell's points are contiguous).
NeighbourPairs findNeighbourPairs(const std::vector<Eigen::Vector3f>& points, float radius,
                                  std::vector<std::uint32_t>& order);

}  // namespace cosmo::registration
