#include "cosmo/ros/run_stop.hpp"

#include <std_msgs/Empty.h>
#include <std_msgs/String.h>

#include <fstream>

namespace cosmo::ros_glue {

RunStop::RunStop(ros::NodeHandle& nh, std::string status_file)
    : status_file_(std::move(status_file)), abort_pub_(nh.advertise<std_msgs::String>("/player/abort", 1, true)) {}

void RunStop::status(const std::string& text) const {
  if (status_file_.empty()) return;
  std::ofstream out(status_file_);
  out << text << "\n";
  if (!out) ROS_ERROR("player: cannot write ~status_file %s", status_file_.c_str());
}

void RunStop::done() const { status("done"); }

void RunStop::stopped(const std::string& reason) const {
  std_msgs::String m;
  m.data = reason;
  abort_pub_.publish(m);
  ROS_ERROR("player: the run stops: %s", reason.c_str());
  status("stopped: " + reason);
}

void RunStop::failed() const { status("failed: see the player's log"); }

RunEndListener listenForRunEnd(ros::NodeHandle& nh, std::function<void()> on_done,
                               std::function<void(const std::string& reason)> on_abort) {
  RunEndListener l;
  l.done = nh.subscribe<std_msgs::Empty>("/player/done", 1, [on_done](const std_msgs::Empty::ConstPtr&) { on_done(); });
  l.abort = nh.subscribe<std_msgs::String>("/player/abort", 1,
                                           [on_abort](const std_msgs::String::ConstPtr& m) { on_abort(m->data); });
  return l;
}

}  // namespace cosmo::ros_glue
