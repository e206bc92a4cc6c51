// LAMP's translation-first covariances become JRL's rotation-first ones and back, element by element.
#include <gtest/gtest.h>

#include <sstream>

#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/covariance_order.hpp"
#include "cosmo/nebula/g2o_io.hpp"

using namespace cosmo;
using namespace cosmo::nebula;

TEST(CovarianceOrder, TranslationFirstBecomesRotationFirst) {
  // LAMP order (x, y, z, rx, ry, rz): variance of x is 1, of rx is 4; cov(x, rx) = 0.5; cov(y, rz) = 0.25.
  std::array<double, 36> lamp{};
  lamp[0 * 6 + 0] = 1.0;
  lamp[3 * 6 + 3] = 4.0;
  lamp[0 * 6 + 3] = lamp[3 * 6 + 0] = 0.5;
  lamp[1 * 6 + 5] = lamp[5 * 6 + 1] = 0.25;
  const Matrix6 jrl = toJrlCovariance(lamp);
  // JRL order (rx, ry, rz, x, y, z).
  EXPECT_EQ(jrl(0, 0), 4.0);  // rx
  EXPECT_EQ(jrl(3, 3), 1.0);  // x
  EXPECT_EQ(jrl(0, 3), 0.5);  // rx, x
  EXPECT_EQ(jrl(3, 0), 0.5);
  EXPECT_EQ(jrl(2, 4), 0.25);  // rz, y
  EXPECT_EQ(jrl(4, 2), 0.25);
  EXPECT_EQ(toLampCovariance(jrl), lamp);
  EXPECT_EQ(toJrlCovariance(lamp, CovarianceOrder::RotationFirst)(0, 0), 1.0);
}

TEST(CovarianceOrder, RoundTripsAnyMatrix) {
  Matrix6 m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = 10 * r + c + 0.125;
  EXPECT_EQ(toJrlCovariance(toLampCovariance(m)), m);
  EXPECT_EQ(swapTranslationRotation(swapTranslationRotation(m)), m);
}

TEST(CovarianceOrder, AdjointMapsTheCovarianceOfAnInverse) {
  // First-order check: T exp(xi) inverted equals T^-1 exp(-Ad_T xi).
  const Pose3 T = makePose(1.0, -2.0, 0.5, 0.3, -0.2, 1.1);
  Vector6 xi;
  xi << 1e-6, -2e-6, 3e-6, 4e-6, 1e-6, -2e-6;
  const Pose3 lhs = (T * expSE3(xi)).inverse();
  const Pose3 rhs = T.inverse() * expSE3(-adjoint(T) * xi);
  EXPECT_LT((lhs.matrix() - rhs.matrix()).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(G2o, ReadsVerticesAndEdgesWithCovarianceRotationFirst) {
  Matrix6 cov = Matrix6::Zero();
  cov.diagonal() << 1e-4, 2e-4, 3e-4, 0.01, 0.02, 0.03;  // rotation first
  const std::map<std::uint64_t, Pose3> v{{jrl::symbol('c', 0), Pose3::Identity()},
                                         {jrl::symbol('c', 1), makePose(1, 2, 3, 0.1, 0.2, 0.3)}};
  const std::vector<G2oEdge> e{{jrl::symbol('c', 0), jrl::symbol('c', 1), makePose(1, 2, 3, 0.1, 0.2, 0.3), cov, 0}};
  const std::string text = g2oText(v, e);
  // g2o's information is translation first: its first entry is 1 / var(x) = 100.
  EXPECT_NE(text.find(" 100 "), std::string::npos) << text;
  std::istringstream in(text + "VERTEX_XYZ 5 1 2 3\n");
  const G2oGraph g = parseG2o(in, "x.g2o");
  ASSERT_EQ(g.vertices.size(), 2u);
  ASSERT_EQ(g.edges.size(), 1u);
  EXPECT_LT((g.edges[0].covariance - cov).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_TRUE(g.vertices.at(jrl::symbol('c', 1)).isApprox(v.at(jrl::symbol('c', 1)), 1e-12));
  EXPECT_EQ(g.skipped.at("VERTEX_XYZ"), 1u);
}

TEST(G2o, ErrorsNameFileAndLine) {
  auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parseG2o(in, "result.g2o");
    } catch (const std::runtime_error& e) { return std::string(e.what()); }
    return std::string("no error");
  };
  EXPECT_EQ(error("VERTEX_SE3:QUAT 1 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 2 0 0 0 0 0\n"), "result.g2o:2: missing field qz");
  EXPECT_EQ(error("VERTEX_SE3:QUAT 1 0 0 0 0 0 0 2\n"), "result.g2o:1: quaternion norm 2.000000 is not 1");
  EXPECT_EQ(error("VERTEX_SE3:QUAT -3 0 0 0 0 0 0 1\n"), "result.g2o:1: key: '-3' is not a key");
  EXPECT_EQ(error("VERTEX_SE3:QUAT 1 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 0 0 0 0 0 0 1\n"),
            "result.g2o:2: vertex 1 appears twice");
  EXPECT_EQ(error("EDGE_SE3:QUAT 1 2 0 0 0 0 0 0 1 " + std::string(21 * 2, ' ') + "\n").substr(0, 13), "result.g2o:1:");
  EXPECT_EQ(error("VERTEX_SE3:QUAT 1 nan 0 0 0 0 0 1\n"), "result.g2o:1: x: 'nan' is not a finite number");
}
