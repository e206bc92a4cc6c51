// recorder: gathers every robot's keyframes (odometry, reference pose) and loop closures and writes the
// COSMO-Bench JRL (DatasetRecorder, include/cosmo/dataset/dataset_recorder.hpp) to <output_dir>/<name>.jrl,
// atomically, on shutdown (SIGINT/SIGTERM included: the handler only sets a flag, the main thread writes),
// on request (service ~write, std_srvs/Trigger, or any message on ~write_request) and every ~autosave_period.
//
// Nothing it acknowledged is lost: every measurement is numbered by its sender (seq); a new one goes to the journal
// <output_dir>/<name>.journal (dataset/measurement_journal.hpp), which is synced to disk before /recorder/progress
// acknowledges it; a duplicate (a sender sends again what was not acknowledged) is dropped (RecorderIntake). A
// recorder that starts and finds its run's journal replays it and goes on (the launch respawns it); a journal of
// another run is moved aside. The run is the player's (/player/sequence run_id), else ~run_id, else roslaunch's
// /run_id. The journal is removed once the complete dataset was written at the end.
//
// Subscribes, per robot r: /<r>/keyframes_meas (cosmo/RecorderKeyframe) and /<r>/loop_closures
// (cosmo/RecorderLoopClosure), once its journal is open; /player/sequence (the run and robots), /player/done and
// /player/abort (std_msgs/String: the run stops; the dataset so far is written marked incomplete).
// Publishes /recorder/progress (cosmo/RecorderProgress, latched): per robot what it holds and acknowledged.
// <name>.recorder.yaml says whether the dataset is complete (the player finished the sequence), else why not, the
// run id, the recorder's sessions (restarts), the front-ends' restarts and skipped scans (the largest count their
// keyframes or their acks, /<r>/ack, reported). The node exits 1 after
// writing an incomplete dataset.
// Parameters: ~robots ("a,b,c" or a list; absent: the player's sequence), ~name (dataset name), ~output_dir, the
// noise models: ~noise_models (YAML path), else those of ~sequence (a sequence config: its environment /
// noise_models), else those of the built-in sequence of ~simulate_config (sequence_noise_models.hpp; none of them, or
// a missing file: the node stops with a message that says how to make them), ~config_dir (config/noise_models/ lives
// there), ~outlier_rule (fidelity | squared), ~autosave_period (s, 0 = off), ~progress_period (s, 0 = off), ~run_id,
// ~player_node (the player watched for its death, default /player; empty: not watched). The sequence's lines of
// <name>.recorder.yaml (its name, source, reference_offset, trials: trials::sequenceMetadata, as cosmo_generate writes
// them) come from the sequence the player resolved (/player/resolved_sequence and /player/resolved_data_root), else
// from ~sequence below ~data_root (empty: the config's own precedence); without either (live robots) there are none.
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <sstream>

#include "cosmo/FrontendAck.h"
#include "cosmo/TeamSequence.h"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/measurement_journal.hpp"
#include "cosmo/dataset/recorder_intake.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/ros/recorder_msgs.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"
#include "cosmo/trials/sequence_metadata.hpp"

