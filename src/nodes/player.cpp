// player: replays a sequence's trials as one team (trials::resolveSequence resolves it) in the offline driver's
// event order (lockstep) or at wall speed (real time), watches its peers and ends the run (ros_glue::RunStop).
// Topics, parameters, lockstep, robot-side playback and the peer policy: docs/nodes.md.
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_ros/transform_broadcaster.h>

#include <atomic>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <nlohmann/json.hpp>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/reference_stream.hpp"
#include "cosmo/pipeline/team_drain.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/lockstep_link.hpp"
#include "cosmo/ros/lockstep_msgs.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/ros/played_sequence.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/recorder_msgs.hpp"
#include "cosmo/ros/robot_playback.hpp"
#include "cosmo/ros/run_stop.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

struct Options {
  trials::SequenceChoice sequence;
  std::string mode = "lockstep", world_frame = "world", status_file, playback = "base";
  std::string frontend_node = "/{r}/frontend", broker_node = "/comm_broker", recorder_node = "/recorder";
  std::string trial_player_node = "/{r}/trial_player";
  live::PeerPolicyParams peers;
  double rate = 1.0, end_linger = -1.0;
  bool wait_for_broker = true;
  bool lockstep() const { return mode == "lockstep"; }
  bool robotPlayback() const { return playback == "robot"; }
  std::string frontendNode(char r) const { return forRobot(frontend_node, r); }
  std::string trialPlayerNode(char r) const { return forRobot(trial_player_node, r); }
  static std::string forRobot(std::string n, char r) {
    if (const auto at = n.find("{r}"); at != std::string::npos) n.replace(at, 3, std::string(1, r));
    return n;
  }
};

trials::SequenceChoice readSequenceChoice(const ros::NodeHandle& pnh) {
  trials::SequenceChoice c;
  int seed = -1;  // -1: the config's
  pnh.param("sequence", c.sequence, c.sequence);
  pnh.param("data_root", c.data_root, c.data_root);
  pnh.param("seed", seed, seed);
  if (seed >= 0) c.seed = static_cast<unsigned long long>(seed);
  pnh.param("max_seconds", c.max_seconds, c.max_seconds);
  pnh.param("simulate_config", c.simulate_config, c.simulate_config);
  pnh.param("simulate_out", c.simulate_out, c.simulate_out);
  pnh.param("noise_models", c.noise_models, c.noise_models);
  pnh.param("config_dir", c.config_dir, cosmo::defaultConfigDir());
  return c;
}

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  o.sequence = readSequenceChoice(pnh);
  pnh.param("mode", o.mode, o.mode);
  pnh.param("rate", o.rate, o.rate);
  pnh.param("wait_for_broker", o.wait_for_broker, o.wait_for_broker);
  pnh.param("status_file", o.status_file, o.status_file);
  pnh.param("frontend_node", o.frontend_node, o.frontend_node);
  pnh.param("broker_node", o.broker_node, o.broker_node);
  pnh.param("recorder_node", o.recorder_node, o.recorder_node);
  pnh.param("trial_player_node", o.trial_player_node, o.trial_player_node);
  pnh.param("playback", o.playback, o.playback);
  pnh.param("connect_timeout", o.peers.connect_timeout, o.peers.connect_timeout);
  pnh.param("death_grace", o.peers.death_grace, o.peers.death_grace);
  pnh.param("recorder_timeout", o.peers.recorder_timeout, o.peers.recorder_timeout);
  pnh.param("end_linger", o.end_linger, o.end_linger);
  pnh.param("world_frame", o.world_frame, o.world_frame);
  if (o.mode != "lockstep" && o.mode != "realtime")
    throw std::runtime_error("~mode must be lockstep or realtime, got '" + o.mode + "'");
  if (o.playback != "base" && o.playback != "robot")
    throw std::runtime_error("~playback must be base (this node reads the trials) or robot (each robot's "
                             "trial_player does), got '" + o.playback + "'");
  o.sequence.check = !o.robotPlayback();  // the robots' trial players check their own trials
  if (!(o.rate > 0)) o.rate = 1.0;
  if (o.end_linger < 0) o.end_linger = o.lockstep() ? 0.0 : 3.0;
  return o;
}

/// A random id of a run (the recorder's journal names it).
std::string randomRunId() {
  std::random_device rd;
  char id[32];
  std::snprintf(id, sizeof id, "%08x%08x", rd(), rd());
  return id;
}

