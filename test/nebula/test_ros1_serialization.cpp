// The ROS 1 PoseGraph codec: round trip, and every malformed input is a DecodeError naming field and offset.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"

using namespace cosmo;
using namespace cosmo::nebula;

namespace {

PoseGraph sampleGraph() {
  PoseGraph g;
  g.header.seq = 7;
  g.header.sec = 1600000000;
  g.header.nsec = 123;
  g.header.frame_id = "world";
  g.incremental = true;
  for (int i = 0; i < 3; ++i) {
    PoseGraphNode n;
    n.header.sec = 1600000000 + i;
    n.header.frame_id = "world";
    n.key = jrl::symbol('c', i);
    n.id = i == 2 ? "artifact" : "";
    n.pose.position = {1.0 * i, 2.0, 3.0};
    n.pose.orientation = {0.0, 0.0, 0.6, 0.8};
    for (int k = 0; k < 36; ++k) n.covariance[k] = k * 0.5 + i;
    g.nodes.push_back(n);
  }
  for (int i = 0; i < 2; ++i) {
    PoseGraphEdge e;
    e.key_from = jrl::symbol('c', i);
    e.key_to = jrl::symbol('c', i + 1);
    e.type = i == 0 ? kOdom : kLoopClose;
    e.pose.position = {0.5, -0.5, 0.25};
    for (int k = 0; k < 36; ++k) e.covariance[k] = -k;
    e.range = 4.5;
    e.range_error = 0.1;
    g.edges.push_back(e);
  }
  return g;
}

}  // namespace

TEST(Ros1Serialization, RoundTripKeepsEveryField) {
  const PoseGraph g = sampleGraph();
  const auto bytes = encodePoseGraph(g);
  // header 4+8+4+5, bool 1, 3 nodes (21 header, 8 key, 4+ID, 56 pose, 288 cov), 2 edges of 380 bytes
  EXPECT_EQ(bytes.size(), 21u + 1u + 4u + 3u * (21u + 8u + 4u + 56u + 288u) + 8u + 4u + 2u * 380u);
  const PoseGraph d = decodePoseGraph(bytes);
  EXPECT_EQ(d.header.seq, 7u);
  EXPECT_EQ(d.header.stampNs(), 1600000000'000000123ull);
  EXPECT_EQ(d.header.frame_id, "world");
  ASSERT_EQ(d.nodes.size(), 3u);
  EXPECT_EQ(d.nodes[2].key, jrl::symbol('c', 2));
  EXPECT_EQ(d.nodes[2].id, "artifact");
  EXPECT_EQ(d.nodes[1].pose.position, g.nodes[1].pose.position);
  EXPECT_EQ(d.nodes[1].pose.orientation, g.nodes[1].pose.orientation);
  EXPECT_EQ(d.nodes[2].covariance, g.nodes[2].covariance);
  ASSERT_EQ(d.edges.size(), 2u);
  EXPECT_EQ(d.edges[1].type, kLoopClose);
  EXPECT_EQ(d.edges[1].covariance, g.edges[1].covariance);
  EXPECT_EQ(d.edges[1].range, 4.5);
  EXPECT_EQ(d.edges[1].range_error, 0.1);
  EXPECT_EQ(encodePoseGraph(d), bytes);
}

TEST(Ros1Serialization, EveryTruncationIsADecodeError) {
  const auto bytes = encodePoseGraph(sampleGraph());
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    try {
      decodePoseGraph(bytes.data(), n);
      ADD_FAILURE() << "a message cut to " << n << " bytes decoded";
    } catch (const DecodeError& e) {
      EXPECT_NE(std::string(e.what()).find("PoseGraph."), std::string::npos) << e.what();
    }
  }
}

TEST(Ros1Serialization, NamesTheFieldWhereTheMessageEnds) {
  // A cut that the array-length check cannot see (a long string): the field where the bytes run out is named.
  PoseGraph g = sampleGraph();
  g.nodes[2].id = std::string(2000, 'x');
  const auto bytes = encodePoseGraph(g);
  const std::size_t cut = 21 + 1 + 4 + 2 * (21 + 8 + 4 + 56 + 288) + 21 + 8 + 4 + 1000;  // inside nodes[2].ID
  try {
    decodePoseGraph(bytes.data(), cut);
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_EQ(std::string(e.what()), "PoseGraph.nodes[2].ID at byte " + std::to_string(cut - 1000) +
                                         ": message ends (needs 2000 bytes, 1000 left)");
  }
  // Otherwise the array length is refused before anything is read.
  try {
    decodePoseGraph(bytes.data(), bytes.size() - 10);
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("PoseGraph.edges length at byte"), std::string::npos) << e.what();
  }
}

TEST(Ros1Serialization, RejectsTrailingBytesBadBoolAndHugeArrays) {
  auto bytes = encodePoseGraph(sampleGraph());
  auto longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(decodePoseGraph(longer), DecodeError);

  auto bad_bool = bytes;
  bad_bool[21] = 2;  // after the header (4 + 8 + 4 + "world")
  try {
    decodePoseGraph(bad_bool);
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("incremental"), std::string::npos) << e.what();
  }

  auto huge = bytes;
  const std::uint32_t n = 0xFFFFFFF0u;  // node count far beyond the bytes: refused before allocating
  std::memcpy(&huge[22], &n, 4);
  try {
    decodePoseGraph(huge);
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes length"), std::string::npos) << e.what();
  }
}

TEST(Ros1Serialization, EmptyGraph) {
  PoseGraph g;
  const PoseGraph d = decodePoseGraph(encodePoseGraph(g));
  EXPECT_TRUE(d.nodes.empty());
  EXPECT_TRUE(d.edges.empty());
  EXPECT_TRUE(d.incremental);
}

TEST(Ros1Serialization, MutatedBytesDecodeOrThrowNeverCrash) {
  const auto bytes = encodePoseGraph(sampleGraph());
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
  std::uniform_int_distribution<int> value(0, 255), count(1, 8);
  std::size_t decoded = 0, refused = 0;
  for (int run = 0; run < 3000; ++run) {
    auto mutated = bytes;
    for (int k = count(rng); k > 0; --k) mutated[at(rng)] = static_cast<std::uint8_t>(value(rng));
    if (run % 3 == 0) mutated.resize(at(rng));
    try {
      decodePoseGraph(mutated);
      ++decoded;
    } catch (const DecodeError&) { ++refused; }
  }
  EXPECT_EQ(decoded + refused, 3000u);
  EXPECT_GT(refused, 0u);
  EXPECT_GT(decoded, 0u);  // flipped numbers are still a valid layout
}
