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

/// One robot's vertices: ids first .. first + count - 1.
struct Block {
  char robot = 0;
  long first = 0, count = 0;
};

/// The graph's path without its ".g2o", the start of the files beside it.
std::string g2oStem(const std::string& g2o_path) {
  const std::string ext = ".g2o";
  const bool has_ext =
      g2o_path.size() > ext.size() && g2o_path.compare(g2o_path.size() - ext.size(), ext.size(), ext) == 0;
  return has_ext ? g2o_path.substr(0, g2o_path.size() - ext.size()) : g2o_path;
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write");
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

std::string g2oBlocksPath(const std::string& g2o_path) { return g2oStem(g2o_path) + ".blocks.csv"; }

std::string g2oIdsPath(const std::string& g2o_path) { return g2oStem(g2o_path) + ".ids.csv"; }

std::vector<std::string> exportG2o(const Dataset& dataset, const std::string& path) {
  const PoseGraph g = poseGraph(dataset);
  if (g.initialization.empty()) throw std::runtime_error(dataset.name + ": no initialization to export");
  std::map<Key, long> id;
  std::vector<Block> blocks;
  std::string header = "# " + dataset.name + " (cosmo_jrl export): vertex ids in JRL key order, first ids";
  for (const auto& [key, T] : g.initialization) {
    const long next = static_cast<long>(id.size());
    if (id.empty() || robotOf(id.rbegin()->first) != robotOf(key)) {
      header += std::string(" ") + robotOf(key) + " " + std::to_string(next);
      blocks.push_back({robotOf(key), next, 0});
    }
    ++blocks.back().count;
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

  std::string text = "robot,first_id,count\n";
  for (const Block& b : blocks)
    text += std::string(1, b.robot) + "," + std::to_string(b.first) + "," + std::to_string(b.count) + "\n";
  const std::string blocks_path = g2oBlocksPath(path);
  writeText(blocks_path, text);
  text = "g2o_id,robot,jrl_key,stamp\n";
  for (const auto& [key, vertex] : id) {
    const auto stamp = g.stamps.find(key);
    text += std::to_string(vertex) + "," + std::string(1, robotOf(key)) + "," + std::to_string(key) + "," +
            (stamp == g.stamps.end() ? "" : std::to_string(stamp->second)) + "\n";
  }
  const std::string ids_path = g2oIdsPath(path);
  writeText(ids_path, text);
  return {path, blocks_path, ids_path};
}

}  // namespace cosmo::jrl
