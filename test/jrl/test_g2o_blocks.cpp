// The g2o export as a distributed (DPGO-style) solver loads it: one global graph whose vertex ids 0..N-1 are split
// into one contiguous block per robot by OUT.blocks.csv, odometry edges i -> i+1 inside a block, loop closures
// anywhere (across blocks for inter-robot ones), and OUT.ids.csv naming the robot, JRL key and stamp of each id.
// On the tiny example of jrl.md §12, a synthetic three-robot dataset and, when ../shared exists, the reference file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <unistd.h>

#include "cosmo/common/shared_data.hpp"
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

namespace {

fs::path tempDir(const std::string& name) { return jrl_test::tempDir("g2o_blocks_" + name); }

/// A CSV line's fields (an empty last one after a trailing comma).
std::vector<std::string> csvFields(const std::string& line) {
  auto out = jrl_test::splitBy(line, ',');
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// What a DPGO-style reader takes from the files: the global graph and, per robot, its block of ids; each edge
/// classified as odometry (i -> i+1 inside a block), a loop closure inside a block, or one across two blocks.
struct DpgoBlock {
  std::string robot;
  long first = 0, count = 0;
};
struct DpgoEdge {
  long a = 0, b = 0;
  std::size_t block_a = 0, block_b = 0;
  bool odometry = false;
};
struct DpgoGraph {
  std::vector<long> vertex_ids;  ///< in file order
  std::map<long, Pose3> vertices;
  std::vector<DpgoBlock> blocks;
  std::vector<DpgoEdge> edges;  ///< in file order

  std::size_t blockOf(long id) const {
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (id >= blocks[i].first && id < blocks[i].first + blocks[i].count) return i;
    ADD_FAILURE() << "vertex " << id << " in no block";
    return blocks.size();
  }
};

DpgoGraph readDpgo(const std::string& g2o, const std::string& blocks_csv) {
  DpgoGraph g;
  std::ifstream blocks(blocks_csv);
  std::string line;
  std::getline(blocks, line);
  EXPECT_EQ(line, "robot,first_id,count");
  while (std::getline(blocks, line)) {
    const auto f = csvFields(line);
    EXPECT_EQ(f.size(), 3u) << line;
    if (f.size() == 3) g.blocks.push_back({f[0], std::stol(f[1]), std::stol(f[2])});
  }
  std::ifstream in(g2o);
  std::vector<std::pair<long, long>> edge_ids;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "VERTEX_SE3:QUAT") {
      long id;
      double x, y, z, qx, qy, qz, qw;
      ls >> id >> x >> y >> z >> qx >> qy >> qz >> qw;
      EXPECT_TRUE(ls) << line;
      g.vertex_ids.push_back(id);
      g.vertices[id] = makePose({x, y, z}, Eigen::Quaterniond(qw, qx, qy, qz));
    } else if (tag == "EDGE_SE3:QUAT") {
      long a, b;
      ls >> a >> b;
      EXPECT_TRUE(ls) << line;
      edge_ids.emplace_back(a, b);
    } else {
      EXPECT_EQ(tag.substr(0, 1), "#") << line;
    }
  }
  for (const auto& [a, b] : edge_ids) {
    DpgoEdge e{a, b, g.blockOf(a), g.blockOf(b), false};
    e.odometry = e.block_a == e.block_b && b == a + 1;
    g.edges.push_back(e);
  }
  return g;
}

