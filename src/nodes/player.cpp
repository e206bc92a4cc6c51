// player: replays the trials of a sequence config as one team (spec section 3 synchronization) on ROS topics.
//
// Publishes  /clock                  (rosgraph_msgs/Clock) sequence time
//            /<r>/points             (sensor_msgs/PointCloud2, frame <r>/base_link = the LiDAR) each scan
//            /<r>/reference_pose     (geometry_msgs/PoseStamped, frame world) the LiDAR's reference pose, about
//                                    every 20 ms of the reference trajectory up to each scan
//            TF world -> <r>/reference (the reference LiDAR pose)
//            /player/sequence        (cosmo/TeamSequence, latched) the resolved sequence: robots, spans, seed
//            /<r>/reference_trajectory (cosmo/ReferenceTrajectory, latched) each robot's whole reference, bit-exact
//            /player/progress        (std_msgs/String) "t / total" once per second of wall time
//            /player/done            (std_msgs/Empty, latched) when it is done; then it exits
//            params /player/robots (as soon as the config is read: the launch starts one front-end per robot),
//            /player/resolved_sequence, /player/resolved_seed, /player/resolved_data_root
// Lockstep (~mode lockstep, default): the offline driver's event order (pipeline::LockstepSchedule, which TeamRun
//   runs too), so the JRL is byte-identical to cosmo_generate's. Before a scan it waits for every scan published
//   so far to be acknowledged (/<r>/ack, cosmo/FrontendAck) when the schedule says so, and asks the comm_broker to
//   step the radio through the scan's time (/comm/step_request, answered on /comm/step_done) and waits until the
//   delivered scans are processed. At the end the radio runs through the sequence end and the player waits until
//   the recorder's intake (/recorder/progress) holds everything the front-ends acknowledged. The lockstep nodes
//   take the sequence from the latched topics (nothing from disk).
//   Real time (~mode realtime): scans at ~rate x wall speed, nothing waited for (results may depend on CPU speed).
// Params: ~sequence (config path; empty: the built-in synthetic sequence, cosmo_simulate --config ~simulate_config
//         --out ~simulate_out, cached), ~data_root (empty: the config's precedence), ~mode, ~rate, ~seed (-1: the
//         config's), ~max_seconds (0: all), ~ack_timeout (s wall; a silent front-end is skipped with a warning),
//         ~connect_timeout (s wall for the nodes to connect), ~wait_for_broker, ~end_linger (s wall after the last
//         scan; default 3 realtime, 0 lockstep), ~world_frame, ~noise_models / ~config_dir (checked before anything
//         is played: a run that cannot be labelled does not start).
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_ros/transform_broadcaster.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

#include "cosmo/FrontendAck.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RadioStepRequest.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/lockstep_schedule.hpp"
#include "cosmo/pipeline/reference_stream.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"
#include "cosmo/ros/trial_probe.hpp"
#include "cosmo/sim/simulation_params.hpp"
#include "cosmo/trials/trial_reference.hpp"

using namespace cosmo;

namespace {

struct Options {
  std::string sequence, data_root, mode = "lockstep", world_frame = "world";
  std::string simulate_config, simulate_out = "/tmp/cosmo_builtin_sequence";
  std::string noise_models, config_dir;
  double rate = 1.0, max_seconds = 0.0, ack_timeout = 30.0, connect_timeout = 120.0, end_linger = -1.0;
  int seed = -1;
  bool wait_for_broker = true;
  bool lockstep() const { return mode == "lockstep"; }
};

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  pnh.param("sequence", o.sequence, o.sequence);
  pnh.param("data_root", o.data_root, o.data_root);
  pnh.param("mode", o.mode, o.mode);
  pnh.param("rate", o.rate, o.rate);
  pnh.param("seed", o.seed, o.seed);
  pnh.param("max_seconds", o.max_seconds, o.max_seconds);
  pnh.param("ack_timeout", o.ack_timeout, o.ack_timeout);
  pnh.param("connect_timeout", o.connect_timeout, o.connect_timeout);
  pnh.param("wait_for_broker", o.wait_for_broker, o.wait_for_broker);
  pnh.param("end_linger", o.end_linger, o.end_linger);
  pnh.param("world_frame", o.world_frame, o.world_frame);
  pnh.param("simulate_config", o.simulate_config, o.simulate_config);
  pnh.param("simulate_out", o.simulate_out, o.simulate_out);
  pnh.param("noise_models", o.noise_models, o.noise_models);
  pnh.param("config_dir", o.config_dir, pipeline::defaultConfigDir());
  if (o.mode != "lockstep" && o.mode != "realtime")
    throw std::runtime_error("~mode must be lockstep or realtime, got '" + o.mode + "'");
  if (!(o.rate > 0)) o.rate = 1.0;
  if (o.end_linger < 0) o.end_linger = o.lockstep() ? 0.0 : 3.0;
  return o;
}

