#pragma once
// Live robots stamp their messages with their own clocks, and the base compares those stamps with its own (the
// radio steps on the base's ROS time): the machines' clocks must be in step (chrony; README "A robot per
// machine"). This tells when they are not, from the messages alone: over a robot's recent messages, the smallest
// delay (arrival on this machine's clock minus the stamp) is its clock's offset from this one plus the network's
// latency. A negative one means its clock runs ahead of this machine's; a large one that it runs behind (or that the
// robot lags its sensor by that much). ROS-free: the node passes the arrival time.
#include <deque>
#include <map>
#include <optional>
#include <string>

#include "cosmo/common/time.hpp"

namespace cosmo::live {

class ClockSkewWatch {
 public:
  /// `ahead_s`: how far in this machine's future a stamp may be; `behind_s`: how late the least late message may be;
  /// `window`: messages per robot the smallest delay is taken over.
  ClockSkewWatch(double ahead_s = 0.2, double behind_s = 5.0, std::size_t window = 5);

  /// `robot`'s message stamped `stamp` arrived at `arrival`. A warning when the robot's clock looks out of step (once
  /// the window is full; again only after it was in step in between).
  std::optional<std::string> observe(char robot, StampNs stamp, StampNs arrival);

 private:
  struct Robot {
    std::deque<double> delays;
    bool warned = false;
  };
  double ahead_, behind_;
  std::size_t window_;
  std::map<char, Robot> robots_;
};

}  // namespace cosmo::live
