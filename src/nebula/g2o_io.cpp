#include "cosmo/nebula/g2o_io.hpp"

#include <Eigen/Cholesky>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "cosmo/nebula/covariance_order.hpp"

namespace cosmo::nebula {

namespace {

/// Tokens of one line with the place for errors.
class LineFields {
 public:
  LineFields(std::string source, std::size_t line, std::istringstream& tokens)
      : where_(std::move(source) + ":" + std::to_string(line) + ": "), tokens_(tokens) {}

  std::uint64_t key(const char* what) {
    const std::string t = next(what);
    errno = 0;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(t.c_str(), &end, 10);
    if (t.empty() || t[0] == '-' || *end || errno == ERANGE) fail(std::string(what) + ": '" + t + "' is not a key");
    return v;
  }
  double number(const char* what) {
    const std::string t = next(what);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end || !std::isfinite(v)) fail(std::string(what) + ": '" + t + "' is not a finite number");
    return v;
  }
  Pose3 pose() {
    const double x = number("x"), y = number("y"), z = number("z");
    const double qx = number("qx"), qy = number("qy"), qz = number("qz"), qw = number("qw");
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    if (std::abs(q.norm() - 1.0) > 1e-3) fail("quaternion norm " + std::to_string(q.norm()) + " is not 1");
    return makePose(Eigen::Vector3d(x, y, z), q);
  }
  [[noreturn]] void fail(const std::string& problem) const { throw std::runtime_error(where_ + problem); }

 private:
  std::string next(const char* what) {
    std::string t;
    if (!(tokens_ >> t)) fail(std::string("missing field ") + what);
    return t;
  }
  std::string where_;
  std::istringstream& tokens_;
};

}  // namespace

G2oGraph parseG2o(std::istream& in, const std::string& source) {
  G2oGraph graph;
  std::string text;
  for (std::size_t line_no = 1; std::getline(in, text); ++line_no) {
    std::istringstream tokens(text);
    std::string tag;
    if (!(tokens >> tag) || tag[0] == '#') continue;
    LineFields f(source, line_no, tokens);
    if (tag == "VERTEX_SE3:QUAT") {
      const std::uint64_t key = f.key("key");
      const Pose3 pose = f.pose();
      if (!graph.vertices.emplace(key, pose).second) f.fail("vertex " + std::to_string(key) + " appears twice");
    } else if (tag == "EDGE_SE3:QUAT") {
      G2oEdge e;
      e.line = line_no;
      e.key1 = f.key("key1");
      e.key2 = f.key("key2");
      e.measurement = f.pose();
      Matrix6 info;
      for (int r = 0; r < 6; ++r)
        for (int c = r; c < 6; ++c) info(r, c) = info(c, r) = f.number("information");
      const Eigen::LLT<Matrix6> llt(info);
      if (llt.info() != Eigen::Success) f.fail("information matrix is not positive definite");
      e.covariance = swapTranslationRotation(llt.solve(Matrix6::Identity()));
      graph.edges.push_back(e);
    } else {
      ++graph.skipped[tag];
    }
  }
  return graph;
}

G2oGraph readG2o(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open g2o file");
  return parseG2o(in, path);
}

std::string g2oText(const std::map<std::uint64_t, Pose3>& vertices, const std::vector<G2oEdge>& edges) {
  std::ostringstream out;
  out << std::setprecision(17);
  auto pose = [&](const Pose3& T) {
    const Eigen::Quaterniond q(T.linear());
    out << T.translation().x() << ' ' << T.translation().y() << ' ' << T.translation().z() << ' ' << q.x() << ' '
        << q.y() << ' ' << q.z() << ' ' << q.w();
  };
  for (const auto& [key, T] : vertices) {
    out << "VERTEX_SE3:QUAT " << key << ' ';
    pose(T);
    out << '\n';
  }
  for (const G2oEdge& e : edges) {
    out << "EDGE_SE3:QUAT " << e.key1 << ' ' << e.key2 << ' ';
    pose(e.measurement);
    const Matrix6 info = swapTranslationRotation(e.covariance).inverse();
    for (int r = 0; r < 6; ++r)
      for (int c = r; c < 6; ++c) out << ' ' << info(r, c);
    out << '\n';
  }
  return out.str();
}

}  // namespace cosmo::nebula
