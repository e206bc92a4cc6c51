// Exports (issue 25): each is read back and gives the same graph (g2o), poses (TUM) and labels (CSV), on the
// tiny example of jrl.md §12, a synthetic dataset and, when ../shared exists, the reference file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <unistd.h>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/closure_error.hpp"
#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/pose_graph.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "export_fixture.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::jrl;
namespace fs = std::filesystem;
using jrl_test::kTiny;
using jrl_test::splitBy;

namespace {

fs::path tempDir(const std::string& name) { return jrl_test::tempDir("exports_" + name); }

struct G2oEdge {
  long a = 0, b = 0;
  Pose3 measured;
  Matrix6 information;  // g2o's convention (jrl/exports.hpp)
};

struct G2oGraph {
  std::map<long, Pose3> vertices;
  std::vector<G2oEdge> edges;
};

Pose3 poseOf(std::istream& in) {
  double x, y, z, qx, qy, qz, qw;
  in >> x >> y >> z >> qx >> qy >> qz >> qw;
  return makePose({x, y, z}, Eigen::Quaterniond(qw, qx, qy, qz));
}

G2oGraph readG2o(const std::string& path) {
  G2oGraph g;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "VERTEX_SE3:QUAT") {
      long id;
      ls >> id;
      g.vertices[id] = poseOf(ls);
    } else if (tag == "EDGE_SE3:QUAT") {
      G2oEdge e;
      ls >> e.a >> e.b;
      e.measured = poseOf(ls);
      for (int i = 0; i < 6; ++i)
        for (int j = i; j < 6; ++j) {
          ls >> e.information(i, j);
          e.information(j, i) = e.information(i, j);
        }
      EXPECT_TRUE(ls) << line;
      g.edges.push_back(e);
    } else {
      EXPECT_EQ(tag[0], '#') << line;
    }
  }
  return g;
}

double poseDistance(const Pose3& a, const Pose3& b) { return logSE3(a.inverse() * b).norm(); }

/// g2o's chi² of an EDGE_SE3:QUAT as g2o defines its error (types_slam3d, EdgeSE3::computeError): the
/// translation and the quaternion's vector part (sign chosen with w >= 0) of m^-1 T1^-1 T2, in that order.
double g2oChi2(const Pose3& m, const Matrix6& information, const Pose3& T1, const Pose3& T2) {
  const Pose3 delta = m.inverse() * T1.inverse() * T2;
  Eigen::Quaterniond q(delta.linear());
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  Vector6 e;
  e << delta.translation(), q.vec();
  return e.dot(information * e);
}

void expectG2oRoundTrip(const Dataset& d, const fs::path& dir) {
  const std::string path = (dir / "graph.g2o").string();
  exportG2o(d, path);
  const G2oGraph g2o = readG2o(path);
  const PoseGraph g = poseGraph(d);
  ASSERT_EQ(g2o.vertices.size(), g.initialization.size());
  std::map<Key, long> id;
  for (const auto& [key, T] : g.initialization) id[key] = static_cast<long>(id.size());
  for (const auto& [key, T] : g.initialization) EXPECT_LT(poseDistance(g2o.vertices.at(id[key]), T), 1e-12);
  std::size_t e = 0;
  for (const PoseFactor& f : g.factors) {
    if (f.kind == FactorKind::Prior) continue;
    ASSERT_LT(e, g2o.edges.size());
    const G2oEdge& edge = g2o.edges[e++];
    EXPECT_EQ(edge.a, id.at(f.key1));
    EXPECT_EQ(edge.b, id.at(f.key2));
    EXPECT_LT(poseDistance(edge.measured, f.measured), 1e-12);
    // Back to GTSAM's order and units (rotation vector, not half of it) and to a covariance: the stored one.
    Matrix6 info;
    const int back[6] = {3, 4, 5, 0, 1, 2};
    const double unit[6] = {0.5, 0.5, 0.5, 1.0, 1.0, 1.0};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) info(i, j) = unit[i] * unit[j] * edge.information(back[i], back[j]);
    const Matrix6 cov = info.inverse();
    EXPECT_LT((cov - f.covariance).norm(), 1e-9 * f.covariance.norm());
  }
  EXPECT_EQ(e, g2o.edges.size());
}

