#pragma once
// The recorder node's parameters (docs/nodes.md), read and checked, and what it learns before it records: which
// run and robots (the player's sequence, or ~robots for a live team) and the sequence's metadata lines.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/dataset/recorder_session.hpp"
#include "cosmo/live/peer_watch.hpp"
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::ros_glue {

struct RecorderOptions {
  std::string name = "cosmo", output_dir = ".";
  trials::SequenceChoice sequence;  ///< ~sequence, ~data_root, ~simulate_config, ~noise_models, ~config_dir
  std::string player_node = "/player", run_id;
  dataset::OutlierRule rule = dataset::OutlierRule::Fidelity;
  double autosave_period = 30.0, progress_period = 5.0;

  /// <output_dir>/<name>.jrl
  std::string jrlPath() const;
  /// The noise models it labels with: ~noise_models, else the sequence's (sequence/sequence_noise_models.hpp).
  dataset::NoiseModels noiseModels() const;
};

/// Every parameter; throws std::runtime_error naming the one that is out of range.
RecorderOptions readRecorderOptions(const ros::NodeHandle& pnh);

/// The run and its robots.
struct RecorderRun {
  std::string id;
  std::vector<char> robots;
  bool with_player = false;  ///< the team comes from the player (its sequence names them)
};
/// ~robots (a live team; the run is ~run_id, else /run_id, else "live"), else the player's sequence, waited for
/// until it comes or `stopped()`; throws std::runtime_error when it never came or names no run.
RecorderRun waitForRun(ros::NodeHandle& nh, const ros::NodeHandle& pnh, const std::string& run_id,
                       const std::function<bool()>& stopped);

/// The sequence's metadata lines (trials/sequence_metadata.hpp): of the sequence the player announced, else of
/// ~sequence; none while neither can be read (warned once).
std::optional<dataset::MetadataLines> sequenceMetadataLines(const RecorderOptions& o);

/// The player, watched as a lockstep peer (the recorder stops the run when it dies before the end).
live::PeerWatch playerWatch(const std::string& node);

/// The journal's note (a torn tail cut off, another run's journal moved aside), and whether the session resumed it, in
/// the log.
void logJournalOpening(const dataset::RecorderSession& session);

/// A random id of this recorder's session (a restart is a new session of the same run).
std::string randomSessionId();

}  // namespace cosmo::ros_glue
