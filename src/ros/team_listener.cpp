#include "cosmo/ros/team_listener.hpp"

#include <std_msgs/String.h>

#include <nlohmann/json.hpp>

#include "cosmo/ros/lockstep_msgs.hpp"
#include "cosmo/ros/recorder_msgs.hpp"

namespace cosmo::ros_glue {

TeamListener::TeamListener(ros::NodeHandle& nh, const std::vector<char>& robots, bool acks) {
  stats_sub_ = nh.subscribe<std_msgs::String>("/comm/stats", 100, [this](const std_msgs::String::ConstPtr& m) {
    try {
      delivered_ = nlohmann::json::parse(m->data).value("delivered", std::uint64_t{0});
    } catch (const std::exception&) {}
  });
  recorder_sub_ = nh.subscribe<cosmo::RecorderProgress>("/recorder/progress", 10,
                                                        [this](const cosmo::RecorderProgress::ConstPtr& m) {
                                                          std::lock_guard<std::mutex> lock(mutex_);
                                                          recorder_ = *m;
                                                        });
  if (!acks) return;
  for (char r : robots)
    ack_subs_.push_back(nh.subscribe<cosmo::FrontendAck>(
        std::string("/") + r + "/ack", 10, [this, r](const cosmo::FrontendAck::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          drain_.reported(r, frontendProgressFromMsg(*m), m->queued, ros::WallTime::now().toSec());
        }));
}

std::string TeamListener::behind(const std::vector<char>& robots, const std::function<bool(char)>& alive) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string behind;
  const double now = ros::WallTime::now().toSec();
  for (char r : robots) {
    if (!alive(r)) continue;
    const std::uint64_t acked = recorder_ ? recorderAcked(*recorder_, r) : drain_.lastSeq(r);
    if (!drain_.drained(r, acked, now)) behind += r;
  }
  return behind;
}

std::optional<std::string> TeamListener::writtenIncomplete() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!recorder_ || recorder_->incomplete.empty()) return std::nullopt;
  return recorder_->written;
}

}  // namespace cosmo::ros_glue
