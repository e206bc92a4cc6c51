#pragma once
// Robot-side playback on ROS (sequence.launch playback:=robot): each robot's trial is read by a trial_player node
// on the robot's own machine, so raw scans never leave it. The base's player holds no scan: it takes each trial's
// span and reference from the robot's announcement (/<r>/played_trial, cosmo/PlayedTrial), merges the robots'
// read-ahead stamps (/<r>/scans_ahead, cosmo/ScansAhead) into the team's order with the merge it always uses, and
// asks each robot for its scans one by one (/<r>/play_scan, cosmo/PlayScan). sequence/scan_read_ahead.hpp is the
// protocol without ROS; this is the base's side of it (the robot's side is the trial_player node).
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "cosmo/PlayScan.h"
#include "cosmo/PlayedTrial.h"
#include "cosmo/ScansAhead.h"
#include "cosmo/sequence/scan_read_ahead.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/trial_basis.hpp"

namespace cosmo::ros_glue {

/// /<robot>/<name>: the robot-side playback topics.
std::string playedTrialTopic(char robot);
std::string scansAheadTopic(char robot);
std::string playScanTopic(char robot);

/// The robot side's announcement of its trial.
cosmo::PlayedTrial playedTrialMsg(const std::string& sequence, const sequence::TrialConfig& trial,
                                  const sequence::TrialBasis& basis, bool check_ok, const std::string& check);
/// The robot side: checks `robot`'s trial alone (trials::checkTrial, noise models looked up in `config_dir`), logs
/// the check, reads the trial's basis when it passed and announces both on `pub` (advertised here on
/// playedTrialTopic, latched: keep it). True when the check passed.
bool announcePlayedTrial(ros::NodeHandle& nh, const sequence::SequenceConfig& config, char robot,
                         const std::string& config_dir, ros::Publisher& pub);
/// Its basis; throws std::runtime_error naming the topic when the message is malformed.
sequence::TrialBasis trialBasisFromMsg(const cosmo::PlayedTrial& msg);

class RobotPlayback {
 public:
  /// `connect_timeout`: wall seconds a robot's trial player may take to register and answer; `node`: its node name
  /// for a robot (e.g. "/a/trial_player").
  RobotPlayback(ros::NodeHandle& nh, const std::vector<char>& robots, double connect_timeout,
                std::function<std::string(char)> node);

  /// Waits for every robot's trial, prints the robots' pre-flight checks and returns the trials' bases. Every 5 s
  /// it names the robots not heard from and what their trial players are (probed as the peer watch does); one that
  /// answers is waited for without a limit (it may be generating the built-in sequence), one that does not after
  /// `connect_timeout` stops the run: ros_glue::RunStopped naming it and the likely cause. Throws
  /// std::runtime_error when a robot's check failed or a robot plays another sequence or trial than `config` names.
  std::map<char, sequence::TrialBasis> trials(const sequence::SequenceConfig& config);
  /// `robot`'s trial player listens for requests (the player's link check of that peer).
  bool listening(char robot) const;
  /// One source per robot, for the merge: the robot's announced stamps in recorded time, without points. Its
  /// next() waits for the robot's next announcement without a limit (a robot reading a slow disk is not a failure),
  /// naming the robot every 10 s, and calls `check` while it waits (the peer policy: it throws to stop the run); it
  /// throws when ROS shuts down or an announcement breaks the protocol.
  std::map<char, std::unique_ptr<sequence::ScanSource>> sources(std::function<void()> check);
  /// Asks `robot` to publish the scan stamped `recorded` (recorded time) stamped `stamp` (sequence time).
  void play(char robot, StampNs recorded, StampNs stamp);

 private:
  class Source;
  void onTrial(char robot, const cosmo::PlayedTrial& m);
  void onAhead(char robot, const cosmo::ScansAhead& m);
  std::vector<char> notHeard() const;  ///< with the mutex held
  /// What robot's trial player is now (probed), and whether it answers.
  std::string describe(char robot, bool& alive) const;

  std::vector<char> robots_;
  double connect_timeout_;
  std::function<std::string(char)> node_;
  std::function<void()> check_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<char, cosmo::PlayedTrial> trials_;
  std::map<char, sequence::AnnouncedStamps> announced_;
  std::map<char, std::string> errors_;  ///< a robot's broken announcement
  std::vector<ros::Subscriber> subs_;
  std::map<char, ros::Publisher> play_pubs_;
};

}  // namespace cosmo::ros_glue
