// trial_player: plays one robot's trial on that robot's own machine (robot-side playback: robot.launch
// playback:=robot; sequence.launch playback:=robot starts one per robot), so that its raw scans never cross the
// network: only what the front-end makes of them (keyframe scans for the radio, measurements, acks) does. The base's
// player decides the order (ros_glue::RobotPlayback); this node reads ahead and plays what it is asked for.
//
// Publishes  /<r>/played_trial (cosmo/PlayedTrial, latched) the trial's span and reference as read, and the
//                              pre-flight check of the trial
//            /<r>/scans_ahead  (cosmo/ScansAhead, latched) the stamps of the scans read and not played yet
//            /<r>/points       (sensor_msgs/PointCloud2) each scan the base's player asks for, stamped in sequence
//                              time, as the player publishes it
// Subscribes /<r>/play_scan    (cosmo/PlayScan) the base's requests, in the team's order
//            /player/done      (std_msgs/Empty, latched) the run is over: the node exits
//            /player/abort     (std_msgs/String, latched) the run stops: the node exits 1
// Params     ~robot (default: the namespace); ~sequence, ~data_root, ~simulate_config, ~simulate_out: the sequence
//            config, as the base's player is given it (empty ~sequence: the built-in one, generated here too);
//            only this robot's trial is read. ~read_ahead (scans held, >= 2; default 4), ~lockstep (the points'
//            time encoding, as the player's: true in lockstep).
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>

#include <memory>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/scan_read_ahead.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/played_sequence.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/robot_playback.hpp"
#include "cosmo/ros/trial_probe.hpp"

using namespace cosmo;

namespace {

struct Options {
  char robot = 'a';
  ros_glue::SequenceChoice sequence;
  int read_ahead = 4;
  bool lockstep = true;
};

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  std::string ns = ros::this_node::getNamespace(), robot;
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  pnh.param<std::string>("robot", robot, ns);
  if (robot.size() != 1 || robot[0] < 'a' || robot[0] > 'z')
    throw std::runtime_error("~robot must be one lower-case letter (or run in namespace /<r>), got '" + robot + "'");
  o.robot = robot[0];
  pnh.param("sequence", o.sequence.sequence, o.sequence.sequence);
  pnh.param("data_root", o.sequence.data_root, o.sequence.data_root);
  pnh.param("simulate_config", o.sequence.simulate_config, o.sequence.simulate_config);
  pnh.param("simulate_out", o.sequence.simulate_out, o.sequence.simulate_out);
  pnh.param("read_ahead", o.read_ahead, o.read_ahead);
  pnh.param("lockstep", o.lockstep, o.lockstep);
  if (o.read_ahead < 2) throw std::runtime_error("~read_ahead must be at least 2, got " + std::to_string(o.read_ahead));
  return o;
}

/// The pre-flight check of this robot's trial alone, as the player checks every trial.
bool checkTrial(const pipeline::SequenceConfig& config, const pipeline::TrialConfig& trial, std::string& text) {
  pipeline::SequenceConfig alone = config;
  alone.trials = {trial};
  return ros_glue::checkSequence(alone, pipeline::chooseNoiseModels(config, pipeline::defaultConfigDir()), text);
}

class TrialPlayer {
 public:
  TrialPlayer(ros::NodeHandle& nh, const Options& o, std::unique_ptr<pipeline::ScanSource> source)
      : robot_(o.robot),
        frame_(std::string(1, o.robot) + "/base_link"),
        encoding_(o.lockstep ? ros_glue::PointTimeEncoding::RelativeSeconds : ros_glue::PointTimeEncoding::OusterNs),
        source_(std::move(source)),
        ahead_(static_cast<std::size_t>(o.read_ahead)) {
    points_pub_ = nh.advertise<sensor_msgs::PointCloud2>(std::string("/") + robot_ + "/points", 5);
    ahead_pub_ = nh.advertise<cosmo::ScansAhead>(ros_glue::scansAheadTopic(robot_), 1, true);
    play_sub_ = nh.subscribe(ros_glue::playScanTopic(robot_), 100, &TrialPlayer::onPlay, this);
  }

  /// Reads until the read-ahead is full (or the trial ends), announcing the stamps after every scan.
  void readAhead() {
    while (ahead_.wantsMore() && readOne()) announce();
    announce();
  }

  std::size_t played() const { return played_; }