/// The built-in synthetic sequence: cosmo_simulate (beside this program) writes it once, cached by its parameters.
std::string builtInSequence(const Options& o) {
  const std::string config =
      o.simulate_config.empty() ? std::string(COSMO_SOURCE_DIR) + "/config/sim/default.yaml" : o.simulate_config;
  const std::string name = sim::SimulationParams::load(config).name;
  char exe[4096] = {0};
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  const std::string dir = n > 0 ? std::filesystem::path(std::string(exe, n)).parent_path().string() : ".";
  const std::string cmd = "'" + dir + "/cosmo_simulate' --config '" + config + "' --out '" + o.simulate_out + "'";
  ROS_INFO("player: built-in sequence: %s (generated on the first run; several minutes)", cmd.c_str());
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("cosmo_simulate failed: " + cmd);
  return o.simulate_out + "/" + name + ".yaml";
}

/// The sequence as played: config (effective seed), time synchronization, references, the end of the replay.
struct Sequence {
  pipeline::SequenceConfig config;
  pipeline::SequenceTiming timing;
  std::map<char, Trajectory> references;
  StampNs end = 0;
  std::vector<char> robots() const {
    std::vector<char> r;
    for (const auto& t : config.trials) r.push_back(t.robot);
    return r;
  }
};

/// Loads and checks the sequence; the robots are announced first (the launch starts their front-ends meanwhile).
Sequence resolveSequence(const Options& o) {
  const std::string path = o.sequence.empty() ? builtInSequence(o) : o.sequence;
  Sequence s;
  s.config = pipeline::SequenceConfig::load(path, o.data_root);
  ros_glue::publishTeamRobots(s.robots());
  ROS_INFO("player: noise models %s",
           pipeline::loadSequenceNoiseModels(s.config, o.config_dir, o.noise_models).describe().c_str());
  if (o.seed >= 0) s.config.seed = static_cast<unsigned long long>(o.seed);
  std::string check;
  const bool ok =
      ros_glue::checkSequence(s.config, pipeline::chooseNoiseModels(s.config, pipeline::defaultConfigDir()), check);
  ROS_INFO("player: pre-flight check:\n%s", check.c_str());
  if (!ok) throw std::runtime_error("the pre-flight check failed (above)");
  s.timing = ros_glue::synchronizeSequence(s.config);
  s.references = trials::loadSequenceReferences(s.config, s.timing);
  ros_glue::publishResolvedSequence(std::filesystem::absolute(path).string(), s.config.seed,
                                    std::filesystem::absolute(s.config.data_root).string());
  s.end = o.max_seconds > 0 ? std::min(s.timing.end(), s.timing.start() + toStampNs(o.max_seconds)) : s.timing.end();
  return s;
}

class Player {
 public:
  Player(ros::NodeHandle& nh, Options options, Sequence sequence)
      : o_(std::move(options)), seq_(std::move(sequence)), schedule_(seq_.robots(), false) {
    advertise(nh);
    subscribe(nh);
    publishSequence();
  }

