// Simulated scans: ring/time fields, determinism, and points on the world's surfaces when transformed with
// the ground truth at each point's own time.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "cosmo/sim/material.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/world_generator.hpp"

using namespace cosmo;
using namespace cosmo::sim;

namespace {
SimulationParams smallParams() {
  SimulationParams p;
  p.name = "test";
  p.world.blocks_x = 2;
  p.world.blocks_y = 2;
  p.world.block_min = 50;
  p.world.block_max = 60;
  p.world.outer_ring = 30;
  p.world.terrain_margin = 60;
  TrialParams t;
  t.robot = "a";
  t.name = "t_a";
  t.platform = "atv";
  t.motion = MotionParams::preset("atv");
  t.length = 120;
  t.start_node = 0;
  p.trials.push_back(t);
  t.robot = "b";
  t.name = "t_b";
  t.platform = "handheld";
  t.motion = MotionParams::preset("handheld");
  t.length = 60;
  t.start_node = 4;
  p.trials.push_back(t);
  return p;
}

const PlannedSequence& plan() {
  static const PlannedSequence seq = planSequence(smallParams());
  return seq;
}
}  // namespace

TEST(ScanSimulator, RingAndTimeFields) {
  const auto& seq = plan();
  const auto& t = seq.trials[0];
  LidarModel lidar = LidarModel::os1_64();
  ScanSimulator sim(*seq.world, lidar);
  ASSERT_GT(t.scan_stamps.size(), 50u);
  const StampNs stamp = t.scan_stamps[40];
  const Scan s = sim.simulate(t.body, t.params.extrinsicPose(), stamp, 1);
  ASSERT_GT(s.size(), 20000u);
  ASSERT_TRUE(s.hasRing() && s.hasTime() && s.hasIntensity());
  EXPECT_EQ(s.stamp, stamp);
  const auto el = lidar.elevations();
  float t_min = 0, t_max = -1;
  for (std::size_t i = 0; i < s.size(); ++i) {
    ASSERT_LT(s.ring[i], 64);
    ASSERT_LE(s.time[i], 0.0f);
    ASSERT_GT(s.time[i], -0.1f);
    t_min = std::min(t_min, s.time[i]);
    t_max = std::max(t_max, s.time[i]);
    // The ring is the beam whose elevation the point has (points are in the sensor frame at their time).
    const Eigen::Vector3f& p = s.points[i];
    const double e = std::atan2(p.z(), std::hypot(p.x(), p.y()));
    ASSERT_NEAR(e, el[s.ring[i]], 0.004) << "point " << i;
    ASSERT_GE(p.norm(), lidar.min_range);
    ASSERT_LE(p.norm(), lidar.max_range);
    // Column from azimuth, time from column.
    const double az = std::atan2(p.y(), p.x());
    const double frac = std::remainder(M_PI - az, 2 * M_PI) / (2 * M_PI);
    const double col = std::fmod(frac + 1.0, 1.0) * lidar.columns;
    const double expected = lidar.columnTime(static_cast<int>(std::lround(col)) % lidar.columns);
    ASSERT_NEAR(s.time[i], expected, 0.5 / (lidar.columns * lidar.rate_hz) + 1e-6) << "point " << i;
  }
  EXPECT_NEAR(t_min, -0.1 + 0.1 / 1024, 1e-3);
  EXPECT_NEAR(t_max, 0.0, 1e-3);
  // Ring-major order, time increasing within a ring.
  for (std::size_t i = 1; i < s.size(); ++i) {
    ASSERT_GE(s.ring[i], s.ring[i - 1]);
    if (s.ring[i] == s.ring[i - 1]) { ASSERT_GT(s.time[i], s.time[i - 1]); }
  }
}

TEST(ScanSimulator, SameSeedSameBytesAnyThreadCount) {
  const auto& seq = plan();
  const auto& t = seq.trials[0];
  ScanSimulator sim(*seq.world, LidarModel::os1_64());
  const StampNs stamp = t.scan_stamps[30];
  Scan a, b, c;
  a = sim.simulate(t.body, t.params.extrinsicPose(), stamp, 42);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = sim.simulate(t.body, t.params.extrinsicPose(), stamp, 42);
  }
  c = sim.simulate(t.body, t.params.extrinsicPose(), stamp, 43);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(Eigen::Vector3f)));
  EXPECT_EQ(a.intensity, b.intensity);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.ring, b.ring);
  // Another seed: other noise.
  EXPECT_FALSE(a.size() == c.size() && std::memcmp(a.points.data(), c.points.data(), a.size() * 12) == 0);
  // Planning is deterministic too.
  const auto again = planSequence(smallParams());
  ASSERT_EQ(again.trials[0].body.size(), t.body.size());
  EXPECT_TRUE(again.trials[0].body.poses().back().pose.isApprox(t.body.poses().back().pose, 0.0));
}