namespace {

using cosmo::dataset::MeasurementRecord;

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

std::string randomId() {
  std::random_device rd;
  std::ostringstream s;
  s << std::hex << rd() << rd();
  return s.str();
}

std::string yamlQuoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

/// The run and its robots: the player's sequence when the team comes from the player, else the parameters.
struct Run {
  std::string id;
  std::vector<char> robots;
  bool with_player = false;
};

Run whichRun(ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  Run run;
  pnh.param<std::string>("run_id", run.id, "");
  if (pnh.hasParam("robots")) {
    run.robots = cosmo::ros_glue::readRobotsParam(pnh);
    if (run.id.empty()) ros::param::get("/run_id", run.id);
    if (run.id.empty()) run.id = "live";
    return run;
  }
  run.with_player = true;
  std::optional<cosmo::TeamSequence> sequence;
  auto sub = nh.subscribe<cosmo::TeamSequence>(cosmo::ros_glue::kTeamSequenceTopic, 1,
                                               [&](const cosmo::TeamSequence::ConstPtr& m) { sequence = *m; });
  ROS_INFO("recorder: waiting for the player's sequence (%s): its run and robots", cosmo::ros_glue::kTeamSequenceTopic);
  while (ros::ok() && !g_stop && !sequence) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  if (!sequence) throw std::runtime_error("shut down before the player's sequence arrived");
  run.robots.assign(sequence->robots.begin(), sequence->robots.end());
  if (run.id.empty()) run.id = sequence->run_id;
  if (run.id.empty()) throw std::runtime_error("the player's sequence names no run_id");
  return run;
}

class RecorderNode {
 public:
  RecorderNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : session_(randomId()) {
    std::string name = "cosmo", output_dir = ".", noise_path, rule_name = "fidelity", player_node = "/player";
    pnh.param("name", name, name);
    pnh.param("output_dir", output_dir, output_dir);
    std::string sequence_path, simulate_config, config_dir = cosmo::pipeline::defaultConfigDir();
    pnh.param("noise_models", noise_path, noise_path);
    pnh.param("sequence", sequence_path, sequence_path);
    pnh.param("data_root", data_root_, data_root_);
    sequence_path_ = sequence_path;
    pnh.param("simulate_config", simulate_config, simulate_config);
    pnh.param("config_dir", config_dir, config_dir);
    pnh.param("outlier_rule", rule_name, rule_name);
    pnh.param("autosave_period", autosave_period_, 30.0);
    pnh.param("progress_period", progress_period_, 5.0);
    pnh.param("player_node", player_node, player_node);
    const auto rule = cosmo::parseOutlierRule(rule_name);
    if (!rule) throw std::runtime_error("~outlier_rule: expected 'fidelity' or 'squared', got '" + rule_name + "'");
    const cosmo::NoiseModels noise =
        cosmo::pipeline::loadRunNoiseModels(noise_path, sequence_path, simulate_config, config_dir);
    std::filesystem::create_directories(output_dir);
    path_ = (std::filesystem::path(output_dir) / (name + ".jrl")).string();
    run_ = whichRun(nh, pnh);
    const bool player_runs = run_.with_player;  // (a journal may say so too: a recorder started on its own)
    recorder_.emplace(name, run_.robots, noise, *rule);
    intake_.emplace(run_.robots);
    openJournal((std::filesystem::path(output_dir) / (name + ".journal")).string(), name);
    subscribe(nh, pnh);
    if (player_runs && !player_node.empty()) watchPlayer(player_node);
    ROS_INFO("recorder: run %s, session %s, %zu robots, noise models %s, outlier rule %s, writing %s",
             run_.id.c_str(), session_.c_str(), run_.robots.size(), noise.describe().c_str(),
             cosmo::outlierRuleName(*rule), path_.c_str());
  }

  /// Main loop in the calling thread: until SIGINT/SIGTERM or ros::shutdown, then the final write. Returns the exit
  /// code: 1 when the dataset is incomplete.
  int run() {
    ros::WallTime last_progress = ros::WallTime::now(), last_save = last_progress;
    ros::WallRate rate(100.0);
    while (!g_stop && ros::ok()) {
      ros::spinOnce();
      acknowledge();
      if (player_died_ && !done_ && incomplete_.empty())
        stopRun("the player ended before the end of the sequence: " + player_death_);
      const ros::WallTime now = ros::WallTime::now();
      if (progress_period_ > 0 && (now - last_progress).toSec() >= progress_period_) {
        ROS_INFO("recorder: %s", recorder_->progressLine().c_str());
        last_progress = now;
      }
      if (autosave_period_ > 0 && (now - last_save).toSec() >= autosave_period_ && changed_) {
        write("autosave", false);
        last_save = now;
      }
      rate.sleep();
    }
    if (ros::ok()) ros::spinOnce();  // what already arrived
    acknowledge();
    if (run_.with_player && !done_ && incomplete_.empty())
      incomplete_ = "the run ended before the player finished the sequence (no /player/done)";
    const bool written = write("shutdown");
    if (written && incomplete_.empty() && journal_) {
      journal_->remove();
      ROS_INFO("recorder: the dataset is complete; journal %s removed", journal_->path().c_str());
    }
    return incomplete_.empty() && written ? 0 : 1;
  }

 private:
  void openJournal(const std::string& path, const std::string& name) {
    cosmo::dataset::MeasurementJournal::Opened opened;
    journal_.emplace(path, cosmo::dataset::JournalHeader{run_.id, name, run_.robots, run_.with_player}, &opened);
    if (!opened.note.empty()) ROS_WARN("recorder: journal %s: %s", path.c_str(), opened.note.c_str());
    sessions_ = opened.contents.sessions + 1;
    if (opened.resumed) {  // a recorder started on its own to write the journal of a run with a player
      run_.with_player = run_.with_player || opened.contents.header.with_player;
      done_ = opened.contents.player_done;
    }
    for (const MeasurementRecord& r : opened.contents.records) take(r, /*journal=*/false);
    if (opened.resumed)
      ROS_INFO("recorder: resumed from journal %s (session %zu): %zu measurements; %s", path.c_str(), sessions_,
               opened.contents.records.size(), recorder_->progressLine().c_str());
    else
      ROS_INFO("recorder: journal %s", path.c_str());
    progress_changed_ = true;
  }