  /// Waits for the front-ends (and, in lockstep, the broker) to connect; decides whether a radio runs.
  void connect() {
    const ros::WallTime deadline = ros_glue::wallDeadline(o_.connect_timeout);
    auto waitConnected = [&](const std::function<bool()>& connected) { ros_glue::waitUntil(connected, deadline); };
    for (auto& [r, pub] : points_pub_) waitConnected([&] { return pub.getNumSubscribers() > 0; });
    for (auto& [r, pub] : pose_pub_)
      if (!seq_.references[r].empty()) waitConnected([&] { return pub.getNumSubscribers() > 0; });
    if (o_.lockstep()) {  // a message sent before its connection exists is lost, and the lockstep would wait for it
      for (auto& sub : ack_subs_) waitConnected([&] { return sub.getNumPublishers() > 0; });
      if (o_.wait_for_broker) {
        waitConnected([&] { return step_pub_.getNumSubscribers() > 0 && step_done_sub_.getNumPublishers() > 0; });
        use_broker_ = step_pub_.getNumSubscribers() > 0 && step_done_sub_.getNumPublishers() > 0;
        if (!use_broker_)
          ROS_WARN("player: lockstep without a lockstep comm_broker (no /comm/step_request subscriber)");
      }
    }
    std::lock_guard<std::mutex> lock(mutex_);
    schedule_.useRadio(use_broker_);
  }

  /// Publishes every scan up to the end, in the team's order (lockstep) or at wall speed (real time).
  void play() {
    pipeline::MergedScanStream stream = ros_glue::openSequenceStream(seq_.config, seq_.timing);
    publishClock(seq_.timing.start());
    ros::WallDuration(0.5).sleep();
    wall_start_ = last_progress_ = ros::WallTime::now();
    char robot;
    Scan scan;
    while (ros::ok() && stream.next(robot, scan) && scan.stamp <= seq_.end) {
      if (o_.lockstep())
        runScheduleBefore(robot, scan.stamp);
      else
        waitForWallTime(scan.stamp);
      publishScan(robot, scan);
      reportProgress(scan.stamp);
    }
  }