TEST(ScanSimulator, DeskewedPointsLieOnSurfacesWithinNoise) {
  const auto& seq = plan();
  LidarModel lidar = LidarModel::os1_64();
  lidar.foliage_spread = 0.0;  // solid canopies: every return is on a surface + range noise
  ScanSimulator sim(*seq.world, lidar);
  for (const auto& t : seq.trials) {
    const Pose3 extrinsic = t.params.extrinsicPose();
    const StampNs stamp = t.scan_stamps[t.scan_stamps.size() / 2];  // moving
    const Scan s = sim.simulate(t.body, extrinsic, stamp, 7);
    double sum = 0.0, sum_static = 0.0, sum_sq_along = 0.0;
    int n = 0;
    const Pose3 at_stamp = *t.body.at(stamp) * extrinsic;
    for (std::size_t i = 0; i < s.size(); i += 37) {
      const auto when = stamp - static_cast<StampNs>(std::llround(-static_cast<double>(s.time[i]) * 1e9));
      const Pose3 T = *t.body.at(when) * extrinsic;
      const Eigen::Vector3d p = s.points[i].cast<double>();
      const Eigen::Vector3d pw = T * p;
      sum += seq.world->surfaceDistance(pw);
      sum_static += seq.world->surfaceDistance(at_stamp * p);
      // Along the beam: the measured range minus the range to the surface seen from the true sensor pose.
      Hit hit;
      const Eigen::Vector3d dir = (pw - T.translation()).normalized();
      ASSERT_TRUE(seq.world->intersect(Ray(T.translation(), dir), 1e-6, 130.0, hit));
      sum_sq_along += std::pow(p.norm() - hit.t, 2);
      ++n;
    }
    const double mean = sum / n, mean_static = sum_static / n, rms_along = std::sqrt(sum_sq_along / n);
    // Along the beam the residual is the range noise: RMS = sigma (2 cm).
    EXPECT_NEAR(rms_along, lidar.range_sigma, 0.004) << t.params.name;
    // Perpendicular to the surface it shrinks by the cosine of the incidence angle (ground is seen at grazing
    // angles): mean distance below E|N(0, sigma)| = 1.6 cm, but clearly not zero.
    EXPECT_GT(mean, 0.002) << t.params.name;
    EXPECT_LT(mean, 0.016) << t.params.name;
    // Without per-point poses the motion distortion shows.
    if (t.params.platform == "atv") { EXPECT_GT(mean_static, 2.0 * mean) << t.params.name; }
    std::printf(
        "%s: mean point-to-surface distance %.4f m (%.4f m without per-point poses), RMS range residual %.4f m\n",
        t.params.name.c_str(), mean, mean_static, rms_along);
    RecordProperty(t.params.name + "_mean_surface_distance_mm", static_cast<int>(1000 * mean));
  }
}

TEST(SequencePlanner, RoutesRevisitAndTrajectoriesAreSmooth) {
  const auto& seq = plan();
  for (const auto& t : seq.trials) {
    const auto& poses = t.body.poses();
    ASSERT_GT(poses.size(), 100u);
    // >= 100 Hz, increasing stamps.
    EXPECT_LE(poses[1].stamp - poses[0].stamp, 10000000u);
    double max_speed = 0, max_yaw_rate = 0, max_acc = 0, prev_v = 0;
    for (std::size_t i = 1; i < poses.size(); ++i) {
      const double dt = toSeconds(poses[i].stamp - poses[i - 1].stamp);
      const double v = (poses[i].pose.translation() - poses[i - 1].pose.translation()).head<2>().norm() / dt;
      max_speed = std::max(max_speed, v);
      max_yaw_rate = std::max(max_yaw_rate, rotationAngle(poses[i - 1].pose.inverse() * poses[i].pose) / dt);
      if (i > 1) max_acc = std::max(max_acc, std::abs(v - prev_v) / dt);
      prev_v = v;
    }
    EXPECT_LT(max_speed, 1.3 * t.params.motion.cruise_speed) << t.params.name;
    EXPECT_LT(max_yaw_rate, 1.5) << t.params.name;  // rad/s
    EXPECT_LT(max_acc, 3.0) << t.params.name;
    // Starts and ends at rest, stamped at a realistic epoch.
    EXPECT_GT(toSeconds(poses.front().stamp), 1.6e9);
    EXPECT_TRUE(poses[0].pose.isApprox(poses[10].pose, 1e-9));
  }
  // The route with the default return fraction passes its start junction again.
  RouteParams rp;
  rp.length = 400;
  rp.start_node = 4;
  std::mt19937_64 rng(1);
  const auto route = planRoute(seq.world->network(), rp, rng);
  EXPECT_GE(std::count(route.begin(), route.end(), 4), 2);
}

