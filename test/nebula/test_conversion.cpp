// cosmo_nebula's conversion on dataset folders in the distributed layout, written by the test: ROS 1 bags with
// pose_graph_msgs/PoseGraph messages (full definition and md5sum in the connection header), result.g2o and
// g2o_pcd/, for 2-4 robots with known truth and a known set of wrong loop closures.
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>

#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/nebula/message_definition.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"
#include "cosmo/ros/nebula_dataset.hpp"
#include "cosmo/ros/nebula_synthetic_folder.hpp"
#include "cosmo/common/whole_file.hpp"
#include "../support/run_command.hpp"

using namespace cosmo;
using namespace cosmo::nebula;
namespace fs = std::filesystem;

namespace {

struct Fixture {
  fs::path dir;
  SyntheticTeam team;
  ~Fixture() { fs::remove_all(dir); }
};

std::unique_ptr<Fixture> writeFixture(const std::string& tag, const SyntheticTeamParams& params, std::uint64_t seed) {
  auto f = std::make_unique<Fixture>();
  f->dir = fs::temp_directory_path() / ("cosmo_nebula_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(f->dir);
  std::mt19937_64 rng(seed);
  f->team = makeSyntheticTeam(params, rng);
  ros_glue::writeNebulaFolder(f->dir.string(), f->team);
  return f;
}

ros_glue::NebulaConversion convert(const fs::path& dir, NoiseSource noise = NoiseSource::Recorded,
                                   bool from_g2o = false) {
  ros_glue::NebulaOptions o;
  o.dataset_dir = dir.string();
  o.from_g2o = from_g2o;
  o.params.name = "fixture";
  o.params.noise = noise;
  return ros_glue::convertNebulaDataset(o);
}

SyntheticTeamParams teamOf(std::size_t robots) {
  const std::vector<std::pair<std::string, char>> all{
      {"husky1", 'a'}, {"husky3", 'c'}, {"husky4", 'd'}, {"spot1", 'e'}};
  SyntheticTeamParams p;
  p.robots.assign(all.begin(), all.begin() + static_cast<long>(robots));
  return p;
}

/// The source edge (key_from, key_to) a stored loop closure came from, whichever way it is stored.
bool isWrong(const SyntheticTeam& team, const jrl::Factor& f) {
  return team.wrong_closures.count({f.keys[0], f.keys[1]}) || team.wrong_closures.count({f.keys[1], f.keys[0]});
}

void expectLabelsMatchTruth(const SyntheticTeam& team, const jrl::Dataset& ds) {
  std::size_t closures = 0, wrong = 0;
  for (char r : ds.robots) {
    const auto& entries = ds.measurements.at(r);
    for (std::size_t e = 0; e < entries.size(); ++e)
      for (std::size_t m = 0; m < entries[e].factors.size(); ++m) {
        const jrl::Factor& f = entries[e].factors[m];
        const bool odometry = f.isBetweenPose3() && jrl::robotOf(f.keys[0]) == jrl::robotOf(f.keys[1]) &&
                              jrl::indexOf(f.keys[1]) == jrl::indexOf(f.keys[0]) + 1 && m == 0;
        if (!f.isBetweenPose3() || odometry) continue;
        ++closures;
        const jrl::FactorId id{e, m};
        EXPECT_TRUE(ds.potential_outliers->at(r).count(id));
        EXPECT_EQ(ds.outliers->at(r).count(id) == 1, isWrong(team, f))
            << r << " entry " << e << " measurement " << m << ": " << jrl::keyName(f.keys[0]) << " -> "
            << jrl::keyName(f.keys[1]);
        wrong += isWrong(team, f);
      }
  }
  EXPECT_EQ(closures, team.intra + team.inter);
  EXPECT_EQ(wrong, team.wrong_closures.size());
  EXPECT_GT(wrong, 0u);
}

}  // namespace

TEST(NebulaConversion, BagsOfTwoToFourRobotsGiveValidLabelledJrl) {
  for (std::size_t robots = 2; robots <= 4; ++robots) {
    SCOPED_TRACE(std::to_string(robots) + " robots");
    const auto f = writeFixture("team" + std::to_string(robots), teamOf(robots), 10 + robots);
    const auto c = convert(f->dir);
    const jrl::Dataset& ds = c.dataset;
    const auto violations = jrl::validate(ds);
    EXPECT_TRUE(violations.empty()) << violations.front().str();
    ASSERT_EQ(ds.robots.size(), robots);
    for (const auto& [ch, name] : f->team.names) {
      EXPECT_EQ(c.graph.robots.at(ch).name, name);
      // One entry per pose, stamped with its node's stamp; the odometry chain complete.
      const auto& entries = ds.measurements.at(ch);
      ASSERT_EQ(entries.size(), f->team.stamps.at(ch).size());
      for (std::size_t i = 0; i < entries.size(); ++i) {
        EXPECT_EQ(entries[i].stamp, f->team.stamps.at(ch)[i]);
        const jrl::Factor& first = entries[i].factors.at(0);
        if (i == 0) {
          EXPECT_TRUE(first.isPriorPose3());
          EXPECT_TRUE(first.pose3().isApprox(f->team.truth.at(jrl::symbol(ch, 0)), 1e-12));
        } else {
          EXPECT_EQ(first.keys, (std::vector<jrl::Key>{jrl::symbol(ch, i - 1), jrl::symbol(ch, i)}));
        }
      }
      // Groundtruth is the reference; initialization starts there and dead-reckons.
      EXPECT_TRUE(
          jrl::pose3At(ds.groundtruth->at(ch), jrl::symbol(ch, 7)).isApprox(f->team.truth.at(jrl::symbol(ch, 7))));
      EXPECT_TRUE(
          jrl::pose3At(ds.initialization->at(ch), jrl::symbol(ch, 0)).isApprox(f->team.truth.at(jrl::symbol(ch, 0))));
    }
    expectLabelsMatchTruth(f->team, ds);
    EXPECT_EQ(c.report.intra, f->team.intra);
    EXPECT_EQ(c.report.inter, f->team.inter);
    // Every other edge type counted, nothing dropped silently.
    for (const auto& [type, n] : f->team.other_edges) EXPECT_EQ(c.graph.ignored_edges.at(type), n) << type;
    EXPECT_EQ(c.graph.warnings.total(), 0u) << c.graph.warnings.str();
    EXPECT_GT(c.graph.repeated_nodes, 0u);
    for (const auto& t : c.topics) EXPECT_TRUE(t.md5_matches);
  }
}

TEST(NebulaConversion, RecordedCovariancesAreReorderedRotationFirst) {
  const auto f = writeFixture("cov", teamOf(2), 5);
  const auto c = convert(f->dir);
  // Odometry is never inverted: its covariance is the recorded one, rotation first, to the bit.
  const jrl::Factor& odo = c.dataset.measurements.at('c')[3].factors[0];
  EXPECT_EQ(odo.covarianceMatrix(), Eigen::MatrixXd(f->team.odometry_covariance));
  // And it differs from the same numbers read translation first: the order matters.
  ros_glue::NebulaOptions o;
  o.dataset_dir = f->dir.string();
  o.covariance_order = CovarianceOrder::RotationFirst;
  const auto wrong_order = ros_glue::convertNebulaDataset(o);
  EXPECT_EQ(wrong_order.dataset.measurements.at('c')[3].factors[0].covarianceMatrix(),
            Eigen::MatrixXd(swapTranslationRotation(f->team.odometry_covariance)));
}

TEST(NebulaConversion, EstimatedNoiseModelsLabelTheWrongClosures) {
  const auto f = writeFixture("estimated", teamOf(3), 21);
  const auto c = convert(f->dir, NoiseSource::Estimated);
  EXPECT_TRUE(jrl::validate(c.dataset).empty());
  ASSERT_TRUE(c.report.estimate);
  EXPECT_EQ(c.report.estimate->loop_closure.rejected, f->team.wrong_closures.size());
  // The estimate recovers the noise's law: rotation within sampling error; translation at least the recorded
  // one (closures stored inverted carry rotation noise times their length into translation).
  const Matrix6& q = c.report.estimate->models.loop_closure;
  const Matrix6& law = f->team.loop_closure_covariance;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::sqrt(q(i, i)), std::sqrt(law(i, i)), 0.5 * std::sqrt(law(i, i))) << i;
  for (int i = 3; i < 6; ++i) {
    EXPECT_GT(std::sqrt(q(i, i)), 0.5 * std::sqrt(law(i, i))) << i;
    EXPECT_LT(std::sqrt(q(i, i)), 4.0 * std::sqrt(law(i, i))) << i;
  }
  expectLabelsMatchTruth(f->team, c.dataset);
  // One constant model per kind.
  EXPECT_EQ(c.dataset.measurements.at('d')[5].factors[0].covarianceMatrix(),
            Eigen::MatrixXd(c.report.models->odometry));
}

