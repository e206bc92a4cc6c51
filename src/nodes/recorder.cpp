// recorder: the team's measurements into the JRL through a dataset::RecorderSession (journal before
// acknowledgement, resume, complete or not); this node moves messages in and progress out, and writes on shutdown,
// on request and every ~autosave_period. Topics and parameters: docs/nodes.md.
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <csignal>
#include <optional>

#include "cosmo/FrontendAck.h"
#include "cosmo/dataset/recorder_session.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/ros/recorder_msgs.hpp"
#include "cosmo/ros/recorder_options.hpp"
#include "cosmo/ros/run_stop.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

class RecorderNode {
 public:
  RecorderNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
      : o_(cosmo::ros_glue::readRecorderOptions(pnh)), path_(o_.jrlPath()) {
    const cosmo::dataset::NoiseModels noise = o_.noiseModels();
    const auto run = cosmo::ros_glue::waitForRun(nh, pnh, o_.run_id, [] { return g_stop != 0; });
    session_.emplace(o_.output_dir, cosmo::dataset::JournalHeader{run.id, o_.name, run.robots, run.with_player}, noise,
                     o_.rule);
    cosmo::ros_glue::logJournalOpening(*session_);
    subscribe(nh, pnh);
    if (run.with_player && !o_.player_node.empty()) watchPlayer(o_.player_node);
    ROS_INFO("recorder: run %s, session %s, %zu robots, noise models %s, outlier rule %s, writing %s", run.id.c_str(),
             session_id_.c_str(), run.robots.size(), noise.describe().c_str(), cosmo::dataset::outlierRuleName(o_.rule),
             path_.c_str());
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
      if (o_.progress_period > 0 && (now - last_progress).toSec() >= o_.progress_period) {
        ROS_INFO("recorder: %s", session_->recorder().progressLine().c_str());
        last_progress = now;
      }
      if (o_.autosave_period > 0 && (now - last_save).toSec() >= o_.autosave_period && changed_) {
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
      subs_.push_back(
          nh.subscribe<cosmo::FrontendAck>(ns + "/ack", 10, [this, r](const cosmo::FrontendAck::ConstPtr& m) {
            session_->frontendSkipped(r, m->skipped);  // also after its last keyframe
          }));
    }
    run_end_ = cosmo::ros_glue::listenForRunEnd(
        nh, [this] { session_->playerDone(); },
        [this](const std::string& why) {
          if (session_->incomplete().empty()) stopRun("the player stopped the run: " + why);
        });
    progress_pub_ = nh.advertise<cosmo::RecorderProgress>("/recorder/progress", 1, true);
    service_ = pnh.advertiseService("write", &RecorderNode::onWriteService, this);
    write_request_ = pnh.subscribe<std_msgs::Empty>("write_request", 10,
                                                    [this](const std_msgs::Empty::ConstPtr&) { write("request"); });
  }

  void watchPlayer(const std::string& node) {
    player_.emplace("recorder", cosmo::ros_glue::playerWatch(node));
    player_->onStop([this](const std::string& why) {
      player_death_ = why;
      player_died_ = true;
    });
    player_->start();
  }

  template <typename Msg>
  void receive(char robot, const Msg& m, const char* topic) {
    try {
      const cosmo::dataset::MeasurementRecord r = cosmo::ros_glue::measurementFromMsg(m, robot);
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
    progress_pub_.publish(cosmo::ros_glue::recorderProgressMsg(*session_, session_id_, written_));
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

  bool write(const char* why, bool print_stats = true, std::string* message = nullptr) {
    try {
      if (!sequence_lines_) sequence_lines_ = cosmo::ros_glue::sequenceMetadataLines(o_);  // once it can be read
      cosmo::jrl::Dataset ds;
      const cosmo::dataset::BuildReport report =
          session_->write(path_, sequence_lines_.value_or(cosmo::dataset::MetadataLines{}), &ds);
      changed_ = false;
      written_ = session_->writtenLine(path_, why, report);
      progress_changed_ = true;
      ROS_INFO("recorder: %s", written_.c_str());
      if (print_stats)
        std::cout << cosmo::jrl::formatStats(cosmo::jrl::computeStats(ds)) << "\n"
                  << cosmo::report::writeFiguresBesideJrl(ds, path_) << std::endl;
      if (message) *message = written_;
      return true;
    } catch (const std::exception& e) {
      ROS_ERROR("recorder: writing %s failed: %s", path_.c_str(), e.what());
      if (message) *message = e.what();
      return false;
    }
  }

  const cosmo::ros_glue::RecorderOptions o_;
  std::string session_id_ = cosmo::ros_glue::randomSessionId();
  std::optional<cosmo::dataset::RecorderSession> session_;  ///< journal -> intake -> dataset (recorder_session.hpp)
  bool progress_changed_ = true, changed_ = false;          ///< the progress to publish changed; the dataset did
  std::string written_;
  std::atomic<bool> player_died_{false};
  std::string player_death_;
  std::optional<cosmo::dataset::MetadataLines> sequence_lines_;
  std::string path_;
  ros::Publisher progress_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber write_request_;
  cosmo::ros_glue::RunEndListener run_end_;
  ros::ServiceServer service_;
  std::optional<cosmo::ros_glue::PeerMonitor> player_;  ///< last: its thread ends first
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::ros_glue::initNode(argc, argv, "recorder", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  int code = 0;
  const int failed = cosmo::ros_glue::runNode("recorder", [&] {
    ros::NodeHandle nh, pnh("~");
    code = RecorderNode(nh, pnh).run();
  });
  ros::shutdown();
  return failed ? failed : code;
}
