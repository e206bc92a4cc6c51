#include "cosmo/ros/robot_playback.hpp"

#include <chrono>
#include <stdexcept>

#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

namespace cosmo::ros_glue {

namespace {

using Clock = std::chrono::steady_clock;

std::string list(const std::vector<char>& robots) {
  std::string s;
  for (char r : robots) s += (s.empty() ? "" : ", ") + std::string(1, r);
  return s;
}

}  // namespace

std::string playedTrialTopic(char robot) { return std::string("/") + robot + "/played_trial"; }
std::string scansAheadTopic(char robot) { return std::string("/") + robot + "/scans_ahead"; }
std::string playScanTopic(char robot) { return std::string("/") + robot + "/play_scan"; }

cosmo::PlayedTrial playedTrialMsg(const std::string& sequence, const pipeline::TrialConfig& trial,
                                  const pipeline::TrialBasis& basis, bool check_ok, const std::string& check) {
  cosmo::PlayedTrial m;
  m.sequence = sequence;
  m.robot = std::string(1, trial.robot);
  m.trial = trial.name;
  m.ok = check_ok;
  m.check = check;
  m.first = basis.span.first;
  m.last = basis.span.last;
  m.body_reference = trajectoryToMsg(trial.robot, basis.body_reference, "");
  return m;
}

pipeline::TrialBasis trialBasisFromMsg(const cosmo::PlayedTrial& m) {
  const std::string topic = m.robot.size() == 1 ? playedTrialTopic(m.robot[0]) : "played_trial";
  if (m.robot.size() != 1) throw std::runtime_error(topic + ": robot '" + m.robot + "' is not one character");
  if (m.first > m.last)
    throw std::runtime_error(topic + ": first " + std::to_string(m.first) + " ns is after last " +
                             std::to_string(m.last) + " ns");
  pipeline::TrialBasis basis;
  basis.span = {m.robot[0], static_cast<StampNs>(m.first), static_cast<StampNs>(m.last)};
  basis.body_reference = trajectoryFromMsg(m.body_reference, topic + " body_reference");
  return basis;
}

/// The merge's source of one robot: its announced stamps.
class RobotPlayback::Source : public pipeline::ScanSource {
 public:
  Source(RobotPlayback& playback, char robot) : p_(playback), robot_(robot) {}

  bool next(Scan& scan) override {
    std::unique_lock<std::mutex> lock(p_.mutex_);
    Clock::time_point noted = Clock::now();
    for (;;) {
      if (const auto e = p_.errors_.find(robot_); e != p_.errors_.end()) throw std::runtime_error(e->second);
      pipeline::AnnouncedStamps& announced = p_.announced_[robot_];
      if (const std::optional<StampNs> stamp = announced.take()) {
        scan = Scan();
        scan.stamp = *stamp;
        return true;
      }
      if (announced.exhausted()) return false;
      if (!ros::ok()) throw std::runtime_error(std::string("ROS shut down while waiting for robot ") + robot_ + "'s scans");
      if (Clock::now() - noted >= std::chrono::seconds(10)) {
        noted = Clock::now();
        ROS_INFO("player: waiting for robot %c's trial player to read its next scan (%s; %zu scans played)", robot_,
                 scansAheadTopic(robot_).c_str(), announced.taken());
      }
      p_.changed_.wait_for(lock, std::chrono::milliseconds(200));
    }
  }

 private:
  RobotPlayback& p_;
  char robot_;
};

RobotPlayback::RobotPlayback(ros::NodeHandle& nh, const std::vector<char>& robots, double connect_timeout)
    : robots_(robots), connect_timeout_(connect_timeout) {
  for (char r : robots_) {
    announced_[r];
    subs_.push_back(nh.subscribe<cosmo::PlayedTrial>(
        playedTrialTopic(r), 1, [this, r](const cosmo::PlayedTrial::ConstPtr& m) { onTrial(r, *m); }));
    subs_.push_back(nh.subscribe<cosmo::ScansAhead>(
        scansAheadTopic(r), 100, [this, r](const cosmo::ScansAhead::ConstPtr& m) { onAhead(r, *m); }));
    play_pubs_[r] = nh.advertise<cosmo::PlayScan>(playScanTopic(r), 100);
  }
}

void RobotPlayback::onTrial(char robot, const cosmo::PlayedTrial& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  trials_[robot] = m;
  changed_.notify_all();
}

void RobotPlayback::onAhead(char robot, const cosmo::ScansAhead& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    if (!m.error.empty()) throw std::runtime_error("robot " + std::string(1, robot) + "'s trial cannot go on: " + m.error);
    announced_[robot].announce(std::vector<StampNs>(m.stamps.begin(), m.stamps.end()), m.end);
  } catch (const std::exception& e) { errors_.emplace(robot, scansAheadTopic(robot) + ": " + e.what()); }
  changed_.notify_all();
}

