#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::jrl {

namespace {

std::string numbers(const std::vector<double>& v) {
  std::string out;
  char buf[40];
  for (double x : v) {
    std::snprintf(buf, sizeof buf, " %.17g", x);
    out += buf;
  }
  return out;
}

std::vector<double> poseNumbers(const cosmo::Pose3& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d& t = T.translation();
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

/// The 21 upper-triangular entries, row by row, of a symmetric matrix.
std::vector<double> upperTriangle(const Matrix6& m) {
  std::vector<double> upper;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) upper.push_back(0.5 * (m(i, j) + m(j, i)));
  return upper;
}

}  // namespace

Matrix6 g2oInformation(const Matrix6& covariance) {
  // e_g2o = D P r to first order: P moves [w, v] to [v, w], D = diag(1, 1, 1, 1/2, 1/2, 1/2) (q.xyz = w/2).
  // r^T Σ^-1 r = e^T (D^-1 P Σ^-1 P^T D^-1) e.
  const Matrix6 info = covariance.inverse();
  const Eigen::Matrix<double, 6, 1> scale = (Eigen::Matrix<double, 6, 1>() << 1, 1, 1, 2, 2, 2).finished();
  const int from[6] = {3, 4, 5, 0, 1, 2};  // g2o index i takes GTSAM index from[i]
  Matrix6 out;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out(i, j) = scale(i) * scale(j) * info(from[i], from[j]);
  return out;
}

void exportG2o(const Dataset& dataset, const std::string& path) {
  const PoseGraph g = poseGraph(dataset);
  if (g.initialization.empty()) throw std::runtime_error(dataset.name + ": no initialization to export");
  std::map<Key, long> id;
  std::string header = "# " + dataset.name + " (cosmo_jrl export): vertex ids in JRL key order, first ids";
  for (const auto& [key, T] : g.initialization) {
    const long next = static_cast<long>(id.size());
    if (id.empty() || robotOf(id.rbegin()->first) != robotOf(key))
      header += std::string(" ") + robotOf(key) + " " + std::to_string(next);
    id.emplace(key, next);
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << header << "\n";
  for (const auto& [key, T] : g.initialization)
    out << "VERTEX_SE3:QUAT " << id.at(key) << numbers(poseNumbers(T)) << "\n";
  for (const PoseFactor& f : g.factors) {
    if (f.kind == FactorKind::Prior) continue;
    const auto a = id.find(f.key1), b = id.find(f.key2);
    if (a == id.end() || b == id.end())
      throw std::runtime_error(dataset.name + ": no initialization of pose " +
                               keyName(a == id.end() ? f.key1 : f.key2));
    out << "EDGE_SE3:QUAT " << a->second << " " << b->second << numbers(poseNumbers(f.measured))
        << numbers(upperTriangle(g2oInformation(f.covariance))) << "\n";
  }
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace cosmo::jrl
