// trial_player: one robot's trial read on the robot's machine (robot-side playback): announces its span and
// reference, plays the scans the base's player asks for. Topics and parameters: docs/nodes.md.
#include <ros/ros.h>

#include <memory>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/sequence/scan_read_ahead.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_playback.hpp"
#include "cosmo/ros/run_stop.hpp"

using namespace cosmo;

namespace {

struct Options {
  char robot = 'a';
  trials::SequenceChoice sequence;
  int read_ahead = 4;
  bool lockstep = true;
};

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  o.robot = ros_glue::nodeRobot(pnh);
  o.sequence = ros_glue::readSequenceChoice(pnh);
  pnh.param("read_ahead", o.read_ahead, o.read_ahead);
  pnh.param("lockstep", o.lockstep, o.lockstep);
  if (o.read_ahead < 2) throw std::runtime_error("~read_ahead must be at least 2, got " + std::to_string(o.read_ahead));
  return o;
}

class TrialPlayer {
 public:
  TrialPlayer(ros::NodeHandle& nh, const Options& o, std::unique_ptr<sequence::ScanSource> source)
      : robot_(o.robot),
        frame_(std::string(1, o.robot) + "/base_link"),
        encoding_(ros_glue::playedPointTimes(o.lockstep)),
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
  std::unique_ptr<sequence::ScanSource> source_;
  sequence::ScanReadAhead ahead_;
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
    const sequence::SequenceConfig config = trials::loadSequence(o.sequence);
    const sequence::TrialConfig& trial = config.trial(o.robot);
    ros::Publisher trial_pub;  // latched
    const bool ok = ros_glue::announcePlayedTrial(nh, config, o.robot, o.sequence.config_dir, trial_pub);
    std::unique_ptr<TrialPlayer> player;
    bool aborted = false;
    const ros_glue::RunEndListener run_end = ros_glue::listenForRunEnd(
        nh,
        [&] {
          ROS_INFO("trial_player %c: the player is done; %zu scans played here", o.robot,
                   player ? player->played() : 0);
          ros::shutdown();
        },
        [&](const std::string& why) {
          ROS_ERROR("trial_player %c: the run stops: %s", o.robot, why.c_str());
          aborted = true;
          ros::shutdown();
        });
    if (ok) {
      player = std::make_unique<TrialPlayer>(nh, o, trials::openTrialSource(trial));
      player->readAhead();
      ROS_INFO("trial_player %c: trial %s of sequence %s, read ahead; playing what the base's player asks for", o.robot,
               trial.name.c_str(), config.name.c_str());
    }
    ros::spin();  // one thread: requests are played in the order they come
    if (!ok) throw std::runtime_error("the pre-flight check of trial " + trial.name + " failed (above)");
    if (aborted) throw std::runtime_error("the player stopped the run (/player/abort)");
  });
}