TEST(NebulaConversion, G2oFoldersGiveTheSameGraphWithIndexStamps) {
  const auto f = writeFixture("g2o", teamOf(2), 8);
  const auto bags = convert(f->dir);
  const auto g2o = convert(f->dir, NoiseSource::Recorded, true);
  EXPECT_TRUE(jrl::validate(g2o.dataset).empty());
  EXPECT_EQ(g2o.report.intra + g2o.report.inter, bags.report.intra + bags.report.inter);
  EXPECT_EQ(g2o.dataset.measurements.at('c')[4].stamp, 4'000'000'000ull);
  EXPECT_EQ(g2o.graph.robots.at('c').name, "");
  expectLabelsMatchTruth(f->team, g2o.dataset);
}

TEST(NebulaConversion, TruncatedMessageNamesBagTopicAndField) {
  const auto f = writeFixture("truncated", teamOf(2), 3);
  {
    ros_glue::PoseGraphBagWriter bag((f->dir / "rosbag" / "husky3.bag").string());
    const std::string topic = "/husky3/lamp/pose_graph_incremental";
    auto bytes = encodePoseGraph(f->team.messages.at("husky3")[0]);
    bag.write(topic, f->team.messages.at("husky3")[0]);
    bytes.resize(bytes.size() - 100);
    bag.writeBytes(topic, f->team.stamps.at('c')[10], bytes);
  }
  try {
    convert(f->dir);
    FAIL() << "a truncated message was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rosbag/husky3.bag /husky3/lamp/pose_graph_incremental #1: PoseGraph.edges length at byte"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("needs at least"), std::string::npos) << what;
  }
}

