#include "cosmo/registration/graph_pruning.hpp"

#include <algorithm>
#include <numeric>

namespace cosmo::registration {

namespace {

/// Batagelj-Zaversnik bucket core decomposition; also returns the removal (degeneracy) order.
void coreDecomposition(const ConsistencyGraph& g, std::vector<int>& core, std::vector<int>& order) {
  const int n = g.size();
  core.assign(static_cast<std::size_t>(n), 0);
  order.assign(static_cast<std::size_t>(n), 0);
  if (n == 0) return;
  int max_deg = 0;
  for (int v = 0; v < n; ++v) {
    core[v] = g.degree(v);
    max_deg = std::max(max_deg, core[v]);
  }
  std::vector<int> bin(static_cast<std::size_t>(max_deg) + 1, 0), pos(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) ++bin[core[v]];
  int start = 0;
  for (int d = 0; d <= max_deg; ++d) {
    const int num = bin[d];
    bin[d] = start;
    start += num;
  }
  for (int v = 0; v < n; ++v) {
    pos[v] = bin[core[v]];
    order[pos[v]] = v;
    ++bin[core[v]];
  }
  for (int d = max_deg; d > 0; --d) bin[d] = bin[d - 1];
  bin[0] = 0;
  for (int i = 0; i < n; ++i) {
    const int v = order[i];
    for (const int u : g.neighbors(v)) {
      if (core[u] > core[v]) {
        const int du = core[u], pu = pos[u];
        const int pw = bin[du], w = order[pw];
        if (u != w) {
          pos[u] = pw, order[pu] = w;
          pos[w] = pu, order[pw] = u;
        }
        ++bin[du];
        --core[u];
      }
    }
  }
}

/// Bitset branch and bound (BBMC, San Segundo et al.) on a vertex subset re-indexed 0..m-1.
class BitsetCliqueSearch {
 public:
  BitsetCliqueSearch(const ConsistencyGraph& g, const std::vector<int>& vertices, std::uint64_t budget)
      : vertices_(vertices),
        m_(static_cast<int>(vertices.size())),
        words_((vertices.size() + 63) / 64),
        budget_(budget) {
    adj_.assign(static_cast<std::size_t>(m_) * words_, 0u);
    for (int a = 0; a < m_; ++a)
      for (int b = a + 1; b < m_; ++b)
        if (g.adjacent(vertices_[a], vertices_[b])) {
          adj_[a * words_ + (b >> 6)] |= std::uint64_t{1} << (b & 63);
          adj_[b * words_ + (a >> 6)] |= std::uint64_t{1} << (a & 63);
        }
  }

  /// Search for a clique larger than `lower_bound` vertices; returns it in original ids (empty if none).
  std::vector<int> run(std::size_t lower_bound) {
    best_size_ = lower_bound;
    std::vector<std::uint64_t> p(words_, 0u);
    for (int v = 0; v < m_; ++v) p[v >> 6] |= std::uint64_t{1} << (v & 63);
    std::vector<int> clique;
    expand(clique, p);
    std::vector<int> out;
    for (const int v : best_) out.push_back(vertices_[v]);
    return out;
  }
  std::uint64_t nodes() const { return nodes_; }
  bool exhausted() const { return exhausted_; }

 private:
  void expand(std::vector<int>& clique, std::vector<std::uint64_t>& p) {
    if (budget_ && nodes_ >= budget_) {
      exhausted_ = true;
      return;
    }
    ++nodes_;
    // Greedy colouring of P in vertex order: order[i] has colour colors[i], non-decreasing.
    std::vector<int> order, colors;
    std::vector<std::uint64_t> q = p, r(words_);
    int color = 0;
    while (any(q)) {
      ++color;
      r = q;
      while (true) {
        const int v = first(r);
        if (v < 0) break;
        r[v >> 6] &= ~(std::uint64_t{1} << (v & 63));
        q[v >> 6] &= ~(std::uint64_t{1} << (v & 63));
        const std::uint64_t* nv = &adj_[static_cast<std::size_t>(v) * words_];
        for (std::size_t w = 0; w < words_; ++w) r[w] &= ~nv[w];
        order.push_back(v);
        colors.push_back(color);
      }
    }
    std::vector<std::uint64_t> next(words_);
    for (int i = static_cast<int>(order.size()) - 1; i >= 0; --i) {
      if (clique.size() + static_cast<std::size_t>(colors[i]) <= best_size_ || exhausted_) return;
      const int v = order[i];
      clique.push_back(v);
      const std::uint64_t* nv = &adj_[static_cast<std::size_t>(v) * words_];
      for (std::size_t w = 0; w < words_; ++w) next[w] = p[w] & nv[w];
      if (!any(next)) {
        if (clique.size() > best_size_) {
          best_size_ = clique.size();
          best_ = clique;
        }
      } else {
        std::vector<std::uint64_t> sub = next;
        expand(clique, sub);
      }
      clique.pop_back();
      p[v >> 6] &= ~(std::uint64_t{1} << (v & 63));
    }
  }
  bool any(const std::vector<std::uint64_t>& b) const {
    for (const auto w : b)
      if (w) return true;
    return false;
  }
  int first(const std::vector<std::uint64_t>& b) const {
    for (std::size_t w = 0; w < words_; ++w)
      if (b[w]) return static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(b[w])));
    return -1;
  }

