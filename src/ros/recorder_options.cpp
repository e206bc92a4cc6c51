#include "cosmo/ros/recorder_options.hpp"

#include <ros/ros.h>

#include <filesystem>
#include <random>
#include <sstream>
#include <stdexcept>

#include "cosmo/TeamSequence.h"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/sequence_metadata.hpp"

namespace cosmo::ros_glue {

std::string RecorderOptions::jrlPath() const { return (std::filesystem::path(output_dir) / (name + ".jrl")).string(); }

dataset::NoiseModels RecorderOptions::noiseModels() const {
  return sequence::loadRunNoiseModels(sequence.noise_models, sequence.sequence, sequence.simulate_config,
                                      sequence.config_dir);
}

RecorderOptions readRecorderOptions(const ros::NodeHandle& pnh) {
  RecorderOptions o;
  std::string rule = "fidelity";
  pnh.param("name", o.name, o.name);
  pnh.param("output_dir", o.output_dir, o.output_dir);
  o.sequence = readSequenceChoice(pnh);
  pnh.param("outlier_rule", rule, rule);
  pnh.param("autosave_period", o.autosave_period, o.autosave_period);
  pnh.param("progress_period", o.progress_period, o.progress_period);
  pnh.param("player_node", o.player_node, o.player_node);
  pnh.param<std::string>("run_id", o.run_id, "");
  const auto parsed = dataset::parseOutlierRule(rule);
  if (!parsed) throw std::runtime_error("~outlier_rule: expected 'fidelity' or 'squared', got '" + rule + "'");
  o.rule = *parsed;
  return o;
}

RecorderRun waitForRun(ros::NodeHandle& nh, const ros::NodeHandle& pnh, const std::string& run_id,
                       const std::function<bool()>& stopped) {
  RecorderRun run;
  run.id = run_id;
  if (pnh.hasParam("robots")) {
    run.robots = readRobotsParam(pnh);
    if (run.id.empty()) ros::param::get("/run_id", run.id);
    if (run.id.empty()) run.id = "live";
    return run;
  }
  run.with_player = true;
  std::optional<cosmo::TeamSequence> sequence;
  auto sub = nh.subscribe<cosmo::TeamSequence>(kTeamSequenceTopic, 1,
                                               [&](const cosmo::TeamSequence::ConstPtr& m) { sequence = *m; });
  ROS_INFO("recorder: waiting for the player's sequence (%s): its run and robots", kTeamSequenceTopic);
  while (ros::ok() && !stopped() && !sequence) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  if (!sequence) throw std::runtime_error("shut down before the player's sequence arrived");
  run.robots.assign(sequence->robots.begin(), sequence->robots.end());
  if (run.id.empty()) run.id = sequence->run_id;
  if (run.id.empty()) throw std::runtime_error("the player's sequence names no run_id");
  return run;
}

std::optional<dataset::MetadataLines> sequenceMetadataLines(const RecorderOptions& o) {
  ResolvedSequence sequence{o.sequence.sequence, o.sequence.data_root, {}};
  if (const auto resolved = resolvedSequence()) sequence = *resolved;
  if (sequence.path.empty()) return std::nullopt;
  try {
    return trials::sequenceMetadata(sequence.load());
  } catch (const std::exception& e) {
    ROS_WARN_ONCE("recorder: the sequence's metadata (reference offset) of %s is not written: %s",
                  sequence.path.c_str(), e.what());
    return std::nullopt;
  }
}

live::PeerWatch playerWatch(const std::string& node) {
  live::PeerWatch watch(live::RunMode::Lockstep);
  watch.expect(node, live::PeerRole::Player, "the player");
  return watch;
}

void logJournalOpening(const dataset::RecorderSession& session) {
  const auto& opening = session.opening();
  if (!opening.note.empty()) ROS_WARN("recorder: journal %s: %s", session.journalPath().c_str(), opening.note.c_str());
  if (opening.resumed)
    ROS_INFO("recorder: resumed from journal %s (session %zu): %zu measurements; %s", session.journalPath().c_str(),
             session.sessions(), opening.records, session.recorder().progressLine().c_str());
  else
    ROS_INFO("recorder: journal %s", session.journalPath().c_str());
}

std::string randomSessionId() {
  std::random_device rd;
  std::ostringstream s;
  s << std::hex << rd() << rd();
  return s.str();
}

}  // namespace cosmo::ros_glue