  void subscribe(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    for (const char r : run_.robots) {
      const std::string ns = "/" + std::string(1, r);
      subs_.push_back(nh.subscribe<cosmo::RecorderKeyframe>(
          ns + "/keyframes_meas", 10000,
          [this, r](const cosmo::RecorderKeyframe::ConstPtr& m) { receive(r, *m, "/keyframes_meas"); }));
      subs_.push_back(nh.subscribe<cosmo::RecorderLoopClosure>(
          ns + "/loop_closures", 10000,
          [this, r](const cosmo::RecorderLoopClosure::ConstPtr& m) { receive(r, *m, "/loop_closures"); }));
      subs_.push_back(nh.subscribe<cosmo::FrontendAck>(ns + "/ack", 10, [this, r](const cosmo::FrontendAck::ConstPtr& m) {
        skipped_[r] = std::max(skipped_[r], m->skipped);  // also after its last keyframe
      }));
    }
    subs_.push_back(nh.subscribe<std_msgs::Empty>("/player/done", 1, [this](const std_msgs::Empty::ConstPtr&) {
      if (done_) return;
      done_ = true;
      journal_->appendDone();  // a recorder that resumes knows the dataset is complete
    }));
    subs_.push_back(nh.subscribe<std_msgs::String>("/player/abort", 1, [this](const std_msgs::String::ConstPtr& m) {
      if (incomplete_.empty()) stopRun("the player stopped the run: " + m->data);
    }));
    progress_pub_ = nh.advertise<cosmo::RecorderProgress>("/recorder/progress", 1, true);
    service_ = pnh.advertiseService("write", &RecorderNode::onWriteService, this);
    write_request_ = pnh.subscribe<std_msgs::Empty>("write_request", 10,
                                                    [this](const std_msgs::Empty::ConstPtr&) { write("request"); });
  }

  void watchPlayer(const std::string& node) {
    cosmo::pipeline::PeerWatch watch(cosmo::pipeline::RunMode::Lockstep);
    watch.expect(node, cosmo::pipeline::PeerRole::Player, "the player");
    player_.emplace("recorder", std::move(watch));
    player_->onStop([this](const std::string& why) {
      player_death_ = why;
      player_died_ = true;
    });
    player_->start();
  }

  template <typename Msg>
  void receive(char robot, const Msg& m, const char* topic) {
    try {
      take(cosmo::ros_glue::measurementFromMsg(m, robot), /*journal=*/true);
    } catch (const std::exception& e) {
      ROS_WARN_THROTTLE(5.0, "recorder: /%c%s: %s (ignored)", robot, topic, e.what());
    }
  }

  /// A new measurement goes to the journal (when it came from a sender) and into the dataset; a duplicate is dropped.
  void take(const MeasurementRecord& r, bool journal) {
    if (!intake_->take(r)) return;
    if (journal) journal_->append(r);
    progress_changed_ = true;
    changed_ = true;
    try {
      if (const cosmo::dataset::KeyframeMeasurement* k = r.keyframe()) {
        std::optional<std::size_t> from;
        if (k->bridge_from) from = *k->bridge_from;
        recorder_->addKeyframe(k->robot, k->index, k->stamp, k->odometry, k->reference, from);
      } else {
        recorder_->addLoopClosure(*r.loopClosure());
      }
    } catch (const std::exception& e) {
      ROS_WARN("recorder: robot %c measurement %llu: %s (kept out of the dataset)", r.robot,
               static_cast<unsigned long long>(r.seq), e.what());
    }
  }

  /// The journal on disk first, then the acknowledgement.
  void acknowledge() {
    if (journal_->unsynced()) journal_->sync();
    if (!progress_changed_) return;
    cosmo::RecorderProgress p = cosmo::ros_glue::recorderProgressMsg(*intake_, *recorder_);
    for (std::size_t i = 0; i < p.robots.size(); ++i)
      p.scans_skipped[i] = std::max(p.scans_skipped[i], skipped_[p.robots[i]]);
    p.run_id = run_.id;
    p.session = session_;
    p.incomplete = incomplete_;
    p.written = written_;
    progress_pub_.publish(p);
    progress_changed_ = false;
  }

  /// The run stops: the dataset so far, marked incomplete.
  void stopRun(const std::string& why) {
    incomplete_ = why;
    ROS_ERROR("recorder: %s", why.c_str());
    write("run stopped");
    ROS_ERROR("recorder: %s", written_.c_str());
    progress_changed_ = true;
    acknowledge();
  }

