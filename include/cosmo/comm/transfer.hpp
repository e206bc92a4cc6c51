#pragma once
// One finished keyframe transfer of the radio simulation.
#include <cstddef>
#include <string>

namespace cosmo {

struct Transfer {
  char sender = 0;
  char receiver = 0;
  std::size_t keyframe = 0;  ///< the sender's keyframe index
  double start = 0.0;        ///< time (s) of the step that initialized the communication
  double end = 0.0;          ///< time (s) of the step in which it completed or timed out
  std::size_t bytes = 0;     ///< payload size the transfer had to deliver
  enum class Outcome { Delivered, TimedOut } outcome = Outcome::Delivered;
  double bytes_delivered = 0.0;  ///< bytes that got through (== bytes when delivered)
};

/// "delivered" | "timed_out".
std::string toString(Transfer::Outcome outcome);

}  // namespace cosmo
