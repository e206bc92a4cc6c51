#pragma once
// The player node's parameters (docs/nodes.md), read and checked, and what follows from them: the sequence choice
// (shared with the trial_player), the peers it watches and the node name of each robot's peers.
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "cosmo/live/peer_watch.hpp"
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::ros_glue {

struct PlayerOptions {
  trials::SequenceChoice sequence;
  std::string mode = "lockstep", world_frame = "world", status_file, playback = "base";
  std::string frontend_node = "/{r}/frontend", broker_node = "/comm_broker", recorder_node = "/recorder";
  std::string trial_player_node = "/{r}/trial_player";
  live::PeerPolicyParams peers;
  double rate = 1.0, end_linger = -1.0;
  bool wait_for_broker = true;

  bool lockstep() const { return mode == "lockstep"; }
  bool robotPlayback() const { return playback == "robot"; }
  std::string frontendNode(char robot) const;
  std::string trialPlayerNode(char robot) const;
};

/// Every parameter; throws std::runtime_error naming the one that is out of range.
PlayerOptions readPlayerOptions(const ros::NodeHandle& pnh);
/// The peers the player watches: a front-end per robot (and its trial player with robot-side playback), the
/// broker unless ~wait_for_broker is off, the recorder.
live::PeerWatch playerPeerWatch(const PlayerOptions& o, const std::vector<char>& robots);
/// A random id of a run (the recorder's journal names it).
std::string randomRunId();

}  // namespace cosmo::ros_glue
