#include "cosmo/ros/robot_playback.hpp"

#include <chrono>
#include <stdexcept>

#include "cosmo/live/peer_address_hint.hpp"
#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/trial_probe.hpp"

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

cosmo::PlayedTrial playedTrialMsg(const std::string& sequence, const sequence::TrialConfig& trial,
                                  const sequence::TrialBasis& basis, bool check_ok, const std::string& check) {
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

bool announcePlayedTrial(ros::NodeHandle& nh, const sequence::SequenceConfig& config, char robot,
                         const std::string& config_dir, ros::Publisher& pub) {
  const sequence::TrialConfig& trial = config.trial(robot);
  std::string check;
  const bool ok = trials::checkTrial(config, robot, config_dir, check);
  ROS_INFO("trial_player %c: pre-flight check of trial %s:\n%s", robot, trial.name.c_str(), check.c_str());
  sequence::TrialBasis basis;
  if (ok) basis = trials::readTrialBasis(trial);
  pub = nh.advertise<cosmo::PlayedTrial>(playedTrialTopic(robot), 1, true);
  pub.publish(playedTrialMsg(config.name, trial, basis, ok, check));
  return ok;
}

sequence::TrialBasis trialBasisFromMsg(const cosmo::PlayedTrial& m) {
  const std::string topic = m.robot.size() == 1 ? playedTrialTopic(m.robot[0]) : "played_trial";
  if (m.robot.size() != 1) throw std::runtime_error(topic + ": robot '" + m.robot + "' is not one character");
  if (m.first > m.last)
    throw std::runtime_error(topic + ": first " + std::to_string(m.first) + " ns is after last " +
                             std::to_string(m.last) + " ns");
  sequence::TrialBasis basis;
  basis.span = {m.robot[0], static_cast<StampNs>(m.first), static_cast<StampNs>(m.last)};
  basis.body_reference = trajectoryFromMsg(m.body_reference, topic + " body_reference");
  return basis;
}

/// The merge's source of one robot: its announced stamps.
class RobotPlayback::Source : public sequence::ScanSource {
 public:
  Source(RobotPlayback& playback, char robot) : p_(playback), robot_(robot) {}

  bool next(Scan& scan) override {
    std::unique_lock<std::mutex> lock(p_.mutex_);
    Clock::time_point noted = Clock::now();
    for (;;) {
      if (const auto e = p_.errors_.find(robot_); e != p_.errors_.end()) throw std::runtime_error(e->second);
      sequence::AnnouncedStamps& announced = p_.announced_[robot_];
      if (const std::optional<StampNs> stamp = announced.take()) {
        scan = Scan();
        scan.stamp = *stamp;
        return true;
      }
      if (announced.exhausted()) return false;
      if (!ros::ok())
        throw std::runtime_error(std::string("ROS shut down while waiting for robot ") + robot_ + "'s scans");
      if (p_.check_) {
        lock.unlock();  // the check may take the peer monitor's lock
        p_.check_();
        lock.lock();
      }
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

RobotPlayback::RobotPlayback(ros::NodeHandle& nh, const std::vector<char>& robots, double connect_timeout,
                             std::function<std::string(char)> node)
    : robots_(robots), connect_timeout_(connect_timeout), node_(std::move(node)) {
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
    if (!m.error.empty())
      throw std::runtime_error("robot " + std::string(1, robot) + "'s trial cannot go on: " + m.error);
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

std::string RobotPlayback::describe(char robot, bool& alive) const {
  const std::string node = node_(robot);
  const live::PeerProbe p = probePeer(node);
  alive = p.answered;
  if (p.answered)
    return std::string("robot ") + robot + ": its trial player " + node + " answers (pid " + std::to_string(p.pid) +
           ") and is preparing its trial (checking it; the built-in sequence is generated first)";
  if (p.registered)
    return std::string("robot ") + robot + ": its trial player " + node + " registered at " + p.uri +
           " but does not answer (" + p.error + "): " + (p.hint.empty() ? "did it die?" : p.hint);
  return std::string("robot ") + robot + ": its trial player " + node +
         " (robot.launch playback:=robot): " + live::neverRegisteredHint(ros::master::getURI());
}

std::map<char, sequence::TrialBasis> RobotPlayback::trials(const sequence::SequenceConfig& config) {
  const Clock::time_point start = Clock::now();
  Clock::time_point noted = start;
  bool late_seen = false;
  for (;;) {
    std::vector<char> missing;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait_for(lock, std::chrono::milliseconds(200), [&] { return notHeard().empty(); });
      missing = notHeard();
    }
    if (missing.empty()) break;
    if (!ros::ok()) throw std::runtime_error("ROS shut down while waiting for the robots' trials");
    const bool late = std::chrono::duration<double>(Clock::now() - start).count() >= connect_timeout_;
    if (Clock::now() - noted < std::chrono::seconds(5) && (!late || late_seen)) continue;
    late_seen = late;
    noted = Clock::now();
    std::string what, dead;
    for (char r : missing) {
      bool alive = false;
      const std::string d = describe(r, alive);
      what += "\n  " + d;
      if (!alive) dead += (dead.empty() ? "" : "; ") + d;
    }
    if (late && !dead.empty())
      throw RunStopped("no trial announced within " + std::to_string(static_cast<int>(connect_timeout_)) +
                       " s: " + dead);
    ROS_INFO("player: robot-side playback: waiting for the trials of robots %s (/<r>/played_trial):%s",
             list(missing).c_str(), what.c_str());
  }
  std::unique_lock<std::mutex> lock(mutex_);
  std::map<char, sequence::TrialBasis> basis;
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

bool RobotPlayback::listening(char robot) const { return play_pubs_.at(robot).getNumSubscribers() > 0; }

std::map<char, std::unique_ptr<sequence::ScanSource>> RobotPlayback::sources(std::function<void()> check) {
  check_ = std::move(check);
  std::map<char, std::unique_ptr<sequence::ScanSource>> s;
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
