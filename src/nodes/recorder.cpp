// recorder: the team's measurements into the JRL through a dataset::RecorderSession (journal before
// acknowledgement, resume, complete or not); this node moves messages in and progress out, and writes on shutdown,
// on request and every ~autosave_period. Topics and parameters: docs/nodes.md.
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
#include "cosmo/dataset/recorder_session.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
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
  RecorderNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : session_id_(randomId()) {
    std::string name = "cosmo", output_dir = ".", noise_path, rule_name = "fidelity", player_node = "/player";
    pnh.param("name", name, name);
    pnh.param("output_dir", output_dir, output_dir);
    std::string sequence_path, simulate_config, config_dir = cosmo::defaultConfigDir();
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
        cosmo::sequence::loadRunNoiseModels(noise_path, sequence_path, simulate_config, config_dir);
    path_ = (std::filesystem::path(output_dir) / (name + ".jrl")).string();
    const Run run = whichRun(nh, pnh);
    session_.emplace(output_dir, cosmo::dataset::JournalHeader{run.id, name, run.robots, run.with_player}, noise,
                     *rule);
    const auto& opening = session_->opening();
    if (!opening.note.empty()) ROS_WARN("recorder: journal %s: %s", session_->journalPath().c_str(), opening.note.c_str());
    if (opening.resumed)
      ROS_INFO("recorder: resumed from journal %s (session %zu): %zu measurements; %s",
               session_->journalPath().c_str(), session_->sessions(), opening.records,
               session_->recorder().progressLine().c_str());
    else
      ROS_INFO("recorder: journal %s", session_->journalPath().c_str());
    progress_changed_ = true;
    subscribe(nh, pnh);
    if (run.with_player && !player_node.empty()) watchPlayer(player_node);
    ROS_INFO("recorder: run %s, session %s, %zu robots, noise models %s, outlier rule %s, writing %s",
             run.id.c_str(), session_id_.c_str(), run.robots.size(), noise.describe().c_str(),
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
      if (player_died_ && !session_->playerFinished() && session_->incomplete().empty())
        stopRun("the player ended before the end of the sequence: " + player_death_);
      const ros::WallTime now = ros::WallTime::now();
      if (progress_period_ > 0 && (now - last_progress).toSec() >= progress_period_) {
        ROS_INFO("recorder: %s", session_->recorder().progressLine().c_str());
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
    session_->end();
    const bool written = write("shutdown");
    if (session_->finish(written))
      ROS_INFO("recorder: the dataset is complete; journal %s removed", session_->journalPath().c_str());
    return session_->incomplete().empty() && written ? 0 : 1;
  }

 private:
  void subscribe(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    for (const char r : session_->run().robots) {
      const std::string ns = "/" + std::string(1, r);
      subs_.push_back(nh.subscribe<cosmo::RecorderKeyframe>(
          ns + "/keyframes_meas", 10000,
          [this, r](const cosmo::RecorderKeyframe::ConstPtr& m) { receive(r, *m, "/keyframes_meas"); }));
      subs_.push_back(nh.subscribe<cosmo::RecorderLoopClosure>(
          ns + "/loop_closures", 10000,
          [this, r](const cosmo::RecorderLoopClosure::ConstPtr& m) { receive(r, *m, "/loop_closures"); }));
      subs_.push_back(nh.subscribe<cosmo::FrontendAck>(ns + "/ack", 10, [this, r](const cosmo::FrontendAck::ConstPtr& m) {
        session_->frontendSkipped(r, m->skipped);  // also after its last keyframe
      }));
    }
    subs_.push_back(nh.subscribe<std_msgs::Empty>("/player/done", 1,
                                                  [this](const std_msgs::Empty::ConstPtr&) { session_->playerDone(); }));
    subs_.push_back(nh.subscribe<std_msgs::String>("/player/abort", 1, [this](const std_msgs::String::ConstPtr& m) {
      if (session_->incomplete().empty()) stopRun("the player stopped the run: " + m->data);
    }));
    progress_pub_ = nh.advertise<cosmo::RecorderProgress>("/recorder/progress", 1, true);
    service_ = pnh.advertiseService("write", &RecorderNode::onWriteService, this);
    write_request_ = pnh.subscribe<std_msgs::Empty>("write_request", 10,
                                                    [this](const std_msgs::Empty::ConstPtr&) { write("request"); });
  }

  void watchPlayer(const std::string& node) {
    cosmo::live::PeerWatch watch(cosmo::live::RunMode::Lockstep);
    watch.expect(node, cosmo::live::PeerRole::Player, "the player");
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
      const MeasurementRecord r = cosmo::ros_glue::measurementFromMsg(m, robot);
      std::string refused;
      if (!session_->take(r, &refused)) return;
      progress_changed_ = changed_ = true;
      if (!refused.empty())
        ROS_WARN("recorder: robot %c measurement %llu: %s (kept out of the dataset)", r.robot,
                 static_cast<unsigned long long>(r.seq), refused.c_str());
    } catch (const std::exception& e) {
      ROS_WARN_THROTTLE(5.0, "recorder: /%c%s: %s (ignored)", robot, topic, e.what());
    }
  }

  /// The journal on disk first, then the acknowledgement.
  void acknowledge() {
    session_->durable();
    if (!progress_changed_) return;
    cosmo::RecorderProgress p = cosmo::ros_glue::recorderProgressMsg(session_->intake(), session_->recorder());
    for (std::size_t i = 0; i < p.robots.size(); ++i)
      p.scans_skipped[i] = std::max(p.scans_skipped[i], session_->scansSkipped(p.robots[i]));
    p.run_id = session_->run().run_id;
    p.session = session_id_;
    p.incomplete = session_->incomplete();
    p.written = written_;
    progress_pub_.publish(p);
    progress_changed_ = false;
  }

  /// The run stops: the dataset so far, marked incomplete.
  void stopRun(const std::string& why) {
    session_->stop(why);
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

  /// The sequence's metadata lines, once its config can be read (see the file's header).
  const cosmo::dataset::MetadataLines& sequenceLines() {
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
    static const cosmo::dataset::MetadataLines none;
    return sequence_lines_ ? *sequence_lines_ : none;
  }

  bool write(const char* why, bool print_stats = true, std::string* message = nullptr) {
    try {
      cosmo::jrl::Dataset ds;
      const cosmo::BuildReport report = session_->write(path_, sequenceLines(), &ds);
      changed_ = false;
      std::ostringstream out;
      out << "wrote " << path_ << " (" << why << (session_->incomplete().empty() ? "" : ", marked incomplete")
          << "): " << report.entries << " entries; " << session_->recorder().progressLine();
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

  std::string session_id_;
  std::optional<cosmo::dataset::RecorderSession> session_;  ///< journal -> intake -> dataset (recorder_session.hpp)
  bool progress_changed_ = false, changed_ = false;
  std::string written_;
  std::atomic<bool> player_died_{false};
  std::string player_death_;
  std::optional<cosmo::dataset::MetadataLines> sequence_lines_;
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
