#pragma once
// What the player hears from the team while it plays: the broker's delivered count (/comm/stats, for the progress
// line), the recorder's progress (/recorder/progress) and, in real time, each front-end's acks (/<r>/ack), which
// pipeline::TeamDrain turns into whether the robot is done with what it was given.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "cosmo/RecorderProgress.h"
#include "cosmo/pipeline/team_drain.hpp"

namespace cosmo::ros_glue {

class TeamListener {
 public:
  /// `acks`: listen to the front-ends' acks (real time; in lockstep the lockstep link does).
  TeamListener(ros::NodeHandle& nh, const std::vector<char>& robots, bool acks);

  std::uint64_t delivered() const { return delivered_; }
  /// The robots of `robots` whose front-end is `alive` and not drained: scans waiting, busy, counters still
  /// moving, or measurements the recorder does not hold yet.
  std::string behind(const std::vector<char>& robots, const std::function<bool(char)>& alive);
  /// The file the recorder wrote the dataset so far to, once it reported it incomplete.
  std::optional<std::string> writtenIncomplete();

 private:
  std::atomic<std::uint64_t> delivered_{0};
  std::mutex mutex_;                                 ///< guards recorder_ and drain_
  std::optional<cosmo::RecorderProgress> recorder_;  ///< the recorder's latest /recorder/progress
  pipeline::TeamDrain drain_;
  ros::Subscriber stats_sub_, recorder_sub_;
  std::vector<ros::Subscriber> ack_subs_;
};

}  // namespace cosmo::ros_glue
