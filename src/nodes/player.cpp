// player: replays a sequence's trials as one team (trials::resolveSequence resolves it) in the offline driver's
// event order (lockstep) or at wall speed (real time), watches its peers and ends the run (ros_glue::RunStop).
// Topics, parameters, lockstep, robot-side playback and the peer policy: docs/nodes.md.
#include <ros/ros.h>

#include <memory>
#include <optional>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/ros/lockstep_link.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/ros/playback_publisher.hpp"
#include "cosmo/ros/played_sequence.hpp"
#include "cosmo/ros/player_options.hpp"
#include "cosmo/ros/robot_playback.hpp"
#include "cosmo/ros/run_stop.hpp"
#include "cosmo/ros/team_listener.hpp"
#include "cosmo/trials/bag_scan_source.hpp"

using namespace cosmo;

namespace {

class Player {
 public:
  Player(ros::NodeHandle& nh, ros_glue::PlayerOptions options, trials::ResolvedSequence sequence,
         std::unique_ptr<ros_glue::RobotPlayback> robot_playback, const ros_glue::RunStop& stop)
      : o_(std::move(options)),
        stop_(stop),
        seq_(std::move(sequence)),
        robot_playback_(std::move(robot_playback)),
        team_(nh, seq_.robots(), !o_.lockstep()),
        publisher_(nh, seq_.robots(), o_.world_frame, !robot_playback_, ros_glue::playedPointTimes(o_.lockstep())),
        peers_("player", ros_glue::playerPeerWatch(o_, seq_.robots())) {
    if (o_.lockstep()) {
      ros_glue::LockstepLink::Peers peers{&peers_, {}, o_.wait_for_broker ? o_.broker_node : "", o_.recorder_node};
      for (char r : seq_.robots()) peers.frontends[r] = o_.frontendNode(r);
      lockstep_.emplace(nh, seq_.robots(), std::move(peers));
    }
    publisher_.announce(seq_.config, seq_.timing, run_id_, seq_.references);
    ROS_INFO("player: run %s", run_id_.c_str());
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
      peers_.setLinkCheck(
          o_.frontendNode(r),
          [this, r] {
            const bool reference = seq_.references.at(r).empty() || publisher_.referenceHeard(r);
            const bool points = robot_playback_ || publisher_.pointsHeard(r);  // else the robot's own
            return points && reference && (!lockstep_ || lockstep_->frontendLinked(r));
          },
          std::string("/") + r + "/ack");
    if (robot_playback_)
      for (char r : seq_.robots())
        peers_.setLinkCheck(
            o_.trialPlayerNode(r), [this, r] { return robot_playback_->listening(r); }, ros_glue::scansAheadTopic(r));
    if (lockstep_ && o_.wait_for_broker)
      peers_.setLinkCheck(
          o_.broker_node, [this] { return lockstep_->brokerLinked(); }, "/comm/step_done");
    peers_.start();
    while (ros::ok() && !peers_.connected()) {
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
      ros::WallDuration(0.05).sleep();
    }
    if (lockstep_) lockstep_->useBroker(o_.wait_for_broker && lockstep_->brokerLinked());
  }

  /// Publishes every scan up to the end, in the team's order (lockstep) or at wall speed (real time).
  void play() {
    sequence::MergedScanStream stream = robot_playback_ ? sequence::MergedScanStream(robot_playback_->sources([this] {
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
    }),
                                                                                     seq_.timing)
                                                        : trials::openSequenceStream(seq_.config, seq_.timing);
    publisher_.clock(seq_.timing.start());
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
    publisher_.clock(seq_.end);
    const ros::WallTime linger = ros::WallTime::now();
    ros::WallTime next_notice = linger + ros::WallDuration(10.0);
    while (ros::ok()) {
      const ros::WallTime now = ros::WallTime::now();
      std::string behind;
      if ((now - linger).toSec() >= o_.end_linger &&
          (lockstep_ ||
           (behind = team_.behind(seq_.robots(), [this](char r) { return peers_.alive(o_.frontendNode(r)); })).empty()))
        break;
      if (const auto stop = peers_.stopReason()) throw ros_glue::RunStopped(*stop);
      if (now >= next_notice) {
        ROS_INFO("player: waiting for robots %s to process their waiting scans and the recorder to hold what they sent",
                 behind.c_str());
        next_notice = now + ros::WallDuration(10.0);
      }
      publisher_.clock(seq_.end + toStampNs((now - linger).toSec() * 1e-3));
      ros::WallDuration(0.05).sleep();
    }
    ROS_INFO("player: done, %zu scans in %.1f s wall for %.1f s of sequence", published_,
             (ros::WallTime::now() - wall_start_).toSec(), seq_.seconds());
    stop_.done();
    publisher_.done();
    ros::WallDuration(0.5).sleep();
  }