/// Exports `d` into `dir` and checks what a DPGO-style reader relies on.
void expectDpgoLayout(const Dataset& d, const fs::path& dir) {
  const std::string path = (dir / "graph.g2o").string();
  const auto written = exportG2o(d, path);
  ASSERT_EQ(written,
            (std::vector<std::string>{path, (dir / "graph.blocks.csv").string(), (dir / "graph.ids.csv").string()}));
  const DpgoGraph g = readDpgo(path, written[1]);
  const PoseGraph pg = poseGraph(d);
  const long n = static_cast<long>(pg.initialization.size());

  // Ids 0..N-1 in order, cut into contiguous blocks that cover them, one per robot, in robot (key) order.
  ASSERT_EQ(static_cast<long>(g.vertex_ids.size()), n);
  for (long i = 0; i < n; ++i) EXPECT_EQ(g.vertex_ids[i], i);
  ASSERT_FALSE(g.blocks.empty());
  long next = 0;
  for (std::size_t i = 0; i < g.blocks.size(); ++i) {
    EXPECT_EQ(g.blocks[i].first, next) << g.blocks[i].robot;
    EXPECT_GT(g.blocks[i].count, 0) << g.blocks[i].robot;
    EXPECT_EQ(g.blocks[i].robot.size(), 1u);
    if (i > 0) { EXPECT_LT(g.blocks[i - 1].robot, g.blocks[i].robot); }
    next += g.blocks[i].count;
  }
  EXPECT_EQ(next, n);

  // The edges in the pose graph's order (priors not written): odometry i -> i+1 inside one block, every block's
  // chain unbroken; intra-robot loop closures inside a block; inter-robot ones across two.
  std::size_t e = 0;
  std::vector<long> odometry_per_block(g.blocks.size(), 0);
  for (const PoseFactor& f : pg.factors) {
    if (f.kind == FactorKind::Prior) continue;
    ASSERT_LT(e, g.edges.size());
    const DpgoEdge& edge = g.edges[e++];
    if (f.kind == FactorKind::Odometry) {
      EXPECT_TRUE(edge.odometry) << edge.a << " -> " << edge.b;
      if (edge.odometry) ++odometry_per_block[edge.block_a];
    } else if (f.kind == FactorKind::LoopClosure) {
      EXPECT_EQ(edge.block_a, edge.block_b) << edge.a << " -> " << edge.b;
    } else {
      EXPECT_NE(edge.block_a, edge.block_b) << edge.a << " -> " << edge.b;
    }
  }
  EXPECT_EQ(e, g.edges.size());
  for (std::size_t i = 0; i < g.blocks.size(); ++i)
    EXPECT_EQ(odometry_per_block[i], g.blocks[i].count - 1) << g.blocks[i].robot;
  if (d.robots.size() > 1) {
    std::size_t across = 0;
    for (const DpgoEdge& edge : g.edges) across += edge.block_a != edge.block_b;
    EXPECT_GT(across, 0u);
  }

  // ids.csv: every vertex, in id order, with its block's robot, the JRL key whose initialization it holds and the
  // stamp of the pose.
  std::ifstream ids(written[2]);
  std::string line;
  std::getline(ids, line);
  EXPECT_EQ(line, "g2o_id,robot,jrl_key,stamp");
  long rows = 0;
  while (std::getline(ids, line)) {
    const auto c = csvFields(line);
    ASSERT_EQ(c.size(), 4u) << line;
    const long id = std::stol(c[0]);
    EXPECT_EQ(id, rows);
    const Key key = std::stoull(c[2]);
    EXPECT_EQ(c[1], std::string(1, robotOf(key))) << line;
    EXPECT_EQ(c[1], g.blocks[g.blockOf(id)].robot) << line;
    ASSERT_TRUE(pg.initialization.count(key)) << line;
    EXPECT_LT(logSE3(g.vertices.at(id).inverse() * pg.initialization.at(key)).norm(), 1e-12) << line;
    ASSERT_TRUE(pg.stamps.count(key)) << line;
    EXPECT_EQ(std::stoull(c[3]), pg.stamps.at(key)) << line;
    ++rows;
  }
  EXPECT_EQ(rows, n);

  // Deterministic: a second export gives the same bytes.
  const auto again = exportG2o(d, (dir / "again.g2o").string());
  for (std::size_t i = 0; i < written.size(); ++i)
    EXPECT_EQ(cosmo::readWholeFileOrEmpty(again[i]), cosmo::readWholeFileOrEmpty(written[i])) << written[i];
}

}  // namespace

TEST(G2oBlocks, FilesBesideTheGraph) {
  EXPECT_EQ(g2oBlocksPath("out/graph.g2o"), "out/graph.blocks.csv");
  EXPECT_EQ(g2oIdsPath("out/graph.g2o"), "out/graph.ids.csv");
  EXPECT_EQ(g2oBlocksPath("graph"), "graph.blocks.csv");
  EXPECT_EQ(g2oIdsPath("graph.txt"), "graph.txt.ids.csv");
}

TEST(G2oBlocks, TinyExample) {
  const fs::path dir = tempDir("tiny");
  expectDpgoLayout(readJrl(kTiny), dir);
  // a0 a1 a2 b0 b1 (jrl.md §12).
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(dir / "graph.blocks.csv"), "robot,first_id,count\na,0,3\nb,3,2\n");
  std::ifstream ids(dir / "graph.ids.csv");
  std::string header, first;
  std::getline(ids, header);
  std::getline(ids, first);
  EXPECT_EQ(first, "0,a,6989586621679009792,1700000000000000000");
  fs::remove_all(dir);
}

TEST(G2oBlocks, SyntheticThreeRobots) {
  std::mt19937_64 rng(5);
  SyntheticParams p;
  p.poses_per_robot = 60;
  const fs::path dir = tempDir("synthetic");
  expectDpgoLayout(makeSyntheticDataset(p, rng), dir);
  fs::remove_all(dir);
}

TEST(G2oBlocks, ReferenceFile) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const fs::path dir = tempDir("reference");
  expectDpgoLayout(readJrl(*path), dir);
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(dir / "graph.blocks.csv"),
            "robot,first_id,count\na,0,351\nb,351,535\nc,886,139\n");
  fs::remove_all(dir);
}