void expectTumRoundTrip(const Dataset& d, const fs::path& dir) {
  const auto written = exportTum(d, (dir / "tum").string());
  const PoseGraph g = poseGraph(d);
  EXPECT_EQ(written.size(), 2 * d.robots.size());
  for (char r : d.robots) {
    for (const auto& [what, poses] : {std::pair<std::string, const PoseMap*>{"groundtruth", &g.groundtruth},
                                      std::pair<std::string, const PoseMap*>{"initialization", &g.initialization}}) {
      const Trajectory t =
          readTumTrajectory((dir / "tum" / (d.name + "_" + std::string(1, r) + "_" + what + ".tum")).string());
      const auto keys = g.ownKeys(r);
      ASSERT_EQ(t.size(), keys.size()) << r << " " << what;
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const auto& p = t.poses()[i];
        EXPECT_NEAR(double(p.stamp), double(g.stamps.at(keys[i])), 2e3);  // seconds as a double: ~0.5 us
        EXPECT_LT((p.pose.translation() - poses->at(keys[i]).translation()).norm(), 2e-6);
        EXPECT_LT(rotationAngle(p.pose.inverse() * poses->at(keys[i])), 1e-8);
      }
    }
  }
}

void expectLabelsRoundTrip(const Dataset& d, const fs::path& dir) {
  const std::string path = (dir / "labels.csv").string();
  exportLabelsCsv(d, path);
  const PoseGraph g = poseGraph(d);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "robot,entry,measurement,kind,key1,key2,pose1,pose2,stamp_ns,trans_err_m,rot_err_deg,d2,label");
  std::size_t rows = 0;
  for (const PoseFactor& f : g.factors) {
    if (!f.isLoopClosure()) continue;
    ASSERT_TRUE(std::getline(in, line));
    const auto c = splitBy(line, ',');
    ASSERT_EQ(c.size(), 13u) << line;
    EXPECT_EQ(c[0], std::string(1, f.robot));
    EXPECT_EQ(std::stoul(c[1]), f.id.entry);
    EXPECT_EQ(std::stoul(c[2]), f.id.measurement);
    EXPECT_EQ(c[3], factorKindName(f.kind));
    EXPECT_EQ(std::stoull(c[4]), f.key1);
    EXPECT_EQ(std::stoull(c[5]), f.key2);
    EXPECT_EQ(c[6], keyName(f.key1));
    EXPECT_EQ(std::stoull(c[8]), f.stamp);
    const ClosureError e = closureError(f, g.groundtruth);
    EXPECT_NEAR(std::stod(c[9]), e.trans_m, 1e-6);
    EXPECT_NEAR(std::stod(c[11]), e.d2, 1e-6 * std::max(1.0, e.d2));
    EXPECT_EQ(c[12], f.outlier ? "outlier" : "inlier");
    EXPECT_EQ(f.outlier, d.outliers->at(f.robot).count(f.id) == 1);
    ++rows;
  }
  EXPECT_FALSE(std::getline(in, line)) << "extra row " << line;
  EXPECT_GT(rows, 0u);
}

}  // namespace

