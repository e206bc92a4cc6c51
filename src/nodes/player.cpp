// player: replays the trials of a sequence config as one team (spec section 3 synchronization) on ROS topics.
//
// Publishes  /clock                  (rosgraph_msgs/Clock) sequence time
//            /<r>/points             (sensor_msgs/PointCloud2, frame <r>/base_link = the LiDAR) each scan
//            /<r>/reference_pose     (geometry_msgs/PoseStamped, frame world) the LiDAR's reference pose, about
//                                    every 20 ms of the reference trajectory up to each scan
//            TF world -> <r>/reference (the reference LiDAR pose)
//            /player/progress        (std_msgs/String) "t / total" once per second of wall time
// Lockstep (~mode lockstep, default): the offline driver's event order (TeamRun), so the JRL is byte-identical
//   to cosmo_generate's. Per scan of the merged stream that lies at or after the broker's next radio step
//   (RadioStepDone.next_stamp), or whose robot's previous scan is not acknowledged yet: every scan published so
//   far is acknowledged (/<r>/ack, cosmo/FrontendAck); then, with a comm_broker (~wait_for_broker), the player
//   asks it to step the radio through the scan's time (/comm/step_request: robots on = processed a scan,
//   keyframes offered so far, which the broker waits for) and waits for /comm/step_done and for every delivered
//   scan to be processed by its receiver. Then the scan is published (per-point times as float seconds, exact).
//   Scans of different robots between two radio steps are independent, so they are processed in parallel. At the end
//   the radio is stepped through the sequence end the same way, and, when a recorder is running, the player waits
//   until /recorder/progress (cosmo/RecorderProgress) shows every keyframe and loop closure the front-ends
//   acknowledged (FrontendAck.keyframes / loop_closures), so the final JRL never depends on message timing. The resolved sequence path and seed are set on
//   the parameter server first (ros_glue::publishResolvedSequence) for the lockstep front-ends and broker.
//   Real time (~mode realtime): scans at ~rate x wall speed, nothing waited for (results may depend on CPU speed).
// Params: ~sequence (config path), ~data_root (the trials' data root; empty: the config's precedence), ~mode, ~rate, ~seed (-1: the config's), ~max_seconds (0: all),
//         ~ack_timeout (s wall; a front-end silent this long is skipped with a warning), ~wait_for_broker,
//         ~end_linger (s wall after the last scan, radio still stepping; default 3 realtime, 0 lockstep), ~world_frame.
//         With an empty ~sequence the built-in synthetic sequence is used: cosmo_simulate --config
//         ~simulate_config --out ~simulate_out (cached by its parameters, so only the first run generates it).
//         ~noise_models (file; empty: the sequence's environment / noise_models under ~config_dir): checked before
//         anything is played; none: the player stops with a message that says how to make them.
// When done it publishes /player/done (latched std_msgs/Empty) and exits (the launch marks it required).
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/FrontendAck.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RadioStepRequest.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/trial_probe.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/sim/simulation_params.hpp"
#include "cosmo/trials/trial_reference.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/point_cloud.hpp"

using namespace cosmo;

