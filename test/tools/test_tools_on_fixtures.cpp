// The command-line tools as a user runs them (found beside this test binary), on sequences that
// `cosmo_simulate --layout mcd | cu-multi` writes in the real datasets' layouts: `cosmo_check` reports each trial
// (bag, topic, stamp convention, reference span) and exits 0; `cosmo_generate` writes a labelled JRL whose every
// keyframe carries the simulator's true LiDAR pose as its groundtruth (1 mm, 0.01 deg), byte for byte the same
// with the scan cache off, cold (being filled) and warm; a wrong topic makes cosmo_check exit 1 naming the topics
// the bag has. The sequences are small (16 x 256 sweeps, two robots, about 26 s each): seconds per tool run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "cosmo/jrl/io.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/trial_reference.hpp"
#include "cosmo/common/whole_file.hpp"
#include "../support/run_command.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

namespace {

using cosmo::test::binDir;

using ToolRun = cosmo::test::CommandRun;  ///< output: stdout and stderr

/// Runs `tool args` with `env` (e.g. "COSMO_SCAN_CACHE=off") in front.
ToolRun runTool(const std::string& tool, const std::string& args, const std::string& env) {
  return cosmo::test::runCommand("env " + env + " '" + (binDir() / tool).string() + "' " + args + " 2>&1");
}

/// Two robots on a one-block campus: a walker along one side (27 s), an ATV along two (26 s).
constexpr const char* kSimConfig = R"(name: tools_fixture
source: synthetic
environment: synthetic
seed: 5
anchor: a
time_offset_sigma: 2.0
world:
  blocks_x: 1
  blocks_y: 1
  block_min: 30.0
  block_max: 32.0
  outer_ring: 30.0
  terrain_margin: 40.0
lidar:
  model: os1_64
  beams: 16
  columns: 256
trials:
  - robot: a
    name: walker
    platform: handheld
    length: 10.0
    start_node: 0
    return_fraction: 1.0
  - robot: b
    name: quad
    platform: atv
    length: 40.0
    start_node: 3
    return_fraction: 1.0
)";

/// One sequence written by cosmo_simulate in a layout, and the simulator's truth for it.
struct Fixture {
  fs::path dir, sequence;
  sim::SimulationParams params;
  sim::PlannedSequence plan;

  Fixture(const fs::path& root, const std::string& layout) : dir(root / layout) {
    fs::create_directories(dir);
    const fs::path sim_config = root / "tools_fixture.sim.yaml";
    std::ofstream(sim_config) << kSimConfig;
    const ToolRun r = runTool(
        "cosmo_simulate",
        "--config '" + sim_config.string() + "' --layout " + layout + " --no-cache --out '" + dir.string() + "'",
        "COSMO_SCAN_CACHE=off");
    if (r.status != 0) throw std::runtime_error("cosmo_simulate failed:\n" + r.output);
    sequence = dir / "tools_fixture.yaml";
    params = sim::SimulationParams::load(sim_config.string());
    if (layout == "cu-multi") params.lidar.rate_hz = 20.0;  // as cosmo_simulate plans it
    plan = sim::planSequence(params);
  }
  /// The true LiDAR pose of `robot` at recorded time `stamp`.
  Pose3 trueLidarPose(char robot, StampNs stamp) const {
    for (const auto& t : plan.trials)
      if (t.params.robot == std::string(1, robot)) return t.body.atClamped(stamp) * t.params.extrinsicPose();
    throw std::runtime_error(std::string("no trial of robot ") + robot);
  }
};