  std::vector<int> vertices_;
  int m_;
  std::size_t words_;
  std::uint64_t budget_;
  std::uint64_t nodes_ = 0;
  bool exhausted_ = false;
  std::size_t best_size_ = 0;
  std::vector<int> best_;
  std::vector<std::uint64_t> adj_;
};

}  // namespace

std::vector<int> coreNumbers(const ConsistencyGraph& graph) {
  std::vector<int> core, order;
  coreDecomposition(graph, core, order);
  return core;
}

std::vector<int> maxKCore(const ConsistencyGraph& graph) {
  const std::vector<int> core = coreNumbers(graph);
  std::vector<int> out;
  if (core.empty()) return out;
  const int k = *std::max_element(core.begin(), core.end());
  if (k == 0) return out;
  for (int v = 0; v < graph.size(); ++v)
    if (core[v] == k) out.push_back(v);
  return out;
}

CliqueResult maxClique(const ConsistencyGraph& graph, std::uint64_t node_budget) {
  CliqueResult result;
  const int n = graph.size();
  if (n == 0) return result;
  std::vector<int> core, order;
  coreDecomposition(graph, core, order);
  std::vector<int> best{order.back()};  // any single vertex is a clique
  const int k_max = *std::max_element(core.begin(), core.end());
  if (k_max > 0) result.max_core_size = static_cast<std::size_t>(std::count(core.begin(), core.end(), k_max));

  // Greedy lower bound from the highest-core vertices (PMC heuristic): grow a clique from v's neighbours in
  // order of decreasing core number.
  const int max_core = core[order.back()];
  constexpr int kHeuristicRoots = 64;
  for (int i = n - 1; i >= 0 && i >= n - kHeuristicRoots; --i) {
    const int v = order[i];
    if (core[v] + 1 <= static_cast<int>(best.size())) break;
    std::vector<int> cand;
    for (const int u : graph.neighbors(v))
      if (core[u] + 1 > static_cast<int>(best.size())) cand.push_back(u);
    std::stable_sort(cand.begin(), cand.end(), [&](int a, int b) { return core[a] > core[b]; });
    std::vector<int> clique{v};
    for (const int u : cand) {
      bool all = true;
      for (const int w : clique)
        if (!graph.adjacent(u, w)) {
          all = false;
          break;
        }
      if (all) clique.push_back(u);
    }
    if (clique.size() > best.size()) best = clique;
    if (static_cast<int>(best.size()) == max_core + 1) break;  // cannot do better than max core + 1
  }

  // Exact bitset branch and bound over the vertices that can still be in a larger clique (core >= |best|),
  // highest core first (a good initial order for the colouring bound).
  if (static_cast<int>(best.size()) < max_core + 1) {
    std::vector<int> cand;
    for (int i = n - 1; i >= 0; --i)
      if (core[order[i]] >= static_cast<int>(best.size())) cand.push_back(order[i]);
    BitsetCliqueSearch search(graph, cand, node_budget);
    std::vector<int> better = search.run(best.size());
    if (better.size() > best.size()) best = std::move(better);
    result.nodes = search.nodes();
    result.proven_maximum = !search.exhausted();
  }
  result.vertices = best;
  std::sort(result.vertices.begin(), result.vertices.end());
  return result;
}

}  // namespace cosmo::registration