  /// The last acks, the radio through the end, the recorder's intake complete; then /player/done.
  void finish() {
    if (o_.lockstep()) {
      waitForScans();
      stepRadio(seq_.end);
      waitFor("recorder intake", [&] { return schedule_.recorderComplete(); });
    }
    publishClock(seq_.end);
    const ros::WallTime linger = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - linger).toSec() < o_.end_linger) {
      publishClock(seq_.end + toStampNs((ros::WallTime::now() - linger).toSec() * 1e-3));
      ros::WallDuration(0.05).sleep();
    }
    ROS_INFO("player: done, %zu scans in %.1f s wall for %.1f s of sequence", published_,
             (ros::WallTime::now() - wall_start_).toSec(), totalSeconds());
    done_pub_.publish(std_msgs::Empty());
    ros::WallDuration(0.5).sleep();
  }

 private:
  void advertise(ros::NodeHandle& nh) {
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    progress_pub_ = nh.advertise<std_msgs::String>("/player/progress", 10);
    done_pub_ = nh.advertise<std_msgs::Empty>("/player/done", 1, true);
    sequence_pub_ = nh.advertise<cosmo::TeamSequence>(ros_glue::kTeamSequenceTopic, 1, true);
    step_pub_ = nh.advertise<cosmo::RadioStepRequest>("/comm/step_request", 10);
    for (char r : seq_.robots()) {
      const std::string ns = std::string("/") + r;
      points_pub_[r] = nh.advertise<sensor_msgs::PointCloud2>(ns + "/points", 5);
      pose_pub_[r] = nh.advertise<geometry_msgs::PoseStamped>(ns + "/reference_pose", 200);
      trajectory_pub_[r] = nh.advertise<cosmo::ReferenceTrajectory>(ros_glue::referenceTrajectoryTopic(r), 1, true);
    }
  }

  void subscribe(ros::NodeHandle& nh) {
    for (char r : seq_.robots())
      ack_subs_.push_back(nh.subscribe<cosmo::FrontendAck>(
          std::string("/") + r + "/ack", 1000, [this, r](const cosmo::FrontendAck::ConstPtr& m) { onAck(r, *m); }));
    step_done_sub_ = nh.subscribe<cosmo::RadioStepDone>(
        "/comm/step_done", 100, [this](const cosmo::RadioStepDone::ConstPtr& m) { onStepDone(*m); });
    subs_.push_back(nh.subscribe<std_msgs::String>("/comm/stats", 100, [this](const std_msgs::String::ConstPtr& m) {
      try {
        const auto j = nlohmann::json::parse(m->data);
        std::lock_guard<std::mutex> lock(mutex_);
        broker_delivered_ = j.value("delivered", std::uint64_t{0});
      } catch (const std::exception&) {}
    }));
    subs_.push_back(nh.subscribe<cosmo::RecorderProgress>(
        "/recorder/progress", 10, [this](const cosmo::RecorderProgress::ConstPtr& m) { onRecorder(*m); }));
  }

  void publishSequence() {
    sequence_pub_.publish(ros_glue::teamSequenceToMsg(seq_.config, seq_.timing));
    for (char r : seq_.robots())
      trajectory_pub_[r].publish(ros_glue::trajectoryToMsg(r, seq_.references[r], o_.world_frame));
  }

  void onAck(char r, const cosmo::FrontendAck& m) {
    pipeline::FrontendProgress p;
    p.last_scan = m.header.stamp.toNSec();
    p.scans = m.scans;
    p.received = m.received;
    p.keyframes = m.keyframes;
    p.loop_closures = m.loop_closures;
    std::lock_guard<std::mutex> lock(mutex_);
    schedule_.frontendReported(r, p);
  }

  void onStepDone(const cosmo::RadioStepDone& m) {
    std::map<char, std::uint32_t> delivered;
    for (std::size_t i = 0; i < m.robots.size() && i < m.delivered.size(); ++i) delivered[m.robots[i]] = m.delivered[i];
    std::lock_guard<std::mutex> lock(mutex_);
    schedule_.radioStepped(m.next_stamp.toNSec(), delivered);
    step_done_seq_ = std::max(step_done_seq_, m.seq);
  }

  void onRecorder(const cosmo::RecorderProgress& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (std::size_t i = 0; i < m.robots.size() && i < m.keyframes.size() && i < m.loop_closures.size(); ++i)
      schedule_.recorderReported(m.robots[i], m.keyframes[i], m.loop_closures[i]);
  }

  /// Waits (polling; the callbacks run on the spinner thread) until `done` holds under the lock, at most
  /// ~ack_timeout; false on a timeout (with a warning).
  bool waitFor(const char* what, const std::function<bool()>& done) {
    const auto locked = [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return done();
    };
    if (ros_glue::waitUntil(locked, ros_glue::wallDeadline(o_.ack_timeout), 0.0005)) return true;
    if (ros::ok()) ROS_WARN("player: no %s within %.0f s; continuing", what, o_.ack_timeout);
    return false;
  }

  void waitForScans() {
    if (waitFor("front-end ack", [&] { return schedule_.scansProcessed(); })) return;
    std::lock_guard<std::mutex> lock(mutex_);
    std::string behind;
    for (char r : schedule_.robotsBehind()) behind += r;
    ROS_WARN("player: front-ends %s did not acknowledge their last scan; going on without", behind.c_str());
    schedule_.stopWaitingForScans();
  }

  /// The broker runs every radio step <= t once the keyframes offered so far reached it; the scans it delivered
  /// are processed by their receivers before anything else happens.
  void stepRadio(StampNs t) {
    if (!use_broker_) return;
    cosmo::RadioStepRequest req;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const pipeline::RadioStepOrder order = schedule_.radioStepOrder(t);
      req.robots.assign(order.robots.begin(), order.robots.end());
      req.on.assign(order.on.begin(), order.on.end());
      req.keyframes = order.keyframes;
    }
    req.seq = ++step_seq_;
    req.stamp = ros_glue::stampToRos(t);
    step_pub_.publish(req);
    const std::uint32_t seq = req.seq;
    if (!waitFor("comm_broker step", [&] { return step_done_seq_ >= seq; })) return;
    waitFor("delivered scans processed", [&] { return schedule_.deliveriesProcessed(); });
  }

  void runScheduleBefore(char robot, StampNs stamp) {
    pipeline::LockstepSchedule::BeforeScan before;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      before = schedule_.beforeScan(robot, stamp);
    }
    if (before.wait_for_scans) waitForScans();
    if (before.step_radio) stepRadio(stamp);
  }

  void waitForWallTime(StampNs stamp) {
    const ros::WallTime due = wall_start_ + ros::WallDuration(toSeconds(stamp - seq_.timing.start()) / o_.rate);
    const ros::WallTime now = ros::WallTime::now();
    if (due > now) (due - now).sleep();
  }

  void publishClock(StampNs t) {
    rosgraph_msgs::Clock c;
    c.clock = ros_glue::stampToRos(t);
    clock_pub_.publish(c);
  }

  /// The reference poses up to the scan (about every 20 ms) and its TF, then the scan.
  void publishScan(char robot, const Scan& scan) {
    publishClock(scan.stamp);
    publishReferenceUpTo(robot, scan.stamp);
    points_pub_[robot].publish(ros_glue::toPointCloud2(
        scan, std::string(1, robot) + "/base_link",
        o_.lockstep() ? ros_glue::PointTimeEncoding::RelativeSeconds : ros_glue::PointTimeEncoding::OusterNs));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      schedule_.scanHandedOver(robot, scan.stamp);
    }
    ++published_;
  }

  void publishReferenceUpTo(char robot, StampNs stamp) {
    const Trajectory& ref = seq_.references[robot];
    if (ref.empty()) return;
    for (StampNs s : reference_stream_.beforeScan(robot, ref, stamp)) {
      geometry_msgs::PoseStamped ps;
      ps.header.stamp = ros_glue::stampToRos(s);
      ps.header.frame_id = o_.world_frame;
      ps.pose = ros_glue::poseToMsg(ref.atClamped(s));
      pose_pub_[robot].publish(ps);
    }
    tf_.sendTransform(ros_glue::transformMsg(ref.atClamped(stamp), ros_glue::stampToRos(stamp), o_.world_frame,
                                             std::string(1, robot) + "/reference"));
  }

  double totalSeconds() const { return toSeconds(seq_.end - seq_.timing.start()); }

  void reportProgress(StampNs stamp) {
    const ros::WallTime now = ros::WallTime::now();
    if ((now - last_progress_).toSec() < 1.0) return;
    last_progress_ = now;
    std::uint64_t delivered = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      delivered = broker_delivered_;
    }
    char line[200];
    std::snprintf(line, sizeof line, "sequence time %.1f / %.1f s, %zu scans, %llu transfers delivered, %.1f s wall",
                  toSeconds(stamp - seq_.timing.start()), totalSeconds(), published_,
                  static_cast<unsigned long long>(delivered), (now - wall_start_).toSec());
    std_msgs::String s;
    s.data = line;
    progress_pub_.publish(s);
    ROS_INFO("player: %s", line);
  }

  Options o_;
  Sequence seq_;
  std::mutex mutex_;  ///< guards what the callbacks update: the schedule and the counters below
  pipeline::LockstepSchedule schedule_;
  std::uint32_t step_done_seq_ = 0;
  std::uint64_t broker_delivered_ = 0;  ///< /comm/stats, for the progress line
  bool use_broker_ = false;
  std::uint32_t step_seq_ = 0;
  std::size_t published_ = 0;
  pipeline::ReferenceStream reference_stream_;  ///< the reference poses sent beside the scans
  ros::WallTime wall_start_, last_progress_;
  ros::Publisher clock_pub_, progress_pub_, done_pub_, sequence_pub_, step_pub_;
  std::map<char, ros::Publisher> points_pub_, pose_pub_, trajectory_pub_;
  std::vector<ros::Subscriber> ack_subs_, subs_;
  ros::Subscriber step_done_sub_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros::init(argc, argv, "player");
  return ros_glue::runNode("player", [] {
    ros::NodeHandle nh, pnh("~");
    const Options options = readOptions(pnh);
    Sequence sequence = resolveSequence(options);
    ROS_INFO("player: sequence %s, %zu robots, %.1f s, mode %s", sequence.config.name.c_str(),
             sequence.config.trials.size(), toSeconds(sequence.end - sequence.timing.start()), options.mode.c_str());
    Player player(nh, options, std::move(sequence));
    ros::AsyncSpinner spinner(1);
    spinner.start();
    player.connect();
    player.play();
    player.finish();
  });
}