TEST(SequencePlanner, ConfigFilesParseAndCiSequenceIsSmall) {
  for (const char* name : {"default.yaml", "ci.yaml"}) {
    const auto p = SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/" + name);
    EXPECT_GE(p.trials.size(), 2u) << name;
    EXPECT_EQ(p.hash(), SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/" + name).hash());
  }
  const auto ci = SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/ci.yaml");
  const auto seq = planSequence(ci);
  std::size_t scans = 0;
  for (const auto& t : seq.trials) {
    const double dur = toSeconds(t.body.endStamp() - t.body.startStamp());
    EXPECT_GT(dur, 15.0) << t.params.name;
    EXPECT_LT(dur, 50.0) << t.params.name;
    scans += t.scan_stamps.size();
  }
  EXPECT_LT(scans, 1500u);
  // A malformed config names the file and key.
  try {
    SimulationParams::fromConfig(ConfigNode{YAML::Load("trials: 3"), "x.yaml: "});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.yaml: trials"), std::string::npos) << e.what();
  }
}

TEST(WorldLayout, EveryTrialSeesTheSameBuildingsAndItsOwnClutter) {
  WorldParams wp = smallParams().world;
  EXPECT_FALSE(changesPerTrial(wp));
  const std::string still = wp.describe();
  wp.car_change = 0.5;
  wp.people_per_100m = 2.0;
  wp.foliage_change = 0.15;
  EXPECT_TRUE(changesPerTrial(wp));
  EXPECT_NE(wp.describe(), still);  // the cache key follows the changes
  const WorldLayout layout = generateLayout(wp, 3);
  ASSERT_GT(layout.cars.size(), 10u);
  ASSERT_GT(layout.canopies.size(), 10u);
  // As generated: every car (two boxes each) and every canopy, no people.
  const World generated = layoutWorld(layout);
  EXPECT_EQ(generated.objects().primitives().size(),
            layout.fixed.size() + 2 * layout.cars.size() + layout.canopies.size());
  const World a = layoutWorld(layout, 1), a_again = layoutWorld(layout, 1), b = layoutWorld(layout, 2);
  const auto& pa = a.objects().primitives();
  const auto& pb = b.objects().primitives();
  ASSERT_GE(pa.size(), layout.fixed.size());
  ASSERT_GE(pb.size(), layout.fixed.size());
  // The fixed world is shared: the same primitives in both trials.
  std::size_t same_fixed = 0;
  for (const Primitive& f : layout.fixed)
    for (const Primitive& p : pa)
      if (p.kind == f.kind && p.center == f.center && p.half == f.half) {
        ++same_fixed;
        break;
      }
  EXPECT_EQ(same_fixed, layout.fixed.size());
  // The clutter differs between the two days, and is the same for the same day.
  EXPECT_NE(pa.size(), pb.size());
  EXPECT_EQ(pa.size(), a_again.objects().primitives().size());
  std::size_t people = 0;
  for (const Primitive& p : pa)
    people += p.kind == Primitive::Kind::Cylinder && p.material == kBark && p.half.x() >= 0.2 &&
              2.0 * p.half.z() < 2.1 && 2.0 * p.half.z() > 1.6;
  EXPECT_GT(people, 5u);
}

TEST(ScanSimulator, BeamCalibrationErrorIsFixedPerSensorAndOfTheConfiguredSize) {
  const auto p = smallParams();
  const auto seq = planSequence(p);
  LidarModel lidar = LidarModel::os1_64();
  lidar.beam_angle_sigma_deg = 0.05;
  const ScanSimulator sim(*seq.world, lidar);
  const auto one = sim.castDirections(1), again = sim.castDirections(1), other = sim.castDirections(2);
  ASSERT_EQ(one.size(), lidar.raysPerScan());
  EXPECT_EQ(one, again);
  EXPECT_NE(one, other);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_NEAR(one[i].norm(), 1.0, 1e-12);
    const int beam = static_cast<int>(i / lidar.columns), column = static_cast<int>(i % lidar.columns);
    const double angle = std::acos(std::clamp(one[i].dot(sim.direction(beam, column)), -1.0, 1.0));
    sum2 += angle * angle;
  }
  // Elevation and azimuth offsets of sigma each: the angle between true and nominal beam has an rms of about
  // sqrt(cos^2(el) + 1) sigma.
  const double rms_deg = std::sqrt(sum2 / static_cast<double>(one.size())) * 180.0 / M_PI;
  EXPECT_GT(rms_deg, 0.05);
  EXPECT_LT(rms_deg, 0.1);
  // Without the error, the nominal directions.
  const ScanSimulator nominal(*seq.world, LidarModel::os1_64());
  EXPECT_EQ(nominal.castDirections(1)[17], nominal.direction(0, 17));
}