/// The peers the player watches, by the options (a front-end per robot, the broker, the recorder).
live::PeerWatch peerWatch(const Options& o, const std::vector<char>& robots) {
  live::PeerWatch watch(o.lockstep() ? live::RunMode::Lockstep : live::RunMode::Realtime, o.peers);
  for (char r : robots) watch.expect(o.frontendNode(r), live::PeerRole::Frontend, std::string("the front-end of robot ") + r);
  if (o.robotPlayback())  // a robot's trial player is a front-end's input: the same policy
    for (char r : robots)
      watch.expect(o.trialPlayerNode(r), live::PeerRole::Frontend, std::string("the trial player of robot ") + r);
  if (o.wait_for_broker && !o.broker_node.empty())
    watch.expect(o.broker_node, live::PeerRole::Broker, "the comm_broker");
  if (!o.recorder_node.empty()) watch.expect(o.recorder_node, live::PeerRole::Recorder, "the recorder");
  return watch;
}

class Player {
 public:
  Player(ros::NodeHandle& nh, Options options, trials::ResolvedSequence sequence,
         std::unique_ptr<ros_glue::RobotPlayback> robot_playback, const ros_glue::RunStop& stop)
      : o_(std::move(options)),
        stop_(stop),
        seq_(std::move(sequence)),
        robot_playback_(std::move(robot_playback)),
        peers_("player", peerWatch(o_, seq_.robots())) {
    advertise(nh);
    stats_sub_ = nh.subscribe<std_msgs::String>("/comm/stats", 100, [this](const std_msgs::String::ConstPtr& m) {
      try {
        broker_delivered_ = nlohmann::json::parse(m->data).value("delivered", std::uint64_t{0});
      } catch (const std::exception&) {}
    });
    recorder_sub_ = nh.subscribe<cosmo::RecorderProgress>(
        "/recorder/progress", 10, [this](const cosmo::RecorderProgress::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(recorder_mutex_);
          recorder_ = *m;
        });
    if (!o_.lockstep())
      for (char r : seq_.robots())
        ack_subs_.push_back(nh.subscribe<cosmo::FrontendAck>(
            std::string("/") + r + "/ack", 10, [this, r](const cosmo::FrontendAck::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(recorder_mutex_);
              drain_.reported(r, ros_glue::frontendProgressFromMsg(*m), m->queued, ros::WallTime::now().toSec());
            }));
    if (o_.lockstep()) {
      ros_glue::LockstepLink::Peers peers{&peers_, {}, o_.wait_for_broker ? o_.broker_node : "", o_.recorder_node};
      for (char r : seq_.robots()) peers.frontends[r] = o_.frontendNode(r);
      lockstep_.emplace(nh, seq_.robots(), std::move(peers));
    }
    publishSequence();
  }

  /// The whole run; 0 when it is done, 1 when the peer policy stopped it (the recorder then wrote the dataset so
  /// far marked incomplete). Writes ~status_file (before /player/done).
  int run() {
    try {
      connect();
      play();
      finish();
      return 0;
    } catch (const ros_glue::RunStopped& stop) {
      stopRun(stop.what());
      return 1;
    }
  }

 private:
  /// Waits until every peer connected (or was given up on, real time); in lockstep whether a radio runs.
  void connect() {
    for (char r : seq_.robots())
      peers_.setLinkCheck(o_.frontendNode(r), [this, r] {
        const bool reference = seq_.references.at(r).empty() || pose_pub_.at(r).getNumSubscribers() > 0;
        const bool points = robot_playback_ || points_pub_.at(r).getNumSubscribers() > 0;  // else the robot's own
        return points && reference && (!lockstep_ || lockstep_->frontendLinked(r));
      }, std::string("/") + r + "/ack");
    if (robot_playback_)
      for (char r : seq_.robots())
        peers_.setLinkCheck(o_.trialPlayerNode(r), [this, r] { return robot_playback_->listening(r); },
                            ros_glue::scansAheadTopic(r));
    if (lockstep_ && o_.wait_for_broker)
      peers_.setLinkCheck(o_.broker_node, [this] { return lockstep_->brokerLinked(); }, "/comm/step_done");
    peers_.start();
    while (ros::ok() && !peers_.connected()) {
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
      ros::WallDuration(0.05).sleep();
    }
    if (lockstep_) lockstep_->useBroker(o_.wait_for_broker && lockstep_->brokerLinked());
  }

  /// Publishes every scan up to the end, in the team's order (lockstep) or at wall speed (real time).
  void play() {
    sequence::MergedScanStream stream =
        robot_playback_ ? sequence::MergedScanStream(robot_playback_->sources([this] {
          if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
        }), seq_.timing)
                        : trials::openSequenceStream(seq_.config, seq_.timing);
    publishClock(seq_.timing.start());
    ros::WallDuration(0.5).sleep();
    wall_start_ = last_progress_ = ros::WallTime::now();
    char robot;
    Scan scan;
    while (ros::ok() && stream.next(robot, scan) && scan.stamp <= seq_.end) {
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
      if (lockstep_)
        lockstep_->beforeScan(robot, scan.stamp);
      else
        waitForWallTime(scan.stamp);
      publishScan(robot, scan);
      reportProgress(scan.stamp);
    }
  }

