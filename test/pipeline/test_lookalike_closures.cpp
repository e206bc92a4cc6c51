// Outliers for honest reasons: in a campus whose street is lined with terraces of one repeated house (equal
// blocks, config/sim terrace_fraction), ScanContext proposes a place a block or two away and the registration
// aligns it convincingly. The gate accepts it; the reference says it is metres off; the chi-square labels with
// the demo's noise models mark it an outlier. Nothing is injected: every closure is one the front-end made.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "../support/synthetic_team.hpp"

using namespace cosmo;
using namespace cosmo::place_recognition;
using namespace cosmo::pipeline;
using namespace cosmo::sequence;

namespace {

/// An ATV along one straight street of four equal blocks whose sides are all terraces of the same house (the
/// CI campus otherwise), with the light 32 x 512 LiDAR of the pipeline tests.
test::SyntheticTrial terracedStreetTrial() {
  sim::SimulationParams params = sim::SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/ci.yaml");
  params.world.blocks_x = 4;
  params.world.blocks_y = 1;
  params.world.block_min = params.world.block_max = 50.0;
  params.world.terrace_fraction = 1.0;
  params.world.p_buildings = 1.0;
  params.world.p_row = params.world.p_park = params.world.p_parking = params.world.p_open = 0.0;
  params.lidar = sim::LidarModel::os1_32();
  params.lidar.columns = 512;
  sim::TrialParams t;
  t.robot = "a";
  t.name = "terraced_street";
  t.platform = "atv";
  t.start_node = 0;
  t.route.waypoints = {4};  // junctions 0..4 along the south street (row-major, 5 x 2 junctions)
  t.motion.start_still = 0.5;
  t.motion.end_still = 0.5;
  params.trials = {t};
  return test::simulateSingleTrial(params);
}

}  // namespace

TEST(LookalikeClosures, ATerracedStreetYieldsAcceptedWrongPlaceClosuresLabelledOutliers) {
  const test::SyntheticTrial trial = terracedStreetTrial();
  std::vector<TrialSpan> spans{{trial.robot, trial.scans.front().stamp, trial.scans.back().stamp}};
  const SequenceTiming timing = SequenceTiming::synchronize(spans, trial.robot, 0.0, 1);
  std::map<char, Trajectory> refs{
      {trial.robot, toSensorReference(trial.body, trial.extrinsic, timing.of(trial.robot))}};
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
  params.noise = dataset::NoiseModels::load(defaultConfigDir() + "/noise_models/synthetic.yaml");
  TeamRun run("terraced_street", refs, params, 5, timing.start());
  std::map<char, std::unique_ptr<ScanSource>> sources;
  sources[trial.robot] = std::make_unique<VectorScanSource>(trial.scans);
  MergedScanStream stream(std::move(sources), timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) run.add(robot, frontend::OwnScan::of(scan));
  run.finish(timing.end());

  // The street is driven once: every loop closure the gate accepted is a place a block or more away.
  const dataset::MeasurementSets sets = dataset::collectMeasurements(run.recorder().build(), trial.robot);
  ASSERT_FALSE(sets.loop_closures.empty()) << "no accepted closure on the terraced street";
  std::size_t wrong = 0;
  for (const auto& m : sets.loop_closures) {
    const double error = (m.measurement.inverse(Eigen::Isometry) * m.truth).translation().norm();
    if (error <= 2.0) continue;
    ++wrong;
    EXPECT_TRUE(dataset::isOutlier(m.measurement, m.truth, params.noise.loop_closure))
        << "closure off by " << error << " m";
  }
  EXPECT_GE(wrong, 1u);
  std::printf("terraced street: %zu accepted loop closures, %zu of them off by > 2 m\n", sets.loop_closures.size(),
              wrong);
}