class ToolsOnFixtures : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("cosmo_tools_fixtures_" + std::to_string(::getpid())));
    fs::create_directories(*root_);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete mcd_;
    delete cu_;
    delete root_;
  }
  static const Fixture& mcd() {
    if (!mcd_) mcd_ = new Fixture(*root_, "mcd");
    return *mcd_;
  }
  static const Fixture& cuMulti() {
    if (!cu_) cu_ = new Fixture(*root_, "cu-multi");
    return *cu_;
  }
  static fs::path root() { return *root_; }

  /// cosmo_generate on `f` into `out` (reference odometry unless `loam`); the JRL's path.
  static fs::path generate(const Fixture& f, const fs::path& out, const std::string& cache, bool loam = false) {
    const ToolRun r = runTool(
        "cosmo_generate",
        "'" + f.sequence.string() + "' --out '" + out.string() + "' --quiet" + (loam ? "" : " --odometry reference"),
        "COSMO_SCAN_CACHE='" + cache + "'");
    EXPECT_EQ(r.status, 0) << r.output;
    return out / "tools_fixture_wifi.jrl";
  }

  /// Every keyframe of the JRL has a groundtruth equal to the simulator's true LiDAR pose, minus the sequence's
  /// reference offset (which the dataset's .recorder.yaml states).
  static void expectTrueGroundtruth(const Fixture& f, const fs::path& jrl_path, const Eigen::Vector3d& frame_shift) {
    const jrl::Dataset ds = jrl::readJrl(jrl_path.string());
    ASSERT_TRUE(ds.groundtruth.has_value()) << "the JRL is not labelled";
    ASSERT_TRUE(ds.outliers.has_value()) << "the JRL has no outlier labels";
    const sequence::SequenceConfig config = sequence::SequenceConfig::load(f.sequence.string());
    const sequence::SequenceTiming timing = trials::synchronizeSequence(config);
    const Eigen::Vector3d offset = trials::sequenceReferenceOffset(config);
    char line[160];
    std::snprintf(line, sizeof line, "reference_offset: [%.3f, %.3f, %.3f]", offset.x(), offset.y(), offset.z());
    std::string recorder_yaml = jrl_path.string();
    recorder_yaml.replace(recorder_yaml.size() - 4, 4, ".recorder.yaml");
    EXPECT_NE(cosmo::readWholeFileOrEmpty(recorder_yaml).find(line), std::string::npos) << line;
    ASSERT_EQ(ds.robots.size(), 2u);
    for (const char r : ds.robots) {
      const auto& gt = ds.groundtruth->at(r);
      const auto& entries = ds.measurements.at(r);
      std::size_t checked = 0;
      for (std::size_t i = 0; gt.count(jrl::symbol(r, i)); ++i, ++checked) {
        ASSERT_LT(i, entries.size());
        const Pose3 truth = f.trueLidarPose(r, timing.of(r).toRecorded(entries[i].stamp));
        const Pose3 written = jrl::pose3At(gt, jrl::symbol(r, i));
        EXPECT_LT((written.translation() - (truth.translation() + frame_shift - offset)).norm(), 1e-3)
            << "robot " << r << " keyframe " << i;
        EXPECT_LT(Eigen::AngleAxisd(truth.linear().transpose() * written.linear()).angle() * 180.0 / M_PI, 0.01)
            << "robot " << r << " keyframe " << i;
      }
      EXPECT_GE(checked, 3u) << "robot " << r;
    }
  }

 private:
  static fs::path* root_;
  static Fixture* mcd_;
  static Fixture* cu_;
};

fs::path* ToolsOnFixtures::root_ = nullptr;
Fixture* ToolsOnFixtures::mcd_ = nullptr;
Fixture* ToolsOnFixtures::cu_ = nullptr;

/// The line cosmo_check prints for `robot`.
std::string checkLine(const std::string& output, char robot) {
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(std::string("robot ") + robot + " ", 0) == 0) return line;
  return "";
}

}  // namespace

TEST_F(ToolsOnFixtures, CheckReportsMcdTrials) {
  const Fixture& f = mcd();
  const ToolRun r = runTool("cosmo_check", "'" + f.sequence.string() + "'", "COSMO_SCAN_CACHE=off");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char robot : {'a', 'b'}) {
    const std::string line = checkLine(r.output, robot);
    SCOPED_TRACE(line);
    EXPECT_NE(line.find("bag ok"), std::string::npos);
    EXPECT_NE(line.find("topic /os_cloud_node/points ("), std::string::npos);
    EXPECT_NE(line.find("10.0 Hz, stamp end"), std::string::npos);
    EXPECT_NE(line.find("fields x:float32@0 y:float32@4 z:float32@8"), std::string::npos);
    EXPECT_NE(line.find("ring:uint8@"), std::string::npos);
    // MCD's pose_inW.csv: 10 Hz, from 1 s after the first scan to 0.5 s before the last one
    EXPECT_NE(line.find("reference 10.0 Hz"), std::string::npos);
    EXPECT_NE(line.find("(uncovered 1.0 s at the start, 0.5 s at the end)"), std::string::npos);
    EXPECT_EQ(line.find("extrinsic rotation 0.00 deg"), std::string::npos);  // MCD's T_body_lidar: ~180 deg
  }
  EXPECT_NE(r.output.find("ok: every trial has scans and a reference over them"), std::string::npos);
}