TEST(NebulaConversion, AnotherMd5sumIsReported) {
  const auto f = writeFixture("md5", teamOf(2), 4);
  {
    ros_glue::PoseGraphBagWriter bag((f->dir / "rosbag" / "husky3.bag").string(), "0123456789abcdef0123456789abcdef");
    for (const auto& m : f->team.messages.at("husky3")) bag.write("/husky3/lamp/pose_graph_incremental", m);
  }
  const auto c = convert(f->dir);
  std::size_t mismatched = 0;
  for (const auto& t : c.topics) mismatched += !t.md5_matches;
  EXPECT_EQ(mismatched, 1u);
  // Same layout: decoded all the same. A layout that differs fails naming both md5sums.
  {
    ros_glue::PoseGraphBagWriter bag((f->dir / "rosbag" / "husky3.bag").string(), "0123456789abcdef0123456789abcdef");
    auto bytes = encodePoseGraph(f->team.messages.at("husky3")[0]);
    bytes.push_back(1);
    bag.writeBytes("/husky3/lamp/pose_graph_incremental", f->team.stamps.at('c')[3], bytes);
  }
  try {
    convert(f->dir);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the connection's md5sum 0123456789abcdef0123456789abcdef is not"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(poseGraphMd5()), std::string::npos) << e.what();
  }
}

TEST(NebulaConversion, WrittenBagsCarryTheDefinitionAndMd5sum) {
  const auto f = writeFixture("header", teamOf(2), 6);
  rosbag::Bag bag((f->dir / "rosbag" / "husky3.bag").string());
  rosbag::View view(bag);
  ASSERT_EQ(view.getConnections().size(), 1u);
  const rosbag::ConnectionInfo* c = view.getConnections()[0];
  EXPECT_EQ(c->topic, "/husky3/lamp/pose_graph_incremental");
  EXPECT_EQ(c->datatype, "pose_graph_msgs/PoseGraph");
  EXPECT_EQ(c->md5sum, "7bcbcc6a764387d0d037d9ff4f38d1b9");
  EXPECT_NE(c->msg_def.find("MSG: pose_graph_msgs/PoseGraphEdge"), std::string::npos);
  EXPECT_EQ(view.size(), f->team.messages.at("husky3").size());
}

