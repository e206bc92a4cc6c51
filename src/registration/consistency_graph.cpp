#include "cosmo/registration/consistency_graph.hpp"

#include <cmath>
#include <stdexcept>

namespace cosmo {

ConsistencyGraph::ConsistencyGraph(int n)
    : n_(std::max(n, 0)), words_((static_cast<std::size_t>(std::max(n, 0)) + 63) / 64) {
  bits_.assign(static_cast<std::size_t>(n_) * words_, 0u);
  adj_.resize(static_cast<std::size_t>(n_));
}

void ConsistencyGraph::addEdgeBits(int a, int b) {
  bits_[static_cast<std::size_t>(a) * words_ + (b >> 6)] |= std::uint64_t{1} << (b & 63);
  bits_[static_cast<std::size_t>(b) * words_ + (a >> 6)] |= std::uint64_t{1} << (a & 63);
}

void ConsistencyGraph::finalize() {
  edges_ = 0;
  for (int v = 0; v < n_; ++v) {
    auto& list = adj_[static_cast<std::size_t>(v)];
    list.clear();
    const std::uint64_t* row = &bits_[static_cast<std::size_t>(v) * words_];
    for (std::size_t w = 0; w < words_; ++w) {
      std::uint64_t word = row[w];
      while (word) {
        const int b = __builtin_ctzll(word);
        list.push_back(static_cast<int>(w * 64 + static_cast<std::size_t>(b)));
        word &= word - 1;
      }
    }
    edges_ += list.size();
  }
  edges_ /= 2;
}

ConsistencyGraph ConsistencyGraph::fromEdges(int n, const std::vector<std::pair<int, int>>& edges) {
  ConsistencyGraph g(n);
  for (const auto& [a, b] : edges) {
    if (a < 0 || b < 0 || a >= n || b >= n) throw std::invalid_argument("ConsistencyGraph: edge vertex out of range");
    if (a != b) g.addEdgeBits(a, b);
  }
  g.finalize();
  return g;
}

ConsistencyGraph ConsistencyGraph::induced(const std::vector<int>& vertices) const {
  const int m = static_cast<int>(vertices.size());
  ConsistencyGraph g(m);
  for (int a = 0; a < m; ++a)
    for (int b = a + 1; b < m; ++b)
      if (adjacent(vertices[static_cast<std::size_t>(a)], vertices[static_cast<std::size_t>(b)])) g.addEdgeBits(a, b);
  g.finalize();
  return g;
}

ConsistencyGraph ConsistencyGraph::fromCorrespondences(const std::vector<Eigen::Vector3f>& source,
                                                       const std::vector<Eigen::Vector3f>& target, double tolerance) {
  if (source.size() != target.size())
    throw std::invalid_argument("ConsistencyGraph: source and target sizes differ");
  const int n = static_cast<int>(source.size());
  ConsistencyGraph g(n);
  const float tol = static_cast<float>(tolerance);
  // Structure-of-arrays copies so the inner loop vectorises.
  std::vector<float> sx(n), sy(n), sz(n), tx(n), ty(n), tz(n);
  for (int i = 0; i < n; ++i) {
    sx[i] = source[i].x(), sy[i] = source[i].y(), sz[i] = source[i].z();
    tx[i] = target[i].x(), ty[i] = target[i].y(), tz[i] = target[i].z();
  }
  std::vector<unsigned char> ok(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const float ax = sx[i], ay = sy[i], az = sz[i], bx = tx[i], by = ty[i], bz = tz[i];
    for (int j = i + 1; j < n; ++j) {
      const float dsx = sx[j] - ax, dsy = sy[j] - ay, dsz = sz[j] - az;
      const float dtx = tx[j] - bx, dty = ty[j] - by, dtz = tz[j] - bz;
      const float ds = std::sqrt(dsx * dsx + dsy * dsy + dsz * dsz);
      const float dt = std::sqrt(dtx * dtx + dty * dty + dtz * dtz);
      ok[static_cast<std::size_t>(j)] = std::fabs(ds - dt) <= tol;
    }
    for (int j = i + 1; j < n; ++j)
      if (ok[static_cast<std::size_t>(j)]) g.addEdgeBits(i, j);
  }
  g.finalize();
  return g;
}

}  // namespace cosmo