  /// The last acks, the radio through the end, the recorder's intake complete (real time: the front-ends' waiting
  /// scans processed and what they sent held by the recorder); then /player/done.
  void finish() {
    if (lockstep_) lockstep_->finish(seq_.end);
    publishClock(seq_.end);
    const ros::WallTime linger = ros::WallTime::now();
    ros::WallTime next_notice = linger + ros::WallDuration(10.0);
    while (ros::ok()) {
      const ros::WallTime now = ros::WallTime::now();
      std::string behind;
      if ((now - linger).toSec() >= o_.end_linger && (lockstep_ || (behind = realtimeBehind()).empty())) break;
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
      if (now >= next_notice) {
        ROS_INFO("player: waiting for robots %s to process their waiting scans and the recorder to hold what they sent",
                 behind.c_str());
        next_notice = now + ros::WallDuration(10.0);
      }
      publishClock(seq_.end + toStampNs((now - linger).toSec() * 1e-3));
      ros::WallDuration(0.05).sleep();
    }
    ROS_INFO("player: done, %zu scans in %.1f s wall for %.1f s of sequence", published_,
             (ros::WallTime::now() - wall_start_).toSec(), seq_.seconds());
    stop_.done();
    done_pub_.publish(std_msgs::Empty());
    ros::WallDuration(0.5).sleep();
  }

  /// Real time: the robots whose front-end is alive and not drained (pipeline::TeamDrain): scans waiting, busy,
  /// counters still moving, or measurements the recorder does not hold yet.
  std::string realtimeBehind() {
    std::lock_guard<std::mutex> lock(recorder_mutex_);
    std::string behind;
    const double now = ros::WallTime::now().toSec();
    for (char r : seq_.robots()) {
      if (!peers_.alive(o_.frontendNode(r))) continue;
      const std::uint64_t acked = recorder_ ? ros_glue::recorderAcked(*recorder_, r) : drain_.lastSeq(r);
      if (!drain_.drained(r, acked, now)) behind += r;
    }
    return behind;
  }

  /// Tells the recorder why the run stops (/player/abort) and waits for it to write the dataset so far.
  void stopRun(const std::string& reason) {
    stop_.stopped(reason);
    const auto written = [this] {
      std::lock_guard<std::mutex> lock(recorder_mutex_);
      return recorder_ && !recorder_->incomplete.empty();
    };
    const bool recorder = !o_.recorder_node.empty() && peers_.alive(o_.recorder_node);
    if (recorder && ros_glue::waitUntil(written, ros_glue::wallDeadline(30.0))) {
      std::lock_guard<std::mutex> lock(recorder_mutex_);
      ROS_ERROR("player: the recorder wrote the dataset so far, marked incomplete: %s", recorder_->written.c_str());
    } else {
      ROS_ERROR("player: the recorder did not confirm a write (%s); what it acknowledged is in its journal",
                recorder ? "no answer within 30 s" : "it is not running");
    }
  }

  void advertise(ros::NodeHandle& nh) {
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    progress_pub_ = nh.advertise<std_msgs::String>("/player/progress", 10);
    done_pub_ = nh.advertise<std_msgs::Empty>("/player/done", 1, true);
    sequence_pub_ = nh.advertise<cosmo::TeamSequence>(ros_glue::kTeamSequenceTopic, 1, true);
    for (char r : seq_.robots()) {
      const std::string ns = std::string("/") + r;
      if (!robot_playback_) points_pub_[r] = nh.advertise<sensor_msgs::PointCloud2>(ns + "/points", 5);
      pose_pub_[r] = nh.advertise<geometry_msgs::PoseStamped>(ns + "/reference_pose", 200);
      trajectory_pub_[r] = nh.advertise<cosmo::ReferenceTrajectory>(ros_glue::referenceTrajectoryTopic(r), 1, true);
    }
  }