namespace {


struct Acks {
  std::mutex mutex;
  std::map<char, StampNs> last_scan;         ///< latest scan stamp acknowledged, per robot
  std::map<char, cosmo::FrontendAck> latest;  ///< latest ack, per robot
  std::uint64_t broker_delivered = 0;         ///< /comm/stats
  bool step_done = false;                     ///< /comm/step_done of the latest request seen
  std::uint32_t step_done_seq = 0;
  std::map<char, std::uint32_t> delivered;    ///< from /comm/step_done, per receiver
  StampNs next_radio_step = 0;                ///< from /comm/step_done: scans before it need no radio step
  bool recorder_seen = false;                 ///< /recorder/progress received
  std::map<char, std::pair<std::uint32_t, std::uint32_t>> recorded;  ///< recorder intake: keyframes, loop closures
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros::init(argc, argv, "player");
  ros::NodeHandle nh, pnh("~");
  std::string sequence_path, mode, world_frame;
  double rate, max_seconds, ack_timeout, end_linger;
  int seed;
  bool wait_for_broker;
  pnh.param<std::string>("sequence", sequence_path, "");
  pnh.param<std::string>("mode", mode, "lockstep");
  pnh.param("rate", rate, 1.0);
  pnh.param("seed", seed, -1);
  pnh.param("max_seconds", max_seconds, 0.0);
  pnh.param("ack_timeout", ack_timeout, 30.0);
  pnh.param("wait_for_broker", wait_for_broker, true);
  pnh.param("end_linger", end_linger, -1.0);
  pnh.param<std::string>("world_frame", world_frame, "world");
  std::string data_root;
  pnh.param<std::string>("data_root", data_root, "");
  std::string simulate_config, simulate_out;
  pnh.param<std::string>("simulate_config", simulate_config, "");
  pnh.param<std::string>("simulate_out", simulate_out, "/tmp/cosmo_builtin_sequence");
  std::string noise_models, config_dir;
  pnh.param<std::string>("noise_models", noise_models, "");
  pnh.param<std::string>("config_dir", config_dir, pipeline::defaultConfigDir());
  if (sequence_path.empty()) {
    try {
      if (simulate_config.empty()) simulate_config = std::string(COSMO_SOURCE_DIR) + "/config/sim/default.yaml";
      const std::string name = sim::SimulationParams::load(simulate_config).name;
      char exe[4096] = {0};
      const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
      const std::string dir = n > 0 ? std::filesystem::path(std::string(exe, n)).parent_path().string() : ".";
      const std::string cmd = "'" + dir + "/cosmo_simulate' --config '" + simulate_config + "' --out '" + simulate_out + "'";
      ROS_INFO("player: built-in sequence: %s (generated on the first run; several minutes)", cmd.c_str());
      if (std::system(cmd.c_str()) != 0) throw std::runtime_error("cosmo_simulate failed: " + cmd);
      sequence_path = simulate_out + "/" + name + ".yaml";
    } catch (const std::exception& e) {
      ROS_FATAL("player: %s", e.what());
      return 1;
    }
  }
  if (mode != "lockstep" && mode != "realtime") {
    ROS_FATAL("player: ~mode must be lockstep or realtime, got '%s'", mode.c_str());
    return 1;
  }
  const bool lockstep = mode == "lockstep";
  if (!(rate > 0)) rate = 1.0;
  if (end_linger < 0) end_linger = lockstep ? 0.0 : 3.0;

