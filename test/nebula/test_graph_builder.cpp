// Merging LAMP messages into a team graph: incremental pieces, repeats, edges of every type counted, and every
// malformed input a GraphError or a counted warning (never a silent drop).
#include <gtest/gtest.h>

#include "cosmo/nebula/graph_builder.hpp"
#include "cosmo/nebula/jrl_assembly.hpp"
#include "cosmo/jrl/validate.hpp"

using namespace cosmo;
using namespace cosmo::nebula;
using jrl::symbol;

namespace {

constexpr StampNs kT0 = 1'600'000'000'000'000'000ull;

PoseGraphNode node(jrl::Key key, StampNs stamp) {
  PoseGraphNode n;
  n.key = key;
  n.header.sec = static_cast<std::uint32_t>(stamp / 1'000'000'000ull);
  n.header.nsec = static_cast<std::uint32_t>(stamp % 1'000'000'000ull);
  return n;
}

PoseGraphEdge edge(jrl::Key from, jrl::Key to, std::int32_t type, double x = 1.0) {
  PoseGraphEdge e;
  e.key_from = from;
  e.key_to = to;
  e.type = type;
  e.pose.position = {x, 0.0, 0.0};
  Matrix6 cov = Matrix6::Identity() * 0.01;
  e.covariance = toLampCovariance(cov);
  return e;
}

/// A robot `c` with poses 0..n-1 one second apart, one message.
PoseGraph chain(char c, std::size_t n, StampNs t0 = kT0) {
  PoseGraph g;
  for (std::size_t i = 0; i < n; ++i) {
    g.nodes.push_back(node(symbol(c, i), t0 + i * 1'000'000'000ull));
    if (i) g.edges.push_back(edge(symbol(c, i - 1), symbol(c, i), kOdom));
  }
  return g;
}

std::string buildError(const GraphBuilder& b) {
  try {
    b.build();
  } catch (const GraphError& e) { return e.what(); }
  return "no error";
}

}  // namespace

TEST(GraphBuilder, MergesIncrementalMessagesAndCountsEveryType) {
  GraphBuilder b;
  PoseGraph first = chain('c', 3);
  PoseGraph second;
  second.nodes.push_back(first.nodes.back());  // LAMP repeats the last node
  for (std::size_t i = 3; i < 6; ++i) {
    second.nodes.push_back(node(symbol('c', i), kT0 + i * 1'000'000'000ull));
    second.edges.push_back(edge(symbol('c', i - 1), symbol('c', i), kOdom));
  }
  second.nodes.push_back(node(symbol('C', 0), kT0));  // an artifact
  second.nodes.push_back(node(symbol('u', 0), kT0));  // a UWB anchor
  for (std::int32_t t : {kPrior, kImu, kArtifact, kUwbRange, kUwbBetween, kInterRobotRange})
    second.edges.push_back(edge(symbol('c', 1), symbol('C', 0), t));
  second.edges.push_back(edge(symbol('c', 5), symbol('c', 1), kLoopClose));
  b.addMessage(first, "husky3", "a.bag #0");
  b.addMessage(second, "husky3", "a.bag #1");
  b.addMessage(first, "husky3", "a.bag #2");  // a full re-publication
  const NebulaGraph g = b.build();
  ASSERT_EQ(g.robots.size(), 1u);
  const RobotGraph& r = g.robots.at('c');
  EXPECT_EQ(r.name, "husky3");
  EXPECT_EQ(r.stamps.size(), 6u);
  EXPECT_EQ(r.odometry.size(), 5u);
  EXPECT_EQ(r.stamps[4], kT0 + 4'000'000'000ull);
  ASSERT_EQ(g.loop_closures.size(), 1u);
  EXPECT_EQ(g.loop_closures[0].key1, symbol('c', 5));
  for (const char* type : {"PRIOR", "IMU", "ARTIFACT", "UWB_RANGE", "UWB_BETWEEN", "INTERROB_RANGE"})
    EXPECT_EQ(g.ignored_edges.at(type), 1u) << type;
  EXPECT_EQ(g.other_nodes.at('C'), 1u);
  EXPECT_EQ(g.other_nodes.at('u'), 1u);
  EXPECT_EQ(g.repeated_nodes, 4u);
  EXPECT_EQ(g.repeated_edges, 2u);
  EXPECT_EQ(g.warnings.total(), 0u) << g.warnings.str();
}

TEST(GraphBuilder, UnknownTypesAndDanglingClosuresAreCountedWarnings) {
  GraphBuilder b;
  PoseGraph g = chain('c', 4);
  g.edges.push_back(edge(symbol('c', 1), symbol('c', 3), 42));                  // unknown type
  g.edges.push_back(edge(symbol('c', 3), symbol('c', 9), kLoopClose));          // c9 has no node
  g.edges.push_back(edge(symbol('c', 3), symbol('q', 1), kInterRobotBetween));  // no robot's pose
  g.edges.push_back(edge(symbol('c', 2), symbol('c', 2), kLoopClose));          // to itself
  g.edges.push_back(edge(symbol('c', 0), symbol('c', 2), kOdom));               // odometry skipping a pose
  b.addMessage(g, "husky3", "a.bag #0");
  PoseGraph again;
  again.nodes.push_back(node(symbol('c', 1), kT0 + 5));                     // another stamp
  again.edges.push_back(edge(symbol('c', 0), symbol('c', 1), kOdom, 2.0));  // another measurement
  b.addMessage(again, "husky3", "a.bag #1");
  const NebulaGraph out = b.build();
  EXPECT_TRUE(out.loop_closures.empty());
  const auto& w = out.warnings.counts;
  EXPECT_EQ(w.at("edges of an unknown type (ignored)"), 1u);
  EXPECT_EQ(w.at("loop closures touching a pose without a node or after its robot's last odometry (dropped)"), 1u);
  EXPECT_EQ(w.at("loop closures touching a key that is no robot's pose (dropped)"), 1u);
  EXPECT_EQ(w.at("loop closures from a pose to itself (dropped)"), 1u);
  EXPECT_EQ(w.at("ODOM edges not between consecutive poses of one robot (ignored)"), 1u);
  EXPECT_EQ(w.at("nodes published again with another stamp (the first stamp is kept)"), 1u);
  EXPECT_EQ(w.at("edges published again with another measurement (the first is kept)"), 1u);
  EXPECT_NE(out.warnings.str().find("unknown type 42 c1 -> c3 (a.bag #0)"), std::string::npos) << out.warnings.str();
  EXPECT_EQ(out.robots.at('c').odometry[0].measurement.translation().x(), 1.0);  // the first copy
}

TEST(GraphBuilder, BrokenChainsAreErrors) {
  {  // a missing ODOM edge in the middle
    GraphBuilder b;
    PoseGraph g = chain('c', 6);
    g.edges.erase(g.edges.begin() + 2);  // c2 -> c3
    b.addMessage(g, "husky3", "a.bag #0");
    EXPECT_NE(buildError(b).find("odometry chain broken: no ODOM edge c2 -> c3"), std::string::npos) << buildError(b);
  }
  {  // an ODOM edge to a key without a node
    GraphBuilder b;
    PoseGraph g = chain('c', 4);
    g.nodes.erase(g.nodes.begin() + 2);
    b.addMessage(g, "husky3", "a.bag #0");
    EXPECT_NE(buildError(b).find("leads to c2, which has no node"), std::string::npos) << buildError(b);
  }
  {  // stamps going back
    GraphBuilder b;
    PoseGraph g = chain('c', 4);
    g.nodes[2].header.sec -= 10;
    b.addMessage(g, "husky3", "a.bag #0");
    EXPECT_NE(buildError(b).find("the stamp of c2"), std::string::npos) << buildError(b);
  }
  {  // no first pose
    GraphBuilder b;
    PoseGraph g = chain('c', 4);
    g.nodes.erase(g.nodes.begin());
    b.addMessage(g, "husky3", "a.bag #0");
    EXPECT_NE(buildError(b).find("no node for its first pose c0"), std::string::npos) << buildError(b);
  }
}

TEST(GraphBuilder, TrailingPoseWithoutOdometryIsLeftOutWithAWarning) {
  GraphBuilder b;
  PoseGraph g = chain('c', 4);
  g.nodes.push_back(node(symbol('c', 4), kT0 + 9'000'000'000ull));
  b.addMessage(g, "husky3", "a.bag #0");
  const NebulaGraph out = b.build();
  EXPECT_EQ(out.robots.at('c').stamps.size(), 4u);
  EXPECT_EQ(out.warnings.counts.at("poses after the last odometry edge of their robot (left out)"), 1u);
}

TEST(GraphBuilder, TwoRobotsWithOneCharacterIsAnError) {
  GraphBuilder b;
  b.addMessage(chain('c', 3), "husky3", "husky3.bag /husky3/lamp/pose_graph_incremental #0");
  b.addMessage(chain('c', 3), "husky4", "husky4.bag /husky4/lamp/pose_graph_incremental #0");
  const std::string error = buildError(b);
  EXPECT_NE(error.find("robot character 'c' is used by two robots: husky3 (husky3.bag"), std::string::npos) << error;
  EXPECT_NE(error.find("husky4 (husky4.bag"), std::string::npos) << error;
}

TEST(JrlAssembly, ClosureGoesToTheLaterPoseAndKeysStay) {
  GraphBuilder b;
  b.addMessage(chain('c', 5), "husky3", "c.bag");
  PoseGraph d = chain('d', 5, kT0 + 500'000'000ull);                            // d_i is half a second after c_i
  d.edges.push_back(edge(symbol('d', 1), symbol('c', 3), kInterRobotBetween));  // c3 is later: stored in c's entry 3
  d.edges.push_back(edge(symbol('d', 4), symbol('c', 0), kLoopClose));          // d4 is later: stays as it is
  b.addMessage(d, "husky4", "d.bag");
  const NebulaGraph g = b.build();
  std::map<jrl::Key, Pose3> reference;
  for (char c : {'c', 'd'})
    for (std::size_t i = 0; i < 5; ++i) reference[symbol(c, i)] = makePose(double(i), c == 'c' ? 0.0 : 5.0, 0, 0, 0, 0);
  ConversionReport report;
  const jrl::Dataset ds = assembleJrl(g, reference, ConversionParams{}, &report);
  EXPECT_TRUE(jrl::validate(ds).empty());
  EXPECT_EQ(report.inverted, 1u);
  const auto& c3 = ds.measurements.at('c')[3].factors;
  ASSERT_EQ(c3.size(), 2u);
  EXPECT_EQ(c3[1].keys, (std::vector<jrl::Key>{symbol('c', 3), symbol('d', 1)}));
  EXPECT_NEAR(c3[1].pose3().translation().x(), -1.0, 1e-12);  // the inverse of d1 -> c3's +1 m
  const auto& d4 = ds.measurements.at('d')[4].factors;
  ASSERT_EQ(d4.size(), 2u);
  EXPECT_EQ(d4[1].keys, (std::vector<jrl::Key>{symbol('d', 4), symbol('c', 0)}));
  EXPECT_EQ(ds.measurements.at('c')[3].stamp, kT0 + 3'000'000'000ull);
  EXPECT_EQ(ds.potential_outliers->at('c').size(), 1u);
}
