#include "cosmo/ros/player_options.hpp"

#include <cstdio>
#include <random>
#include <stdexcept>

#include "cosmo/ros/resolved_sequence.hpp"

namespace cosmo::ros_glue {
namespace {

std::string forRobot(std::string name, char robot) {
  if (const auto at = name.find("{r}"); at != std::string::npos) name.replace(at, 3, std::string(1, robot));
  return name;
}

}  // namespace

std::string PlayerOptions::frontendNode(char robot) const { return forRobot(frontend_node, robot); }
std::string PlayerOptions::trialPlayerNode(char robot) const { return forRobot(trial_player_node, robot); }

PlayerOptions readPlayerOptions(const ros::NodeHandle& pnh) {
  PlayerOptions o;
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
    throw std::runtime_error(
        "~playback must be base (this node reads the trials) or robot (each robot's "
        "trial_player does), got '" +
        o.playback + "'");
  o.sequence.check = !o.robotPlayback();  // the robots' trial players check their own trials
  if (!(o.rate > 0)) o.rate = 1.0;
  if (o.end_linger < 0) o.end_linger = o.lockstep() ? 0.0 : 3.0;
  return o;
}

live::PeerWatch playerPeerWatch(const PlayerOptions& o, const std::vector<char>& robots) {
  live::PeerWatch watch(o.lockstep() ? live::RunMode::Lockstep : live::RunMode::Realtime, o.peers);
  for (char r : robots)
    watch.expect(o.frontendNode(r), live::PeerRole::Frontend, std::string("the front-end of robot ") + r);
  if (o.robotPlayback())  // a robot's trial player is a front-end's input: the same policy
    for (char r : robots)
      watch.expect(o.trialPlayerNode(r), live::PeerRole::Frontend, std::string("the trial player of robot ") + r);
  if (o.wait_for_broker && !o.broker_node.empty())
    watch.expect(o.broker_node, live::PeerRole::Broker, "the comm_broker");
  if (!o.recorder_node.empty()) watch.expect(o.recorder_node, live::PeerRole::Recorder, "the recorder");
  return watch;
}

std::string randomRunId() {
  std::random_device rd;
  char id[32];
  std::snprintf(id, sizeof id, "%08x%08x", rd(), rd());
  return id;
}

}  // namespace cosmo::ros_glue
