#pragma once
// One finished keyframe transfer of the radio simulation.
#include <cstddef>
#include <limits>
#include <string>

namespace cosmo::comm {

struct Transfer {
  char sender = 0;
  char receiver = 0;
  std::size_t keyframe = 0;  ///< the sender's keyframe index
  double start = 0.0;        ///< radio time (s) of the step that initialized the communication
  double end = 0.0;          ///< radio time (s) of the step in which its last byte was sent, or it timed out
  std::size_t bytes = 0;     ///< payload size the transfer had to deliver
  enum class Outcome { Delivered, TimedOut } outcome = Outcome::Delivered;
  double bytes_delivered = 0.0;  ///< bytes that got through (== bytes when delivered)
  /// Delivered: radio time of the step in which the receiver gets the scan: `end`, or with a trace's latency L the
  /// first step at or after end + L. NaN when timed out.
  double received = std::numeric_limits<double>::quiet_NaN();
  /// Which link model decided its steps: phi(d), a radio trace, or both (it crossed a window's edge).
  enum class Link { Distance, Trace, Mixed } link = Link::Distance;
};

/// "delivered" | "timed_out".
std::string toString(Transfer::Outcome outcome);
/// "distance" | "trace" | "mixed".
std::string toString(Transfer::Link link);

}  // namespace cosmo::comm
