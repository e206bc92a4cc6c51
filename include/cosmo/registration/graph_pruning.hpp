#pragma once
// Graph-theoretic outlier pruning over the consistency graph (written here; no Debian package offers it):
// k-core decomposition (Batagelj & Zaversnik, O(E)), the maximum k-core, and an exact maximum clique by
// branch and bound with greedy-colouring bounds (Tomita-style) restricted to the vertices whose core number
// can still beat the incumbent (as in Rossi's PMC used by TEASER++/KISS-Matcher).
#include <cstdint>
#include <vector>

#include "cosmo/registration/consistency_graph.hpp"

namespace cosmo::registration {

/// Core number of every vertex.
std::vector<int> coreNumbers(const ConsistencyGraph& graph);

/// Vertices of the maximum k-core (k = max core number), sorted ascending; empty for an edgeless graph.
std::vector<int> maxKCore(const ConsistencyGraph& graph);

struct CliqueResult {
  std::vector<int> vertices;      ///< sorted ascending
  bool proven_maximum = true;     ///< false when the node budget ran out (the best clique found is returned)
  std::uint64_t nodes = 0;        ///< branch-and-bound nodes expanded
  std::size_t max_core_size = 0;  ///< vertices of the maximum k-core (= maxKCore(graph).size(), found on the way)
};

/// Maximum clique (ties broken deterministically). `node_budget` bounds the search; 0 = unlimited.
CliqueResult maxClique(const ConsistencyGraph& graph, std::uint64_t node_budget = 0);

}  // namespace cosmo::registration