  bool onWriteService(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    std::string message;
    res.success = write("service", true, &message);
    res.message = message;
    return true;
  }

  /// The metadata lines: the sequence's (once its config can be read, see the file's header) and the run's.
  void setMetadata() {
    if (!sequence_lines_) {
      cosmo::ros_glue::ResolvedSequence sequence{sequence_path_, data_root_, {}};
      if (const auto resolved = cosmo::ros_glue::resolvedSequence()) sequence = *resolved;
      if (!sequence.path.empty()) {
        try {
          sequence_lines_ = cosmo::trials::sequenceMetadata(sequence.load());
        } catch (const std::exception& e) {
          ROS_WARN_ONCE("recorder: the sequence's metadata (reference offset) of %s is not written: %s",
                        sequence.path.c_str(), e.what());
        }
      }
    }
    std::vector<std::pair<std::string, std::string>> lines = sequence_lines_.value_or(decltype(lines){});
    lines.emplace_back("complete", incomplete_.empty() ? "true" : "false");
    if (!incomplete_.empty()) lines.emplace_back("incomplete", yamlQuoted(incomplete_));
    lines.emplace_back("run_id", yamlQuoted(run_.id));
    lines.emplace_back("recorder_sessions",
                       std::to_string(sessions_) + "  # recorder processes that wrote the journal (1: no restart)");
    std::string restarts = "{", skipped = "{";
    for (char r : run_.robots) {
      restarts += (restarts.size() > 1 ? ", " : "") + std::string(1, r) + ": " + std::to_string(intake_->restarts(r));
      skipped += (skipped.size() > 1 ? ", " : "") + std::string(1, r) + ": " +
                 std::to_string(std::max(intake_->scansSkipped(r), skipped_[r]));
    }
    lines.emplace_back("frontend_restarts", restarts + "}  # restarts that took a keyframe (bridges: above)");
    lines.emplace_back("scans_skipped", skipped + "}  # skipped to keep up (real time: scan_queue)");
    recorder_->setMetadata(std::move(lines));
  }

  bool write(const char* why, bool print_stats = true, std::string* message = nullptr) {
    setMetadata();
    try {
      cosmo::jrl::Dataset ds;
      const cosmo::BuildReport report = recorder_->write(path_, &ds);
      changed_ = false;
      std::ostringstream out;
      out << "wrote " << path_ << " (" << why << (incomplete_.empty() ? "" : ", marked incomplete")
          << "): " << report.entries << " entries; " << recorder_->progressLine();
      if (!report.labelled) out << "; " << report.labels_note;
      if (report.keyframes_pending || report.loop_closures_pending)
        out << "; pending (not written yet): " << report.keyframes_pending << " keyframes, "
            << report.loop_closures_pending << " loop closures";
      written_ = out.str();
      progress_changed_ = true;
      ROS_INFO("recorder: %s", written_.c_str());
      if (print_stats)
        std::cout << cosmo::jrl::formatStats(cosmo::jrl::computeStats(ds)) << "\n"
                  << cosmo::report::writeFiguresBesideJrl(ds, path_) << std::endl;
      if (message) *message = out.str();
      return true;
    } catch (const std::exception& e) {
      ROS_ERROR("recorder: writing %s failed: %s", path_.c_str(), e.what());
      if (message) *message = e.what();
      return false;
    }
  }

  Run run_;
  std::string session_;
  std::size_t sessions_ = 1;
  std::optional<cosmo::DatasetRecorder> recorder_;
  std::optional<cosmo::dataset::RecorderIntake> intake_;
  std::optional<cosmo::dataset::MeasurementJournal> journal_;
  bool progress_changed_ = false, changed_ = false, done_ = false;
  std::string incomplete_, written_;
  std::map<char, std::uint32_t> skipped_;  ///< the front-ends' latest count of skipped scans (/<r>/ack)
  std::atomic<bool> player_died_{false};
  std::string player_death_;
  std::optional<std::vector<std::pair<std::string, std::string>>> sequence_lines_;
  std::string path_, sequence_path_, data_root_;
  double autosave_period_ = 30.0, progress_period_ = 5.0;
  ros::Publisher progress_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber write_request_;
  ros::ServiceServer service_;
  std::optional<cosmo::ros_glue::PeerMonitor> player_;  ///< last: its thread ends first
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::ros_glue::initNode(argc, argv, "recorder", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  ros::NodeHandle nh, pnh("~");
  int code = 0;
  try {
    RecorderNode node(nh, pnh);
    code = node.run();
  } catch (const std::exception& e) {
    ROS_FATAL("recorder: %s", e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return code;
}