 private:
  /// One scan into the read-ahead; false at the trial's end or when it cannot go on (error_, announced).
  bool readOne() {
    if (!error_.empty() || ahead_.ended()) return false;
    Scan scan;
    try {
      if (!source_->next(scan)) {
        ahead_.endOfTrial();
        return false;
      }
    } catch (const std::exception& e) {
      error_ = e.what();
      ROS_FATAL("trial_player %c: %s", robot_, e.what());
      return false;
    }
    ahead_.add(std::move(scan));
    return true;
  }

  void onPlay(const cosmo::PlayScan::ConstPtr& m) {
    const StampNs recorded = static_cast<StampNs>(m->recorded);
    while (!ahead_.passOver(recorded) && readOne()) {}  // only after a restart is the base ahead of what is held
    try {
      Scan scan = ahead_.take(recorded);
      scan.stamp = m->stamp.toNSec();
      points_pub_.publish(ros_glue::toPointCloud2(scan, frame_, encoding_));
      ++played_;
    } catch (const std::exception& e) {
      error_ = ros_glue::playScanTopic(robot_) + ": " + e.what();
      ROS_FATAL("trial_player %c: %s", robot_, error_.c_str());
    }
    readAhead();
  }

  void announce() {
    cosmo::ScansAhead m;
    for (StampNs s : ahead_.stamps()) m.stamps.push_back(static_cast<std::uint64_t>(s));
    m.end = ahead_.ended();
    m.error = error_;
    ahead_pub_.publish(m);
  }

  char robot_;
  std::string frame_;
  ros_glue::PointTimeEncoding encoding_;
  std::unique_ptr<pipeline::ScanSource> source_;
  pipeline::ScanReadAhead ahead_;
  std::string error_;  ///< the trial cannot go on (announced: the base's player stops with it)
  std::size_t played_ = 0;
  ros::Publisher points_pub_, ahead_pub_;
  ros::Subscriber play_sub_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros_glue::initNode(argc, argv, "trial_player");
  return ros_glue::runNode("trial_player", [] {
    ros::NodeHandle nh, pnh("~");
    const Options o = readOptions(pnh);
    const pipeline::SequenceConfig config = ros_glue::loadSequenceChoice(o.sequence);
    const pipeline::TrialConfig& trial = config.trial(o.robot);
    std::string check;
    const bool ok = checkTrial(config, trial, check);
    ROS_INFO("trial_player %c: pre-flight check of trial %s:\n%s", o.robot, trial.name.c_str(), check.c_str());
    pipeline::TrialBasis basis;
    if (ok) basis = ros_glue::readTrialBasis(trial);
    ros::Publisher trial_pub = nh.advertise<cosmo::PlayedTrial>(ros_glue::playedTrialTopic(o.robot), 1, true);
    trial_pub.publish(ros_glue::playedTrialMsg(config.name, trial, basis, ok, check));
    std::unique_ptr<TrialPlayer> player;
    bool aborted = false;
    ros::Subscriber abort_sub = nh.subscribe<std_msgs::String>(
        "/player/abort", 1, boost::function<void(const std_msgs::String::ConstPtr&)>([&](const std_msgs::String::ConstPtr& m) {
          ROS_ERROR("trial_player %c: the run stops: %s", o.robot, m->data.c_str());
          aborted = true;
          ros::shutdown();
        }));
    ros::Subscriber done_sub = nh.subscribe<std_msgs::Empty>(
        "/player/done", 1, boost::function<void(const std_msgs::Empty::ConstPtr&)>([&](const std_msgs::Empty::ConstPtr&) {
          ROS_INFO("trial_player %c: the player is done; %zu scans played here", o.robot, player ? player->played() : 0);
          ros::shutdown();
        }));
    if (ok) {
      player = std::make_unique<TrialPlayer>(nh, o, ros_glue::openTrialSource(trial));
      player->readAhead();
      ROS_INFO("trial_player %c: trial %s of sequence %s, read ahead; playing what the base's player asks for",
               o.robot, trial.name.c_str(), config.name.c_str());
    }
    ros::spin();  // one thread: requests are played in the order they come
    if (!ok) throw std::runtime_error("the pre-flight check of trial " + trial.name + " failed (above)");
    if (aborted) throw std::runtime_error("the player stopped the run (/player/abort)");
  });
}