  /// Tells the recorder why the run stops (/player/abort) and waits for it to write the dataset so far.
  void stopRun(const std::string& reason) {
    stop_.stopped(reason);
    const bool recorder = !o_.recorder_node.empty() && peers_.alive(o_.recorder_node);
    if (recorder &&
        ros_glue::waitUntil([this] { return team_.writtenIncomplete().has_value(); }, ros_glue::wallDeadline(30.0))) {
      ROS_ERROR("player: the recorder wrote the dataset so far, marked incomplete: %s",
                team_.writtenIncomplete()->c_str());
    } else {
      ROS_ERROR("player: the recorder did not confirm a write (%s); what it acknowledged is in its journal",
                recorder ? "no answer within 30 s" : "it is not running");
    }
  }

  void waitForWallTime(StampNs stamp) {
    const ros::WallTime due = wall_start_ + ros::WallDuration(toSeconds(stamp - seq_.timing.start()) / o_.rate);
    const ros::WallTime now = ros::WallTime::now();
    if (due > now) (due - now).sleep();
  }

  /// The clock, the reference poses up to the scan and its TF, then the scan.
  void publishScan(char robot, const Scan& scan) {
    publisher_.beforeScan(robot, scan.stamp, seq_.references[robot]);
    if (robot_playback_)  // the robot publishes it on its own machine
      robot_playback_->play(robot, seq_.timing.of(robot).toRecorded(scan.stamp), scan.stamp);
    else
      publisher_.points(robot, scan);
    if (lockstep_) lockstep_->scanHandedOver(robot, scan.stamp);
    ++published_;
  }

  void reportProgress(StampNs stamp) {
    const ros::WallTime now = ros::WallTime::now();
    if ((now - last_progress_).toSec() < 1.0) return;
    last_progress_ = now;
    char line[200];
    std::snprintf(line, sizeof line, "sequence time %.1f / %.1f s, %zu scans, %llu transfers delivered, %.1f s wall",
                  toSeconds(stamp - seq_.timing.start()), seq_.seconds(), published_,
                  static_cast<unsigned long long>(team_.delivered()), (now - wall_start_).toSec());
    publisher_.progress(line);
    ROS_INFO("player: %s", line);
  }

  ros_glue::PlayerOptions o_;
  const ros_glue::RunStop& stop_;  ///< the status file and /player/abort
  trials::ResolvedSequence seq_;
  std::unique_ptr<ros_glue::RobotPlayback> robot_playback_;  ///< robot-side playback: the robots read the trials
  std::string run_id_ = ros_glue::randomRunId();             ///< the recorder's journal belongs to this run
  std::optional<ros_glue::LockstepLink> lockstep_;  ///< lockstep mode: the team's event order through the nodes
  std::size_t published_ = 0;
  ros::WallTime wall_start_, last_progress_;
  ros_glue::TeamListener team_;  ///< the broker's, the recorder's and the front-ends' progress
  ros_glue::PlaybackPublisher publisher_;
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
    const ros_glue::PlayerOptions options = ros_glue::readPlayerOptions(pnh);
    stop.emplace(nh, options.status_file);
    ros::AsyncSpinner spinner(1);  // robot-side playback: the robots' announcements arrive while resolving
    spinner.start();
    std::unique_ptr<ros_glue::RobotPlayback> robot_playback;
    const auto from_robots = [&](const sequence::SequenceConfig& config) {
      std::vector<char> robots;
      for (const auto& t : config.trials) robots.push_back(t.robot);
      robot_playback = std::make_unique<ros_glue::RobotPlayback>(nh, robots, options.peers.connect_timeout,
                                                                 [&](char r) { return options.trialPlayerNode(r); });
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
