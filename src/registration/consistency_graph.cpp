#include "cosmo/registration/consistency_graph.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Core>

#include "cosmo/registration/float4.hpp"

namespace cosmo::registration {

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
  if (source.size() != target.size()) throw std::invalid_argument("ConsistencyGraph: source and target sizes differ");
  const int n = static_cast<int>(source.size());
  ConsistencyGraph g(n);
  const float tol = static_cast<float>(tolerance);
  // Structure-of-arrays copies, padded to a multiple of 4, so that the inner loop runs on Float4 (from the
  // aligned block that holds i + 1; the lanes up to i are ignored).
  const std::size_t padded = (static_cast<std::size_t>(n) + 3) / 4 * 4;
  using Aligned = std::vector<float, Eigen::aligned_allocator<float>>;
  Aligned sx(padded, 0.f), sy(padded, 0.f), sz(padded, 0.f), tx(padded, 0.f), ty(padded, 0.f), tz(padded, 0.f);
  for (int i = 0; i < n; ++i) {
    sx[i] = source[i].x(), sy[i] = source[i].y(), sz[i] = source[i].z();
    tx[i] = target[i].x(), ty[i] = target[i].y(), tz[i] = target[i].z();
  }
  std::vector<std::int32_t, Eigen::aligned_allocator<std::int32_t>> ok(padded);
  const Float4 tol4(tol);
  for (int i = 0; i < n; ++i) {
    const Float4 ax(sx[i]), ay(sy[i]), az(sz[i]), bx(tx[i]), by(ty[i]), bz(tz[i]);
    const std::size_t j0 = static_cast<std::size_t>(i + 1) / 4 * 4;
    for (std::size_t j = j0; j < padded; j += 4) {
      const Float4 dsx = Float4::load(&sx[j]) - ax, dsy = Float4::load(&sy[j]) - ay, dsz = Float4::load(&sz[j]) - az;
      const Float4 dtx = Float4::load(&tx[j]) - bx, dty = Float4::load(&ty[j]) - by, dtz = Float4::load(&tz[j]) - bz;
      const Float4 ds = sqrt(dsx * dsx + dsy * dsy + dsz * dsz);
      const Float4 dt = sqrt(dtx * dtx + dty * dty + dtz * dtz);
      (abs(ds - dt) <= tol4).storeMask(&ok[j]);
    }
    for (int j = i + 1; j < n; ++j)
      if (ok[static_cast<std::size_t>(j)]) g.addEdgeBits(i, j);
  }
  g.finalize();
  return g;
}

}  // namespace cosmo::registration
