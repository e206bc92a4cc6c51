#pragma once
// Pairwise-consistency graph of correspondences: vertices are correspondences (s_i, t_i); an edge joins i and
// j when the distance between their source points matches the distance between their target points,
// | |s_i - s_j| - |t_i - t_j| | <= tolerance (a rigid motion preserves lengths). Inliers form a clique.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cosmo::registration {

/// Undirected simple graph with sorted adjacency lists and an adjacency bit matrix (n^2 bits: for n = 5000,
/// 3 MB) for O(1) edge tests.
class ConsistencyGraph {
 public:
  ConsistencyGraph() = default;
  explicit ConsistencyGraph(int n);
  /// Graph from an explicit edge list (tests, small graphs).
  static ConsistencyGraph fromEdges(int n, const std::vector<std::pair<int, int>>& edges);
  /// The pairwise length-consistency graph of corresponding point sets (same size).
  static ConsistencyGraph fromCorrespondences(const std::vector<Eigen::Vector3f>& source,
                                              const std::vector<Eigen::Vector3f>& target, double tolerance);

  /// The subgraph induced by `vertices` (vertex k of the result is vertices[k]).
  ConsistencyGraph induced(const std::vector<int>& vertices) const;

  int size() const { return n_; }
  std::size_t edgeCount() const { return edges_; }
  bool adjacent(int a, int b) const {
    return (bits_[static_cast<std::size_t>(a) * words_ + (b >> 6)] >> (b & 63)) & 1u;
  }
  const std::vector<int>& neighbors(int v) const { return adj_[v]; }
  int degree(int v) const { return static_cast<int>(adj_[v].size()); }

 private:
  void addEdgeBits(int a, int b);
  void finalize();  // builds adjacency lists from the bits

  int n_ = 0;
  std::size_t words_ = 0;
  std::size_t edges_ = 0;
  std::vector<std::uint64_t> bits_;
  std::vector<std::vector<int>> adj_;
};

}  // namespace cosmo::registration