TEST_F(ToolsOnFixtures, CheckReportsCuMultiTrials) {
  const Fixture& f = cuMulti();
  const ToolRun r = runTool("cosmo_check", "'" + f.sequence.string() + "'", "COSMO_SCAN_CACHE=off");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char robot : {'a', 'b'}) {
    const std::string line = checkLine(r.output, robot);
    SCOPED_TRACE(line);
    const std::string n = robot == 'a' ? "1" : "2";
    EXPECT_NE(line.find("bag ok"), std::string::npos);
    EXPECT_NE(line.find("topic robot" + n + "/ouster/points ("), std::string::npos);
    EXPECT_NE(line.find("20.0 Hz, stamp start"), std::string::npos);
    EXPECT_NE(line.find("ring:uint16@"), std::string::npos);
    EXPECT_NE(line.find("reference 20.0 Hz"), std::string::npos);
    EXPECT_NE(line.find("(uncovered 0.0 s at the start"), std::string::npos);
  }
}

TEST_F(ToolsOnFixtures, CheckNamesTheTopicsOfABagWithoutTheConfiguredOne) {
  for (const Fixture* f : {&mcd(), &cuMulti()}) {
    std::string text = cosmo::readWholeFileOrEmpty(f->sequence);
    const std::string topic = f == &mcd() ? "/os_cloud_node/points" : "robot1/ouster/points";
    text.replace(text.find("topic: " + topic), 7 + topic.size(), "topic: /wrong/points");
    const fs::path bad = f->dir / "wrong_topic.yaml";
    std::ofstream(bad) << text;
    const ToolRun r = runTool("cosmo_check", "'" + bad.string() + "'", "COSMO_SCAN_CACHE=off");
    EXPECT_EQ(r.status, 1) << r.output;
    const std::string line = checkLine(r.output, 'a');
    EXPECT_NE(line.find("topic /wrong/points MISSING (the bag has: " + topic + " (sensor_msgs/"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("cannot produce a labelled dataset"), std::string::npos) << r.output;
    // cosmo_generate runs the same check first and stops
    const ToolRun g = runTool("cosmo_generate", "'" + bad.string() + "' --out '" + (root() / "bad").string() + "'",
                              "COSMO_SCAN_CACHE=off");
    EXPECT_EQ(g.status, 1) << g.output;
    EXPECT_FALSE(fs::exists(root() / "bad" / "tools_fixture_wifi.jrl"));
  }
}

TEST_F(ToolsOnFixtures, GenerateOnMcdLayoutWritesTheTrueGroundtruth) {
  const Fixture& f = mcd();
  expectTrueGroundtruth(f, generate(f, root() / "mcd_out", "off"), Eigen::Vector3d::Zero());
}

TEST_F(ToolsOnFixtures, GenerateOnCuMultiLayoutWritesTheTrueGroundtruth) {
  const Fixture& f = cuMulti();
  expectTrueGroundtruth(f, generate(f, root() / "cu_out", "off"), ros_glue::kSimulatedUtmOffset);
}

TEST_F(ToolsOnFixtures, JrlIsByteIdenticalWithoutWithAColdAndWithAWarmScanCache) {
  const Fixture& f = mcd();
  const fs::path cache = root() / "scan_cache";
  const std::string off = cosmo::readWholeFileOrEmpty(generate(f, root() / "cache_off", "off", true));
  const std::string cold = cosmo::readWholeFileOrEmpty(generate(f, root() / "cache_cold", cache.string(), true));
  std::size_t scans = 0, spans = 0;
  for (const auto& e : fs::directory_iterator(cache)) {
    scans += e.path().extension() == ".scans";
    spans += e.path().extension() == ".span";
  }
  EXPECT_EQ(scans, 2u) << "the cold run fills the cache: one file of scans per trial";
  EXPECT_EQ(spans, 2u) << "and one span per trial";
  const std::string warm = cosmo::readWholeFileOrEmpty(generate(f, root() / "cache_warm", cache.string(), true));
  ASSERT_GT(off.size(), 1000u);
  EXPECT_TRUE(off == cold) << "cache off and cold cache differ";
  EXPECT_TRUE(off == warm) << "cache off and warm cache differ";
}
