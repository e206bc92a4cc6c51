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

/// Σ^-1 with rows and columns reordered from [r, t] to [t, r], upper triangle row by row.
std::vector<double> g2oInformation(const Matrix6& covariance) {
  Eigen::PermutationMatrix<6> P;
  P.indices() << 3, 4, 5, 0, 1, 2;  // new index i takes old index P(i)
  Matrix6 reordered;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) reordered(i, j) = covariance(P.indices()(i), P.indices()(j));
  const Matrix6 info = reordered.inverse();
  std::vector<double> upper;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) upper.push_back(0.5 * (info(i, j) + info(j, i)));
  return upper;
}

}  // namespace

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
  for (const auto& [key, T] : g.initialization) out << "VERTEX_SE3:QUAT " << id.at(key) << numbers(poseNumbers(T)) << "\n";
  for (const PoseFactor& f : g.factors) {
    if (f.kind == FactorKind::Prior) continue;
    const auto a = id.find(f.key1), b = id.find(f.key2);
    if (a == id.end() || b == id.end())
      throw std::runtime_error(dataset.name + ": no initialization of pose " + keyName(a == id.end() ? f.key1 : f.key2));
    out << "EDGE_SE3:QUAT " << a->second << " " << b->second << numbers(poseNumbers(f.measured))
        << numbers(g2oInformation(f.covariance)) << "\n";
  }
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace cosmo::jrl