  pipeline::SequenceConfig config;
  pipeline::SequenceTiming timing;
  std::map<char, Trajectory> refs;
  try {
    config = pipeline::SequenceConfig::load(sequence_path, data_root);
    // The run's noise models must exist before anything is played (the recorder labels with them).
    ROS_INFO("player: noise models %s",
             pipeline::loadSequenceNoiseModels(config, config_dir, noise_models).describe().c_str());
    if (seed >= 0) config.seed = static_cast<unsigned long long>(seed);
    std::string check;  // the pre-flight check (cosmo_check): a run that cannot be labelled does not start
    const bool check_ok = ros_glue::checkSequence(config, pipeline::chooseNoiseModels(config, pipeline::defaultConfigDir()), check);
    ROS_INFO("player: pre-flight check:\n%s", check.c_str());
    if (!check_ok) throw std::runtime_error("the pre-flight check failed (above)");
    timing = ros_glue::synchronizeSequence(config);
    refs = trials::loadSequenceReferences(config, timing);
    ros_glue::publishResolvedSequence(std::filesystem::absolute(sequence_path).string(), config.seed,
                                      std::filesystem::absolute(config.data_root).string());
  } catch (const std::exception& e) {
    ROS_FATAL("player: %s", e.what());
    return 1;
  }
  const StampNs end =
      max_seconds > 0 ? std::min(timing.end(), timing.start() + toStampNs(max_seconds)) : timing.end();
  const double total = toSeconds(end - timing.start());
  ROS_INFO("player: sequence %s, %zu robots, %.1f s, mode %s%s", config.name.c_str(), config.trials.size(), total,
           mode.c_str(), lockstep ? "" : (" x" + std::to_string(rate)).c_str());

  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  ros::Publisher progress_pub = nh.advertise<std_msgs::String>("/player/progress", 10);
  ros::Publisher done_pub = nh.advertise<std_msgs::Empty>("/player/done", 1, true);
  std::map<char, ros::Publisher> points_pub, pose_pub;
  std::vector<ros::Subscriber> subs, ack_subs;
  Acks acks;
  for (const auto& t : config.trials) {
    const char r = t.robot;
    const std::string ns = std::string("/") + r;
    points_pub[r] = nh.advertise<sensor_msgs::PointCloud2>(ns + "/points", 5);
    pose_pub[r] = nh.advertise<geometry_msgs::PoseStamped>(ns + "/reference_pose", 200);
    ack_subs.push_back(nh.subscribe<cosmo::FrontendAck>(ns + "/ack", 1000, [&acks, r](const cosmo::FrontendAck::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(acks.mutex);
      acks.last_scan[r] = std::max(acks.last_scan[r], static_cast<StampNs>(m->header.stamp.toNSec()));
      acks.latest[r] = *m;
    }));
  }
  ros::Publisher step_pub = nh.advertise<cosmo::RadioStepRequest>("/comm/step_request", 10);
  ros::Subscriber step_done_sub =
      nh.subscribe<cosmo::RadioStepDone>("/comm/step_done", 100, [&acks](const cosmo::RadioStepDone::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(acks.mutex);
        acks.step_done = true;
        acks.step_done_seq = m->seq;
        acks.next_radio_step = m->next_stamp.toNSec();
        for (std::size_t i = 0; i < m->robots.size() && i < m->delivered.size(); ++i)
          acks.delivered[m->robots[i]] = m->delivered[i];
      });
  subs.push_back(nh.subscribe<std_msgs::String>("/comm/stats", 100, [&acks](const std_msgs::String::ConstPtr& m) {
    try {
      const auto j = nlohmann::json::parse(m->data);
      std::lock_guard<std::mutex> lock(acks.mutex);
      acks.broker_delivered = j.value("delivered", std::uint64_t{0});
    } catch (const std::exception&) {
    }
  }));
  subs.push_back(nh.subscribe<cosmo::RecorderProgress>("/recorder/progress", 10, [&acks](const cosmo::RecorderProgress::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(acks.mutex);
    acks.recorder_seen = true;
    for (std::size_t i = 0; i < m->robots.size() && i < m->keyframes.size() && i < m->loop_closures.size(); ++i)
      acks.recorded[m->robots[i]] = {m->keyframes[i], m->loop_closures[i]};
  }));
  tf2_ros::TransformBroadcaster tf;
  ros::AsyncSpinner spinner(1);
  spinner.start();

  // Wait for the front-ends to subscribe (lockstep needs every robot's ack).
  const ros::WallTime wait_start = ros::WallTime::now();
  auto waitConnected = [&](const std::function<bool()>& connected) {  // at most ~ack_timeout from wait_start
    while (ros::ok() && !connected() && (ros::WallTime::now() - wait_start).toSec() < ack_timeout)
      ros::WallDuration(0.05).sleep();
  };
  auto waitSubscribers = [&](ros::Publisher& pub) { waitConnected([&] { return pub.getNumSubscribers() > 0; }); };
  for (auto& [r, pub] : points_pub) waitSubscribers(pub);
  for (auto& [r, pub] : pose_pub)
    if (!refs[r].empty()) waitSubscribers(pub);
  // Lockstep: every front-end's ack and the broker's step topics connected (a message sent before its
  // connection exists is lost, and the lockstep would wait for it).
  bool use_broker = false;
  if (lockstep) {
    for (auto& sub : ack_subs) waitConnected([&] { return sub.getNumPublishers() > 0; });
    if (wait_for_broker) {
      waitSubscribers(step_pub);
      waitConnected([&] { return step_done_sub.getNumPublishers() > 0; });
      use_broker = step_pub.getNumSubscribers() > 0 && step_done_sub.getNumPublishers() > 0;
      if (!use_broker) ROS_WARN("player: lockstep without a lockstep comm_broker (no /comm/step_request subscriber)");
    }
  }
  auto publishClock = [&](StampNs t) {
    rosgraph_msgs::Clock c;
    c.clock = ros_glue::stampToRos(t);
    clock_pub.publish(c);
  };
  publishClock(timing.start());
  ros::WallDuration(0.5).sleep();