  void publishSequence() {
    cosmo::TeamSequence sequence = ros_glue::teamSequenceToMsg(seq_.config, seq_.timing);
    sequence.run_id = run_id_;
    sequence_pub_.publish(sequence);
    ROS_INFO("player: run %s", run_id_.c_str());
    for (char r : seq_.robots())
      trajectory_pub_[r].publish(ros_glue::trajectoryToMsg(r, seq_.references[r], o_.world_frame));
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
    if (robot_playback_)  // the robot publishes it on its own machine
      robot_playback_->play(robot, seq_.timing.of(robot).toRecorded(scan.stamp), scan.stamp);
    else
      points_pub_[robot].publish(ros_glue::toPointCloud2(
          scan, std::string(1, robot) + "/base_link",
          o_.lockstep() ? ros_glue::PointTimeEncoding::RelativeSeconds : ros_glue::PointTimeEncoding::OusterNs));
    if (lockstep_) lockstep_->scanHandedOver(robot, scan.stamp);
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

  void reportProgress(StampNs stamp) {
    const ros::WallTime now = ros::WallTime::now();
    if ((now - last_progress_).toSec() < 1.0) return;
    last_progress_ = now;
    char line[200];
    std::snprintf(line, sizeof line, "sequence time %.1f / %.1f s, %zu scans, %llu transfers delivered, %.1f s wall",
                  toSeconds(stamp - seq_.timing.start()), seq_.seconds(), published_,
                  static_cast<unsigned long long>(broker_delivered_.load()), (now - wall_start_).toSec());
    std_msgs::String s;
    s.data = line;
    progress_pub_.publish(s);
    ROS_INFO("player: %s", line);
  }

  Options o_;
  const ros_glue::RunStop& stop_;  ///< the status file and /player/abort
  trials::ResolvedSequence seq_;
  std::unique_ptr<ros_glue::RobotPlayback> robot_playback_;  ///< robot-side playback: the robots read the trials
  std::string run_id_ = randomRunId();  ///< the recorder's journal belongs to this run
  std::optional<ros_glue::LockstepLink> lockstep_;  ///< lockstep mode: the team's event order through the nodes
  std::atomic<std::uint64_t> broker_delivered_{0};  ///< /comm/stats, for the progress line
  std::size_t published_ = 0;
  sequence::ReferenceStream reference_stream_;  ///< the reference poses sent beside the scans
  ros::WallTime wall_start_, last_progress_;
  std::mutex recorder_mutex_;                        ///< guards recorder_ and drain_
  std::optional<cosmo::RecorderProgress> recorder_;  ///< the recorder's latest /recorder/progress
  pipeline::TeamDrain drain_;  ///< real time: whether each front-end is done with what it was given
  ros::Publisher clock_pub_, progress_pub_, done_pub_, sequence_pub_;
  std::map<char, ros::Publisher> points_pub_, pose_pub_, trajectory_pub_;
  ros::Subscriber stats_sub_, recorder_sub_;
  std::vector<ros::Subscriber> ack_subs_;
  tf2_ros::TransformBroadcaster tf_;
  ros_glue::PeerMonitor peers_;  ///< last: its thread (link checks use the publishers) ends first
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros_glue::initNode(argc, argv, "player");
  int code = 0;
  std::optional<ros_glue::RunStop> stop;
  const int failed = ros_glue::runNode("player", [&] {
    ros::NodeHandle nh, pnh("~");
    const Options options = readOptions(pnh);
    stop.emplace(nh, options.status_file);
    ros::AsyncSpinner spinner(1);  // robot-side playback: the robots' announcements arrive while resolving
    spinner.start();
    std::unique_ptr<ros_glue::RobotPlayback> robot_playback;
    const auto from_robots = [&](const sequence::SequenceConfig& config) {
      std::vector<char> robots;
      for (const auto& t : config.trials) robots.push_back(t.robot);
      robot_playback = std::make_unique<ros_glue::RobotPlayback>(
          nh, robots, options.peers.connect_timeout, [&](char r) { return options.trialPlayerNode(r); });
      return robot_playback->trials(config);
    };
    std::optional<trials::ResolvedSequence> resolved;
    try {
      resolved = options.robotPlayback() ? ros_glue::resolvePlayedSequence(options.sequence, from_robots)
                                         : ros_glue::resolvePlayedSequence(options.sequence);
    } catch (const ros_glue::RunStopped& why) {  // a robot's trial player never came: nothing was played
      stop->stopped(why.what());
      ros::WallDuration(1.0).sleep();  // the latched message reaches the subscribers already connected
      code = 1;
      return;
    }
    trials::ResolvedSequence& sequence = *resolved;
    ROS_INFO("player: sequence %s, %zu robots, %.1f s, mode %s, trials played %s", sequence.config.name.c_str(),
             sequence.config.trials.size(), sequence.seconds(), options.mode.c_str(),
             options.robotPlayback() ? "on the robots' machines" : "here");
    Player player(nh, options, std::move(sequence), std::move(robot_playback), *stop);
    code = player.run();
  });
  if (failed && stop) stop->failed();
  return failed ? failed : code;
}