TEST(NebulaConversion, CollidingRobotCharacterIsAnError) {
  auto params = teamOf(2);
  const auto f = writeFixture("collide", params, 7);
  // A third robot whose keys use husky3's character.
  SyntheticTeamParams other = params;
  other.robots = {{"spot1", 'c'}};
  std::mt19937_64 rng(99);
  const SyntheticTeam spot = makeSyntheticTeam(other, rng);
  ros_glue::PoseGraphBagWriter bag((f->dir / "rosbag" / "spot1.bag").string());
  for (const auto& m : spot.messages.at("spot1")) bag.write("/spot1/lamp/pose_graph_incremental", m);
  bag.close();
  try {
    convert(f->dir);
    FAIL();
  } catch (const GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("robot character 'c' is used by two robots: husky3"), std::string::npos)
        << e.what();
  }
}

TEST(NebulaConversion, MissingReferenceAndFoldersAreClearErrors) {
  const auto f = writeFixture("missing", teamOf(2), 9);
  fs::remove(f->dir / "ground_truth" / "result.g2o");
  EXPECT_THROW(
      {
        try {
          convert(f->dir);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("result.g2o: reference solution missing"), std::string::npos);
          throw;
        }
      },
      std::runtime_error);
  EXPECT_THROW(convert(f->dir / "nope"), std::runtime_error);
}

namespace {

std::string nebulaTool() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path tool = self.parent_path() / "cosmo_nebula";
  return !ec && fs::exists(tool) ? tool.string() : "";
}

/// Runs cosmo_nebula with `args`; returns {exit code, stdout + stderr}.
std::pair<int, std::string> runTool(const std::string& args) {
  const cosmo::test::CommandRun r = cosmo::test::runCommand("'" + nebulaTool() + "' " + args + " 2>&1");
  return {r.status, r.output};
}

}  // namespace

TEST(NebulaTool, WritesAValidJrlWithStatsMetadataAndModels) {
  if (nebulaTool().empty()) GTEST_SKIP() << "cosmo_nebula is not built beside this test";
  const auto f = writeFixture("tool", teamOf(3), 31);
  const fs::path out = f->dir / "out";
  const auto [code, text] =
      runTool("'" + f->dir.string() + "' --out '" + out.string() + "' --name tunnel --estimate-noise-models");
  ASSERT_EQ(code, 0) << text;
  EXPECT_NE(text.find("robots: a=husky1 (80 poses) c=husky3 (80 poses) d=husky4 (80 poses)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("ignored edges: ARTIFACT"), std::string::npos) << text;
  const jrl::Dataset ds = jrl::readJrl((out / "tunnel.jrl").string());
  EXPECT_TRUE(jrl::validate(ds).empty());
  expectLabelsMatchTruth(f->team, ds);
  EXPECT_NE(
      cosmo::readWholeFileOrEmpty(out / "tunnel.nebula.yaml").find("robots:\n  a: husky1\n  c: husky3\n  d: husky4\n"),
      std::string::npos)
      << cosmo::readWholeFileOrEmpty(out / "tunnel.nebula.yaml");
  EXPECT_NE(cosmo::readWholeFileOrEmpty(out / "tunnel.stats.txt").find("IRLC"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "tunnel.stats.json"));
  // The estimated models, given back, reproduce the same file.
  const auto again = runTool("'" + f->dir.string() + "' --out '" + (f->dir / "out2").string() +
                             "' --name tunnel --noise-models '" + (out / "tunnel.noise_models.yaml").string() + "'");
  ASSERT_EQ(again.first, 0) << again.second;
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(f->dir / "out2" / "tunnel.jrl"),
            cosmo::readWholeFileOrEmpty(out / "tunnel.jrl"));
}

TEST(NebulaTool, BrokenInputExitsOneAndWritesNothing) {
  if (nebulaTool().empty()) GTEST_SKIP() << "cosmo_nebula is not built beside this test";
  const auto f = writeFixture("toolbad", teamOf(2), 32);
  fs::remove(f->dir / "ground_truth" / "result.g2o");
  const fs::path out = f->dir / "out";
  const auto [code, text] = runTool("'" + f->dir.string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(code, 1);
  EXPECT_NE(text.find("result.g2o: reference solution missing"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(runTool("--bogus").first, 2);
}
