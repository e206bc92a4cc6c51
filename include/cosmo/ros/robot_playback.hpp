#pragma once
// Robot-side playback on ROS (sequence.launch playback:=robot): each robot's trial is read by a trial_player node
// on the robot's own machine, so raw scans never leave it. The base's player holds no scan: it takes each trial's
// span and reference from the robot's announcement (/<r>/played_trial, cosmo/PlayedTrial), merges the robots'
// read-ahead stamps (/<r>/scans_ahead, cosmo/ScansAhead) into the team's order with the merge it always uses, and
// asks each robot for its scans one by one (/<r>/play_scan, cosmo/PlayScan). pipeline/scan_read_ahead.hpp is the
// protocol without ROS; this is the base's side of it (the robot's side is the trial_player node).
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "cosmo/PlayScan.h"
#include "cosmo/PlayedTrial.h"
#include "cosmo/ScansAhead.h"
#include "cosmo/pipeline/scan_read_ahead.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/trial_basis.hpp"

namespace cosmo::ros_glue {

/// /<robot>/<name>: the robot-side playback topics.
std::string playedTrialTopic(char robot);
std::string scansAheadTopic(char robot);
std::string playScanTopic(char robot);

/// The robot side's announcement of its trial.
cosmo::PlayedTrial playedTrialMsg(const std::string& sequence, const pipeline::TrialConfig& trial,
                                  const pipeline::TrialBasis& basis, bool check_ok, const std::string& check);
/// Its basis; throws std::runtime_error naming the topic when the message is malformed.
pipeline::TrialBasis trialBasisFromMsg(const cosmo::PlayedTrial& msg);

class RobotPlayback {
 public:
  /// `connect_timeout`: wall seconds the robots' trial players have to announce their trials and listen.
  RobotPlayback(ros::NodeHandle& nh, const std::vector<char>& robots, double connect_timeout);

  /// Waits for every robot's trial (naming the robots not heard from every 5 s), prints the robots' pre-flight
  /// checks and returns the trials' bases. Throws std::runtime_error when a robot's check failed, when a robot
  /// plays another sequence or trial than `config` names, or when a robot is not heard within the timeout.
  std::map<char, pipeline::TrialBasis> trials(const pipeline::SequenceConfig& config);
  /// Waits until every trial player listens for requests (throws after the timeout, naming them).
  void connect();
  /// One source per robot, for the merge: the robot's announced stamps in recorded time, without points. Its
  /// next() waits for the robot's next announcement without a limit (a robot reading a slow disk is not a failure),
  /// naming the robot every 10 s; it throws when ROS shuts down or an announcement breaks the protocol.
  std::map<char, std::unique_ptr<pipeline::ScanSource>> sources();
  /// Asks `robot` to publish the scan stamped `recorded` (recorded time) stamped `stamp` (sequence time).
  void play(char robot, StampNs recorded, StampNs stamp);

 private:
  class Source;
  void onTrial(char robot, const cosmo::PlayedTrial& m);
  void onAhead(char robot, const cosmo::ScansAhead& m);
  std::vector<char> notHeard() const;  ///< with the mutex held

  std::vector<char> robots_;
  double connect_timeout_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<char, cosmo::PlayedTrial> trials_;
  std::map<char, pipeline::AnnouncedStamps> announced_;
  std::map<char, std::string> errors_;  ///< a robot's broken announcement
  std::vector<ros::Subscriber> subs_;
  std::map<char, ros::Publisher> play_pubs_;
};

}  // namespace cosmo::ros_glue