std::vector<char> RobotPlayback::notHeard() const {
  std::vector<char> missing;
  for (char r : robots_)
    if (!trials_.count(r)) missing.push_back(r);
  return missing;
}

std::map<char, pipeline::TrialBasis> RobotPlayback::trials(const pipeline::SequenceConfig& config) {
  std::unique_lock<std::mutex> lock(mutex_);
  const Clock::time_point start = Clock::now(), deadline = start + std::chrono::duration_cast<Clock::duration>(
                                                                        std::chrono::duration<double>(connect_timeout_));
  Clock::time_point noted = start;
  for (std::vector<char> missing = notHeard(); !missing.empty(); missing = notHeard()) {
    if (!ros::ok()) throw std::runtime_error("ROS shut down while waiting for the robots' trials");
    if (Clock::now() >= deadline)
      throw std::runtime_error("robots " + list(missing) + ": no trial announced (/<r>/played_trial) within " +
                               std::to_string(static_cast<int>(connect_timeout_)) +
                               " s: is robot.launch playback:=robot running on each robot's machine, with this "
                               "master in its ROS_MASTER_URI?");
    if (Clock::now() - noted >= std::chrono::seconds(5)) {
      noted = Clock::now();
      ROS_INFO("player: robot-side playback: waiting for the trials of robots %s (/<r>/played_trial from "
               "robot.launch playback:=robot on each robot's machine)",
               list(missing).c_str());
    }
    changed_.wait_for(lock, std::chrono::milliseconds(200));
  }
  std::map<char, pipeline::TrialBasis> basis;
  std::string checks;
  bool ok = true;
  for (const auto& t : config.trials) {
    const cosmo::PlayedTrial& m = trials_.at(t.robot);
    if (m.sequence != config.name || m.trial != t.name)
      throw std::runtime_error(std::string("robot ") + t.robot + " plays trial '" + m.trial + "' of sequence '" +
                               m.sequence + "', but " + config.path + " names trial '" + t.name + "' of sequence '" +
                               config.name + "': give both machines the same sequence config");
    checks += m.check;
    ok = ok && m.ok;
    basis[t.robot] = trialBasisFromMsg(m);
  }
  ROS_INFO("player: robot-side playback: the robots' pre-flight checks:\n%s", checks.c_str());
  if (!ok) throw std::runtime_error("a robot's pre-flight check failed (above)");
  return basis;
}

void RobotPlayback::connect() {
  const Clock::time_point start = Clock::now();
  Clock::time_point noted = start;
  for (;;) {
    std::vector<char> missing;
    for (auto& [r, pub] : play_pubs_)
      if (pub.getNumSubscribers() == 0) missing.push_back(r);
    if (missing.empty()) return;
    if (!ros::ok()) throw std::runtime_error("ROS shut down while waiting for the trial players");
    const double waited = std::chrono::duration<double>(Clock::now() - start).count();
    if (waited >= connect_timeout_)
      throw std::runtime_error("robots " + list(missing) + ": the trial player does not listen on /<r>/play_scan " +
                               "after " + std::to_string(static_cast<int>(connect_timeout_)) + " s");
    if (Clock::now() - noted >= std::chrono::seconds(5)) {
      noted = Clock::now();
      ROS_INFO("player: robot-side playback: waiting for the trial players of robots %s to listen (/<r>/play_scan)",
               list(missing).c_str());
    }
    ros::WallDuration(0.05).sleep();
  }
}

std::map<char, std::unique_ptr<pipeline::ScanSource>> RobotPlayback::sources() {
  std::map<char, std::unique_ptr<pipeline::ScanSource>> s;
  for (char r : robots_) s[r] = std::make_unique<Source>(*this, r);
  return s;
}

void RobotPlayback::play(char robot, StampNs recorded, StampNs stamp) {
  cosmo::PlayScan m;
  m.recorded = static_cast<std::uint64_t>(recorded);
  m.stamp = stampToRos(stamp);
  play_pubs_.at(robot).publish(m);
}

}  // namespace cosmo::ros_glue
