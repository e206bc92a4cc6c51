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
//   take the sequence from the latched topics (nothing from disk). The protocol's side here: ros_glue::LockstepLink.
//   Real time (~mode realtime): scans at ~rate x wall speed, nothing waited for (results may depend on CPU speed).
// Robot-side playback (~playback robot): the player reads no bag and no reference. Each robot's trial_player
//   (robot.launch playback:=robot, on the robot's machine) announces its trial's span and reference and its
//   read-ahead stamps; the player merges them into the same order and asks each robot for its scans
//   (/<r>/play_scan) instead of publishing /<r>/points (ros_glue::RobotPlayback). Everything else is unchanged.
// Params: ~sequence (config path; empty: the built-in synthetic sequence, cosmo_simulate --config ~simulate_config
//         --out ~simulate_out, cached), ~data_root (empty: the config's precedence), ~mode, ~rate, ~seed (-1: the
//         config's), ~max_seconds (0: all), ~ack_timeout (s wall; a silent front-end is skipped with a warning),
//         ~connect_timeout (s wall for the nodes to connect), ~wait_for_broker, ~playback (base | robot), ~end_linger (s wall after the last
//         scan; default 3 realtime, 0 lockstep), ~world_frame, ~noise_models / ~config_dir (checked before anything
//         is played: a run that cannot be labelled does not start).
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_ros/transform_broadcaster.h>

#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/reference_stream.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/lockstep_link.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/played_sequence.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/robot_playback.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

struct Options {
  ros_glue::SequenceChoice sequence;
  std::string mode = "lockstep", world_frame = "world", playback = "base";
  double rate = 1.0, ack_timeout = 30.0, connect_timeout = 120.0, end_linger = -1.0;
  bool wait_for_broker = true;
  bool lockstep() const { return mode == "lockstep"; }
  bool robotPlayback() const { return playback == "robot"; }
};

ros_glue::SequenceChoice readSequenceChoice(const ros::NodeHandle& pnh) {
  ros_glue::SequenceChoice c;
  pnh.param("sequence", c.sequence, c.sequence);
  pnh.param("data_root", c.data_root, c.data_root);
  pnh.param("seed", c.seed, c.seed);
  pnh.param("max_seconds", c.max_seconds, c.max_seconds);
  pnh.param("simulate_config", c.simulate_config, c.simulate_config);
  pnh.param("simulate_out", c.simulate_out, c.simulate_out);
  pnh.param("noise_models", c.noise_models, c.noise_models);
  pnh.param("config_dir", c.config_dir, pipeline::defaultConfigDir());
  return c;
}

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  o.sequence = readSequenceChoice(pnh);
  pnh.param("mode", o.mode, o.mode);
  pnh.param("rate", o.rate, o.rate);
  pnh.param("ack_timeout", o.ack_timeout, o.ack_timeout);
  pnh.param("connect_timeout", o.connect_timeout, o.connect_timeout);
  pnh.param("wait_for_broker", o.wait_for_broker, o.wait_for_broker);
  pnh.param("end_linger", o.end_linger, o.end_linger);
  pnh.param("world_frame", o.world_frame, o.world_frame);
  pnh.param("playback", o.playback, o.playback);
  if (o.mode != "lockstep" && o.mode != "realtime")
    throw std::runtime_error("~mode must be lockstep or realtime, got '" + o.mode + "'");
  if (o.playback != "base" && o.playback != "robot")
    throw std::runtime_error("~playback must be base (this node reads the trials) or robot (each robot's "
                             "trial_player does), got '" + o.playback + "'");
  if (!(o.rate > 0)) o.rate = 1.0;
  if (o.end_linger < 0) o.end_linger = o.lockstep() ? 0.0 : 3.0;
  return o;
}

class Player {
 public:
  Player(ros::NodeHandle& nh, Options options, ros_glue::PlayedSequence sequence,
         std::unique_ptr<ros_glue::RobotPlayback> robot_playback)
      : o_(std::move(options)), seq_(std::move(sequence)), robot_playback_(std::move(robot_playback)) {
    advertise(nh);
    stats_sub_ = nh.subscribe<std_msgs::String>("/comm/stats", 100, [this](const std_msgs::String::ConstPtr& m) {
      try {
        broker_delivered_ = nlohmann::json::parse(m->data).value("delivered", std::uint64_t{0});
      } catch (const std::exception&) {}
    });
    if (o_.lockstep()) lockstep_.emplace(nh, seq_.robots(), o_.ack_timeout);
    publishSequence();
  }

