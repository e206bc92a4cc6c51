// recorder: gathers every robot's keyframes (odometry, reference pose) and loop closures and writes the
// COSMO-Bench JRL (DatasetRecorder, include/cosmo/dataset/dataset_recorder.hpp) to <output_dir>/<name>.jrl,
// atomically, on shutdown (SIGINT/SIGTERM included: the handler only sets a flag, the main thread writes),
// on request (service ~write, std_srvs/Trigger, or any message on ~write_request) and every ~autosave_period.
//
// Subscribes, per robot r of ~robots: /<r>/keyframes_meas (cosmo/RecorderKeyframe) and /<r>/loop_closures
// (cosmo/RecorderLoopClosure). Publishes /recorder/progress (cosmo/RecorderProgress, latched): what it received
// per robot, whenever that changes; the player's lockstep mode waits on it before it ends the run.
// Parameters: ~robots ("a,b,c" or a list; absent: the player's sequence, /player/robots), ~name (dataset name),
// ~output_dir, the noise models: ~noise_models (YAML path), else those of ~sequence (a sequence config: its environment
// / noise_models), else those of the built-in sequence of ~simulate_config (sequence_noise_models.hpp; none of them, or
// a missing file: the node stops with a message that says how to make them), ~config_dir (config/noise_models/ lives
// there), ~outlier_rule (fidelity | squared), ~autosave_period (s, 0 = off), ~progress_period (s, 0 = off). The
// sequence's lines of <name>.recorder.yaml (its name, source, reference_offset, trials: trials::sequenceMetadata, as
// cosmo_generate writes them) come from the sequence the player resolved
// (/player/resolved_sequence and /player/resolved_data_root), else from ~sequence below ~data_root (empty: the
// config's own precedence); without either (live robots) there are none.
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/trials/sequence_metadata.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

