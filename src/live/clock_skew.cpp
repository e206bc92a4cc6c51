#include "cosmo/live/clock_skew.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace cosmo::live {

ClockSkewWatch::ClockSkewWatch(double ahead_s, double behind_s, std::size_t window)
    : ahead_(ahead_s), behind_(behind_s), window_(std::max<std::size_t>(1, window)) {}

std::optional<std::string> ClockSkewWatch::observe(char robot, StampNs stamp, StampNs arrival) {
  Robot& r = robots_[robot];
  r.delays.push_back(static_cast<double>(static_cast<std::int64_t>(arrival - stamp)) * 1e-9);  // may be negative
  if (r.delays.size() > window_) r.delays.pop_front();
  if (r.delays.size() < window_) return std::nullopt;
  const double least = *std::min_element(r.delays.begin(), r.delays.end());
  const bool ahead = least < -ahead_, behind = least > behind_;
  if (!ahead && !behind) {
    r.warned = false;
    return std::nullopt;
  }
  if (r.warned) return std::nullopt;
  r.warned = true;
  char text[400];
  if (ahead)
    std::snprintf(text, sizeof text,
                  "robot %c's messages are stamped up to %.2f s ahead of this machine's clock: its clock runs ahead; "
                  "keep the machines' clocks in step (chrony)",
                  robot, -least);
  else
    std::snprintf(text, sizeof text,
                  "robot %c's messages arrive %.2f s or more after their stamps: its clock runs behind this "
                  "machine's (keep them in step: chrony), or it lags its sensor by that much",
                  robot, least);
  return std::string(text);
}

}  // namespace cosmo::live