  std::map<char, StampNs> last_pose_sent;
  std::map<char, StampNs> expected_ack;
  std::uint32_t step_seq = 0;
  auto waitFor = [&](const char* what, const std::function<bool()>& done) {
    const ros::WallTime start = ros::WallTime::now();
    while (ros::ok() && !done()) {
      if ((ros::WallTime::now() - start).toSec() > ack_timeout) {
        ROS_WARN("player: no %s within %.0f s; continuing", what, ack_timeout);
        return false;
      }
      ros::WallDuration(0.0005).sleep();
    }
    return true;
  };
  // Lockstep: every published scan acknowledged (a robot silent for ~ack_timeout is skipped with a warning).
  auto waitAcks = [&] {
    for (auto it = expected_ack.begin(); it != expected_ack.end();) {
      const char r = it->first;
      const StampNs want = it->second;
      const bool ok = waitFor("front-end ack", [&] {
        std::lock_guard<std::mutex> lock(acks.mutex);
        return acks.last_scan.count(r) && acks.last_scan[r] >= want;
      });
      it = ok ? std::next(it) : expected_ack.erase(it);
    }
  };
  // Lockstep: the broker runs every radio step <= t once the offered keyframes reached it; its deliveries are
  // processed by their receivers before anything else happens.
  auto stepRadio = [&](StampNs t) {
    if (!use_broker) return;
    cosmo::RadioStepRequest req;
    req.seq = ++step_seq;
    req.stamp = ros_glue::stampToRos(t);
    {
      std::lock_guard<std::mutex> lock(acks.mutex);
      for (const auto& trial : config.trials) {
        const char r = trial.robot;
        const auto it = acks.latest.find(r);
        req.robots.push_back(r);
        req.on.push_back(it != acks.latest.end() && it->second.scans > 0);
        req.keyframes.push_back(it != acks.latest.end() ? it->second.keyframes : 0);
      }
    }
    step_pub.publish(req);
    const std::uint32_t seq = req.seq;
    if (!waitFor("comm_broker step", [&] {
          std::lock_guard<std::mutex> lock(acks.mutex);
          return acks.step_done && acks.step_done_seq >= seq;
        }))
      return;
    waitFor("delivered scans processed", [&] {
      std::lock_guard<std::mutex> lock(acks.mutex);
      for (const auto& [r, n] : acks.delivered) {
        const auto it = acks.latest.find(r);
        if (n > 0 && (it == acks.latest.end() || it->second.received < n)) return false;
      }
      return true;
    });
  };