class RecorderNode {
 public:
  RecorderNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    const std::vector<char> robots = cosmo::ros_glue::readTeamRobots(pnh);
    std::string name = "cosmo", output_dir = ".", noise_path, rule_name = "fidelity";
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
    const auto rule = cosmo::parseOutlierRule(rule_name);
    if (!rule) throw std::runtime_error("~outlier_rule: expected 'fidelity' or 'squared', got '" + rule_name + "'");
    const cosmo::NoiseModels noise =
        cosmo::pipeline::loadRunNoiseModels(noise_path, sequence_path, simulate_config, config_dir);
    std::filesystem::create_directories(output_dir);
    path_ = (std::filesystem::path(output_dir) / (name + ".jrl")).string();
    recorder_.emplace(name, robots, noise, *rule);
    for (const char r : robots) {
      const std::string ns = "/" + std::string(1, r);
      subs_.push_back(nh.subscribe<cosmo::RecorderKeyframe>(
          ns + "/keyframes_meas", 10000, [this, r](const cosmo::RecorderKeyframe::ConstPtr& m) { onKeyframe(r, *m); }));
      subs_.push_back(nh.subscribe<cosmo::RecorderLoopClosure>(
          ns + "/loop_closures", 10000,
          [this, r](const cosmo::RecorderLoopClosure::ConstPtr& m) { onLoopClosure(r, *m); }));
    }
    for (const char r : robots) received_[r];
    progress_pub_ = nh.advertise<cosmo::RecorderProgress>("/recorder/progress", 1, true);
    publishProgress();
    service_ = pnh.advertiseService("write", &RecorderNode::onWriteService, this);
    write_request_ = pnh.subscribe<std_msgs::Empty>("write_request", 10,
                                                    [this](const std_msgs::Empty::ConstPtr&) { write("request"); });
    ROS_INFO("recorder: %zu robots, noise models %s, outlier rule %s, writing %s", robots.size(),
             noise.describe().c_str(), cosmo::outlierRuleName(*rule), path_.c_str());
  }

  /// Main loop in the calling thread: until SIGINT/SIGTERM or ros::shutdown, then the final write.
  void run() {
    ros::WallTime last_progress = ros::WallTime::now(), last_save = last_progress;
    ros::WallRate rate(100.0);
    while (!g_stop && ros::ok()) {
      ros::spinOnce();
      if (progress_changed_) publishProgress();
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
    write("shutdown");
  }

 private:
  void onKeyframe(char topic_robot, const cosmo::RecorderKeyframe& m) {
    if (m.robot.size() != 1 || m.robot[0] != topic_robot)
      ROS_WARN_THROTTLE(5.0, "recorder: /%c/keyframes_meas: robot field '%s' differs from the topic's robot",
                        topic_robot, m.robot.c_str());
    const char robot = m.robot.size() == 1 ? m.robot[0] : topic_robot;
    ++received_[topic_robot].keyframes;  // counted as sent, whatever becomes of it
    progress_changed_ = true;
    try {
      std::optional<cosmo::Pose3> reference;
      if (m.has_reference) reference = cosmo::ros_glue::poseFromExactOrMsg(m.reference_exact, m.reference);
      const cosmo::Pose3 odometry =
          m.index == 0 ? cosmo::Pose3::Identity()
                       : cosmo::ros_glue::poseFromExactOrMsg(m.odometry_from_previous_exact, m.odometry_from_previous);
      recorder_->addKeyframe(robot, m.index, m.header.stamp.toNSec(), odometry, reference);
      changed_ = true;
    } catch (const std::exception& e) { ROS_WARN("recorder: /%c/keyframes_meas: %s (ignored)", topic_robot, e.what()); }
  }

  void onLoopClosure(char topic_robot, const cosmo::RecorderLoopClosure& m) {
    ++received_[topic_robot].loop_closures;
    progress_changed_ = true;
    try {
      if (m.owner.size() != 1 || m.robot1.size() != 1 || m.robot2.size() != 1)
        throw std::invalid_argument("owner, robot1 and robot2 must be single characters");
      cosmo::LoopClosureMeasurement lc;
      lc.owner = m.owner[0];
      lc.computed_at = m.header.stamp.toNSec();
      lc.key1 = cosmo::jrl::symbol(m.robot1[0], m.index1);
      lc.key2 = cosmo::jrl::symbol(m.robot2[0], m.index2);
      lc.measurement = cosmo::ros_glue::poseFromExactOrMsg(m.measurement_exact, m.measurement);
      recorder_->addLoopClosure(lc);
      changed_ = true;
    } catch (const std::exception& e) { ROS_WARN("recorder: /%c/loop_closures: %s (ignored)", topic_robot, e.what()); }
  }

  bool onWriteService(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    std::string message;
    res.success = write("service", true, &message);
    res.message = message;
    return true;
  }

  /// The sequence's metadata lines, once its config can be read (see the file's header).
  void setSequenceMetadata() {
    if (metadata_set_) return;
    cosmo::ros_glue::ResolvedSequence sequence{sequence_path_, data_root_, {}};
    if (const auto resolved = cosmo::ros_glue::resolvedSequence()) sequence = *resolved;
    if (sequence.path.empty()) return;
    try {
      recorder_->setMetadata(cosmo::trials::sequenceMetadata(sequence.load()));
      metadata_set_ = true;
    } catch (const std::exception& e) {
      ROS_WARN_ONCE("recorder: the sequence's metadata (reference offset) of %s is not written: %s",
                    sequence.path.c_str(), e.what());
    }
  }

  bool write(const char* why, bool print_stats = true, std::string* message = nullptr) {
    setSequenceMetadata();
    try {
      cosmo::jrl::Dataset ds;
      const cosmo::BuildReport report = recorder_->write(path_, &ds);
      changed_ = false;
      std::ostringstream out;
      out << "wrote " << path_ << " (" << why << "): " << recorder_->progressLine();
      if (!report.labelled) out << "; " << report.labels_note;
      if (report.keyframes_pending || report.loop_closures_pending)
        out << "; pending (not written yet): " << report.keyframes_pending << " keyframes, "
            << report.loop_closures_pending << " loop closures";
      ROS_INFO("recorder: %s", out.str().c_str());
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

  void publishProgress() {
    cosmo::RecorderProgress p;
    for (const auto& [r, n] : received_) {
      p.robots.push_back(r);
      p.keyframes.push_back(n.keyframes);
      p.loop_closures.push_back(n.loop_closures);
    }
    progress_pub_.publish(p);
    progress_changed_ = false;
  }

  struct Received {
    std::uint32_t keyframes = 0, loop_closures = 0;
  };
  std::map<char, Received> received_;  ///< messages received per robot topic (/recorder/progress)
  bool progress_changed_ = false;
  ros::Publisher progress_pub_;
  std::optional<cosmo::DatasetRecorder> recorder_;
  std::string path_, sequence_path_, data_root_;
  bool metadata_set_ = false;
  double autosave_period_ = 30.0, progress_period_ = 5.0;
  bool changed_ = false;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber write_request_;
  ros::ServiceServer service_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::ros_glue::initNode(argc, argv, "recorder", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  ros::NodeHandle nh, pnh("~");
  try {
    RecorderNode node(nh, pnh);
    node.run();
  } catch (const std::exception& e) {
    ROS_FATAL("recorder: %s", e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