TEST(JrlExports, G2oInformationFollowsG2osOwnErrorConvention) {
  // Known covariance: rotation σ 0.01 rad, translation σ 0.1 m, uncorrelated. g2o's error holds the translation
  // first and half the rotation vector, so its information is diag(1/0.1², 4/0.01²).
  Matrix6 cov = Matrix6::Zero();
  cov.diagonal() << 1e-4, 1e-4, 1e-4, 1e-2, 1e-2, 1e-2;
  Matrix6 want = Matrix6::Zero();
  want.diagonal() << 100.0, 100.0, 100.0, 40000.0, 40000.0, 40000.0;
  EXPECT_LT((g2oInformation(cov) - want).norm(), 1e-9 * want.norm());

  // A dense covariance: for a small error g2o's chi² with that information is the JRL d² (rotation first,
  // GTSAM's Log) that the labels and the solver use.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  Matrix6 A = Matrix6::Identity();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < r; ++c) A(r, c) = 0.2 * n(rng);
  const Vector6 sigma = (Vector6() << 0.01, 0.02, 0.015, 0.1, 0.3, 0.2).finished();
  const Matrix6 L = sigma.asDiagonal() * A;
  PoseFactor f;
  f.kind = FactorKind::LoopClosure;
  f.key1 = symbol('a', 0);
  f.key2 = symbol('a', 9);
  f.covariance = L * L.transpose();
  const Matrix6 info = g2oInformation(f.covariance);
  for (int k = 0; k < 20; ++k) {
    Vector6 xi, noise;
    for (int i = 0; i < 6; ++i) xi(i) = (i < 3 ? 1.0 : 10.0) * n(rng);
    for (int i = 0; i < 6; ++i) noise(i) = 1e-4 * n(rng);
    const Pose3 T1 = expSE3(xi * 0.3), T2 = expSE3(xi);
    f.measured = T1.inverse() * T2 * expSE3(noise);
    const double d2 = closureError(f, {{f.key1, T1}, {f.key2, T2}}).d2;
    EXPECT_NEAR(g2oChi2(f.measured, info, T1, T2), d2, 1e-3 * d2);
    // The block swap alone (no factor 4 on the rotation) gives g2o a different chi².
    Matrix6 swapped_only = info;
    swapped_only.bottomRows<3>() *= 0.5;
    swapped_only.rightCols<3>() *= 0.5;
    EXPECT_GT(std::abs(g2oChi2(f.measured, swapped_only, T1, T2) - d2), 1e-2 * d2);
  }
}

TEST(JrlExports, TinyExampleReadsBack) {
  const Dataset d = readJrl(kTiny);
  const fs::path dir = tempDir("tiny");
  expectG2oRoundTrip(d, dir);
  expectTumRoundTrip(d, dir);
  expectLabelsRoundTrip(d, dir);
  // jrl.md §12: a2 -> a0 is the outlier, b1 -> a1 an inlier.
  const std::string text = readWholeFileOrEmpty(dir / "labels.csv");
  EXPECT_NE(text.find("a,2,1,lc,6989586621679009794,6989586621679009792,a2,a0,1700000001000000000,"), std::string::npos)
      << text;
  EXPECT_NE(text.find(",outlier\n"), std::string::npos);
  EXPECT_NE(text.find("b,1,1,irlc,7061644215716937729,6989586621679009793,b1,a1,"), std::string::npos);
  // The g2o header names each robot's first vertex id: a0 a1 a2 b0 b1 -> a 0, b 3.
  std::ifstream g2o(dir / "graph.g2o");
  std::string header;
  std::getline(g2o, header);
  EXPECT_NE(header.find("first ids a 0 b 3"), std::string::npos) << header;
  fs::remove_all(dir);
}

TEST(JrlExports, SyntheticDatasetReadsBack) {
  std::mt19937_64 rng(2);
  SyntheticParams p;
  p.poses_per_robot = 80;
  const Dataset d = makeSyntheticDataset(p, rng);
  const fs::path dir = tempDir("synthetic");
  expectG2oRoundTrip(d, dir);
  expectTumRoundTrip(d, dir);
  expectLabelsRoundTrip(d, dir);
  fs::remove_all(dir);
}

TEST(JrlExports, ReferenceFileReadsBackAndItsLabelsFollowTheRule) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const Dataset d = readJrl(*path);
  const fs::path dir = tempDir("reference");
  expectG2oRoundTrip(d, dir);
  expectTumRoundTrip(d, dir);
  expectLabelsRoundTrip(d, dir);
  // jrl.md §10: outliers have d^2 >= 189, listed inliers <= 152 (the labels' own measure, rotation first).
  const PoseGraph g = poseGraph(d);
  std::size_t outliers = 0;
  for (const PoseFactor& f : g.factors) {
    if (!f.isLoopClosure() || !f.potential_outlier) continue;
    const double d2 = closureError(f, g.groundtruth).d2;
    if (f.outlier) {
      EXPECT_GE(d2, 189.0);
      ++outliers;
    } else {
      EXPECT_LE(d2, 152.5);
    }
  }
  EXPECT_EQ(outliers, 75u);
  fs::remove_all(dir);
}
