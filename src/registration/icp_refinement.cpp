#include "cosmo/registration/icp_refinement.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/kd_tree.hpp"

namespace cosmo::registration {

IcpResult refinePointToPlane(const std::vector<Eigen::Vector3f>& source, const std::vector<Eigen::Vector3f>& target,
                             const std::vector<Eigen::Vector3f>& target_normals, const Eigen::Isometry3d& initial,
                             double max_distance, int max_iterations) {
  if (target.empty()) {
    IcpResult out;
    out.T = initial;
    return out;
  }
  const KdTree<3> tree(target.front().data(), target.size());
  return refinePointToPlane(source, tree, target, target_normals, initial, max_distance, max_iterations);
}

double overlapFraction(const std::vector<Eigen::Vector3f>& source, const KdTree<3>& target_tree,
                       const Eigen::Isometry3d& T, double max_distance) {
  if (source.empty() || target_tree.size() == 0) return 0.0;
  const float max_d2 = static_cast<float>(max_distance * max_distance);
  const Eigen::Matrix3f Rf = T.linear().cast<float>();
  const Eigen::Vector3f tf = T.translation().cast<float>();
  std::size_t matched = 0;
  for (const auto& s : source) {
    const Eigen::Vector3f p = Rf * s + tf;
    matched += target_tree.anyWithin(p.data(), max_d2);
  }
  return static_cast<double>(matched) / static_cast<double>(source.size());
}

Overlaps overlapFractions(const std::vector<Eigen::Vector3f>& source, const std::vector<unsigned char>& flagged,
                          const KdTree<3>& target_tree, const Eigen::Isometry3d& T, double max_distance) {
  Overlaps out;
  if (source.empty() || target_tree.size() == 0) return out;
  const float max_d2 = static_cast<float>(max_distance * max_distance);
  const Eigen::Matrix3f Rf = T.linear().cast<float>();
  const Eigen::Vector3f tf = T.translation().cast<float>();
  std::size_t matched = 0, flagged_count = 0, flagged_matched = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3f p = Rf * source[i] + tf;
    const bool hit = target_tree.anyWithin(p.data(), max_d2);
    const bool f = i < flagged.size() && flagged[i];
    matched += hit;
    flagged_count += f;
    flagged_matched += f && hit;
  }
  out.all = static_cast<double>(matched) / static_cast<double>(source.size());
  if (flagged_count > 0) out.flagged = static_cast<double>(flagged_matched) / static_cast<double>(flagged_count);
  return out;
}

IcpResult refinePointToPlane(const std::vector<Eigen::Vector3f>& source, const KdTree<3>& tree,
                             const std::vector<Eigen::Vector3f>& target,
                             const std::vector<Eigen::Vector3f>& target_normals, const Eigen::Isometry3d& initial,
                             double max_distance, int max_iterations) {
  IcpResult out;
  out.T = initial;
  if (source.empty() || target.empty() || target_normals.size() != target.size() || tree.size() != target.size())
    return out;
  const float max_d2 = static_cast<float>(max_distance * max_distance);
  Eigen::Isometry3d T = initial;
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    std::size_t matched = 0;
    double sq = 0.0;
    const Eigen::Matrix3f Rf = T.linear().cast<float>();
    const Eigen::Vector3f tf = T.translation().cast<float>();
    for (const auto& s : source) {
      const Eigen::Vector3f p = Rf * s + tf;
      const auto [j, d2] = tree.nearestWithin(p.data(), max_d2);
      if (j < 0 || d2 > max_d2) continue;
      const Eigen::Vector3d n = target_normals[static_cast<std::size_t>(j)].cast<double>();
      const Eigen::Vector3d pd = p.cast<double>();
      const double r = n.dot(pd - target[static_cast<std::size_t>(j)].cast<double>());
      Eigen::Matrix<double, 6, 1> J;
      J.head<3>() = pd.cross(n);
      J.tail<3>() = n;
      // Cauchy-like weight keeps far planes from dominating.
      const double w = 1.0 / (1.0 + r * r / (0.1 * max_distance * max_distance));
      H += w * J * J.transpose();
      g += w * J * r;
      sq += r * r;
      ++matched;
    }
    out.matched = matched;
    out.rmse = matched ? std::sqrt(sq / static_cast<double>(matched)) : 0.0;
    if (matched < 6) return out;
    const Eigen::Matrix<double, 6, 1> dx = H.ldlt().solve(-g);
    if (!dx.allFinite()) return out;
    Eigen::Isometry3d dT = Eigen::Isometry3d::Identity();
    dT.linear() = expSO3(dx.head<3>());
    dT.translation() = dx.tail<3>();
    T = dT * T;
    out.T = T;
    if (dx.head<3>().norm() < 1e-4 && dx.tail<3>().norm() < 1e-3) {  // 0.006 deg, 1 mm
      out.converged = true;
      break;
    }
  }
  return out;
}

}  // namespace cosmo::registration
