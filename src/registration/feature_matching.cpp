#include "cosmo/registration/feature_matching.hpp"

#include <algorithm>

#include "cosmo/common/kd_tree.hpp"

namespace cosmo::registration {

std::vector<Correspondence> matchFeatures(const FpfhMatrix& source, const FpfhMatrix& target, std::size_t max_count,
                                          bool mutual, float eps) {
  std::vector<Correspondence> out;
  const auto ns = static_cast<std::size_t>(source.cols());
  const auto nt = static_cast<std::size_t>(target.cols());
  if (ns == 0 || nt == 0 || max_count == 0) return out;
  // Column-major 33 x n: each column is a contiguous row of 33 floats for the kd-tree.
  const KdTree<kFpfhDim> target_tree(target.data(), nt);
  std::vector<int> s2t(ns);
  std::vector<float> s2t_d(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    const auto [j, d] = target_tree.nearest(source.col(static_cast<Eigen::Index>(i)).data(), eps);
    s2t[i] = j;
    s2t_d[i] = d;
  }
  if (mutual) {
    // Nearest source feature only for the targets that some source point picked.
    std::vector<int> t2s(nt, -2);
    for (std::size_t i = 0; i < ns; ++i) t2s[static_cast<std::size_t>(s2t[i])] = -1;
    const KdTree<kFpfhDim> source_tree(source.data(), ns);
    for (std::size_t j = 0; j < nt; ++j) {
      if (t2s[j] != -1) continue;
      t2s[j] = source_tree.nearest(target.col(static_cast<Eigen::Index>(j)).data(), eps).first;
    }
    for (std::size_t i = 0; i < ns; ++i)
      if (t2s[static_cast<std::size_t>(s2t[i])] == static_cast<int>(i))
        out.push_back({static_cast<int>(i), s2t[i], s2t_d[i]});
  } else {
    for (std::size_t i = 0; i < ns; ++i) out.push_back({static_cast<int>(i), s2t[i], s2t_d[i]});
  }
  std::sort(out.begin(), out.end(), [](const Correspondence& a, const Correspondence& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.source < b.source;
  });
  if (out.size() > max_count) out.resize(max_count);
  return out;
}

}  // namespace cosmo::registration