  /// Waits for the front-ends (and, in lockstep, the broker) to connect; decides whether a radio runs.
  void connect() {
    const ros::WallTime deadline = ros_glue::wallDeadline(o_.connect_timeout);
    if (robot_playback_) robot_playback_->connect();
    for (auto& [r, pub] : points_pub_) ros_glue::waitUntil([&] { return pub.getNumSubscribers() > 0; }, deadline);
    for (auto& [r, pub] : pose_pub_)
      if (!seq_.references[r].empty()) ros_glue::waitUntil([&] { return pub.getNumSubscribers() > 0; }, deadline);
    if (lockstep_) lockstep_->connect(deadline, o_.wait_for_broker);
  }

  /// Publishes every scan up to the end, in the team's order (lockstep) or at wall speed (real time).
  void play() {
    pipeline::MergedScanStream stream =
        robot_playback_ ? pipeline::MergedScanStream(robot_playback_->sources(), seq_.timing)
                        : ros_glue::openSequenceStream(seq_.config, seq_.timing);
    publishClock(seq_.timing.start());
    ros::WallDuration(0.5).sleep();
    wall_start_ = last_progress_ = ros::WallTime::now();
    char robot;
    Scan scan;
    while (ros::ok() && stream.next(robot, scan) && scan.stamp <= seq_.end) {
      if (lockstep_)
        lockstep_->beforeScan(robot, scan.stamp);
      else
        waitForWallTime(scan.stamp);
      publishScan(robot, scan);
      reportProgress(scan.stamp);
    }
  }

  /// The last acks, the radio through the end, the recorder's intake complete; then /player/done.
  void finish() {
    if (lockstep_) lockstep_->finish(seq_.end);
    publishClock(seq_.end);
    const ros::WallTime linger = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - linger).toSec() < o_.end_linger) {
      publishClock(seq_.end + toStampNs((ros::WallTime::now() - linger).toSec() * 1e-3));
      ros::WallDuration(0.05).sleep();
    }
    ROS_INFO("player: done, %zu scans in %.1f s wall for %.1f s of sequence", published_,
             (ros::WallTime::now() - wall_start_).toSec(), seq_.seconds());
    done_pub_.publish(std_msgs::Empty());
    ros::WallDuration(0.5).sleep();
  }

 private:
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
    sequence_pub_.publish(ros_glue::teamSequenceToMsg(seq_.config, seq_.timing));
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
  ros_glue::PlayedSequence seq_;
  std::unique_ptr<ros_glue::RobotPlayback> robot_playback_;  ///< robot-side playback: the robots read the trials
  std::optional<ros_glue::LockstepLink> lockstep_;  ///< lockstep mode: the team's event order through the nodes
  std::atomic<std::uint64_t> broker_delivered_{0};  ///< /comm/stats, for the progress line
  std::size_t published_ = 0;
  pipeline::ReferenceStream reference_stream_;  ///< the reference poses sent beside the scans
  ros::WallTime wall_start_, last_progress_;
  ros::Publisher clock_pub_, progress_pub_, done_pub_, sequence_pub_;
  std::map<char, ros::Publisher> points_pub_, pose_pub_, trajectory_pub_;
  ros::Subscriber stats_sub_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros_glue::initNode(argc, argv, "player");
  return ros_glue::runNode("player", [] {
    ros::NodeHandle nh, pnh("~");
    const Options options = readOptions(pnh);
    ros::AsyncSpinner spinner(1);  // robot-side playback: the robots' announcements arrive while resolving
    spinner.start();
    std::unique_ptr<ros_glue::RobotPlayback> robot_playback;
    const auto from_robots = [&](const pipeline::SequenceConfig& config) {
      std::vector<char> robots;
      for (const auto& t : config.trials) robots.push_back(t.robot);
      robot_playback = std::make_unique<ros_glue::RobotPlayback>(nh, robots, options.connect_timeout);
      return robot_playback->trials(config);
    };
    ros_glue::PlayedSequence sequence = options.robotPlayback()
                                            ? ros_glue::resolvePlayedSequence(options.sequence, from_robots)
                                            : ros_glue::resolvePlayedSequence(options.sequence);
    ROS_INFO("player: sequence %s, %zu robots, %.1f s, mode %s, trials played %s", sequence.config.name.c_str(),
             sequence.config.trials.size(), sequence.seconds(), options.mode.c_str(),
             options.robotPlayback() ? "on the robots' machines" : "here");
    Player player(nh, options, std::move(sequence), std::move(robot_playback));
    player.connect();
    player.play();
    player.finish();
  });
}