  try {
    pipeline::MergedScanStream stream = ros_glue::openSequenceStream(config, timing);
    char robot;
    Scan scan;
    const ros::WallTime wall_start = ros::WallTime::now();
    ros::WallTime last_progress = wall_start;
    std::size_t published = 0;
    while (ros::ok() && stream.next(robot, scan)) {
      if (scan.stamp > end) break;
      const double t_rel = toSeconds(scan.stamp - timing.start());
      if (!lockstep) {
        const ros::WallTime due = wall_start + ros::WallDuration(t_rel / rate);
        const ros::WallTime now = ros::WallTime::now();
        if (due > now) (due - now).sleep();
      } else {
        // Every scan published so far processed, then the radio stepped through this scan's time: that is
        // TeamRun's order. Between two radio steps the robots' scans are independent (deliveries and the radio's
        // robot states change only at steps), so a scan that needs no step first is published at once unless its
        // own robot's previous scan is still being processed: the front-ends then work in parallel.
        StampNs next_step = 0;
        {
          std::lock_guard<std::mutex> lock(acks.mutex);
          next_step = acks.next_radio_step;
        }
        const bool needs_step = use_broker && (next_step == 0 || scan.stamp >= next_step);
        if (needs_step || expected_ack.count(robot)) {
          waitAcks();
          expected_ack.clear();
          if (use_broker) stepRadio(scan.stamp);
        }
      }
      publishClock(scan.stamp);
      // reference poses up to the scan (about every 20 ms), then the scan
      const Trajectory& ref = refs[robot];
      if (!ref.empty()) {
        const StampNs from = last_pose_sent.count(robot) ? last_pose_sent[robot] : scan.stamp - std::min<StampNs>(scan.stamp, 200000000ULL);
        std::vector<StampNs> stamps;
        for (const auto& p : ref.poses())
          if (p.stamp > from && p.stamp < scan.stamp && (stamps.empty() || p.stamp - stamps.back() >= 20000000ULL))
            stamps.push_back(p.stamp);
        stamps.push_back(scan.stamp);
        for (StampNs s : stamps) {
          geometry_msgs::PoseStamped ps;
          ps.header.stamp = ros_glue::stampToRos(s);
          ps.header.frame_id = world_frame;
          ps.pose = ros_glue::poseToMsg(ref.atClamped(s));
          pose_pub[robot].publish(ps);
        }
        last_pose_sent[robot] = scan.stamp;
        geometry_msgs::TransformStamped tfm;
        tfm.header.stamp = ros_glue::stampToRos(scan.stamp);
        tfm.header.frame_id = world_frame;
        tfm.child_frame_id = std::string(1, robot) + "/reference";
        const Pose3 T = ref.atClamped(scan.stamp);
        const auto p = ros_glue::poseToMsg(T);
        tfm.transform.translation.x = p.position.x;
        tfm.transform.translation.y = p.position.y;
        tfm.transform.translation.z = p.position.z;
        tfm.transform.rotation = p.orientation;
        tf.sendTransform(tfm);
      }
      sensor_msgs::PointCloud2 msg = ros_glue::toPointCloud2(
          scan, std::string(1, robot) + "/base_link",
          lockstep ? ros_glue::PointTimeEncoding::RelativeSeconds : ros_glue::PointTimeEncoding::OusterNs);
      points_pub[robot].publish(msg);
      expected_ack[robot] = scan.stamp;
      ++published;
      const ros::WallTime now = ros::WallTime::now();
      if ((now - last_progress).toSec() >= 1.0) {
        last_progress = now;
        std::uint64_t delivered = 0;
        {
          std::lock_guard<std::mutex> lock(acks.mutex);
          delivered = acks.broker_delivered;
        }
        char line[200];
        std::snprintf(line, sizeof line, "sequence time %.1f / %.1f s, %zu scans, %llu transfers delivered, %.1f s wall",
                      t_rel, total, published, static_cast<unsigned long long>(delivered), (now - wall_start).toSec());
        std_msgs::String s;
        s.data = line;
        progress_pub.publish(s);
        ROS_INFO("player: %s", line);
      }
    }
    // last acks, then let the radio run to the end of the sequence
    waitAcks();
    if (lockstep) {
      stepRadio(end);
      // everything the front-ends published has reached the recorder (when one runs)
      waitFor("recorder intake", [&] {
        std::lock_guard<std::mutex> lock(acks.mutex);
        if (!acks.recorder_seen) return true;
        for (const auto& [r, a] : acks.latest) {
          const auto it = acks.recorded.find(r);
          if (it == acks.recorded.end() || it->second.first < a.keyframes || it->second.second < a.loop_closures)
            return false;
        }
        return true;
      });
    }
    publishClock(end);
    const ros::WallTime linger = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - linger).toSec() < end_linger) {
      publishClock(end + toStampNs((ros::WallTime::now() - linger).toSec() * 1e-3));
      ros::WallDuration(0.05).sleep();
    }
    ROS_INFO("player: done, %zu scans in %.1f s wall for %.1f s of sequence", published,
             (ros::WallTime::now() - wall_start).toSec(), total);
  } catch (const std::exception& e) {
    ROS_FATAL("player: %s", e.what());
    return 1;
  }
  done_pub.publish(std_msgs::Empty());
  ros::WallDuration(0.5).sleep();
  return 0;
}
