#pragma once
// How the player ends a run, in one place: ~status_file ("done", "stopped: <reason>", "failed: see the player's
// log", which scripts/run.sh and the suite read) and, when the run stops short, /player/abort (std_msgs/String,
// latched: the recorder writes the dataset so far marked incomplete, the trial players exit).
#include <functional>
#include <string>

#include <ros/ros.h>

namespace cosmo::ros_glue {

class RunStop {
 public:
  RunStop(ros::NodeHandle& nh, std::string status_file);

  /// The sequence was played to its end.
  void done() const;
  /// The run stops: /player/abort with the reason, the status, the log line.
  void stopped(const std::string& reason) const;
  /// The player itself failed (an exception): the status only (its log says why).
  void failed() const;

 private:
  void status(const std::string& text) const;

  std::string status_file_;
  ros::Publisher abort_pub_;
};

/// The end of a run as the other nodes hear it: /player/done (the sequence was played to its end) and
/// /player/abort (the run stops, with the reason). Keep the subscribers as long as the node listens.
struct RunEndListener {
  ros::Subscriber done, abort;
};
RunEndListener listenForRunEnd(ros::NodeHandle& nh, std::function<void()> on_done,
                               std::function<void(const std::string& reason)> on_abort);

}  // namespace cosmo::ros_glue
