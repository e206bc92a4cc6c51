#pragma once
// Whether two robots can talk in a radio step, and at what throughput and latency: the distance model phi(d) of
// the paper, or a radio trace (comm/radio_trace.hpp) with phi(d) outside its windows and pairs.
//   range:  inside a trace window of the pair the robots try to start a communication at any distance (the trace
//           says what their link does); elsewhere only within d_init.
//   sample: inside a window, connected / throughput / latency are the window's; elsewhere C ~ Bernoulli(phi(d)),
//           throughput B, latency 0. Either way the sample consumes one uniform draw `u` of the radio's stream, so
//           the radio's other random choices (pair order, sender ties, scan choice) are the same draws whichever
//           model answered: a trace recorded from a run replays that run exactly.
//   connected: whether the pair is connected in the step (docs/design.md "Connectivity"): both robots on and, inside
//           a trace window of the pair, the window's `connected`; elsewhere within d_init (where the model starts a
//           communication). Deterministic (no draw): the Bernoulli sample above is the link's quality inside it.
#include <vector>

#include "cosmo/comm/radio_params.hpp"
#include "cosmo/comm/radio_trace.hpp"

namespace cosmo::comm {

struct LinkSample {
  bool connected = false;
  double throughput_Bps = 0.0;  ///< when alone on the channel
  double latency = 0.0;         ///< s
  bool from_trace = false;
};

class LinkModel {
 public:
  explicit LinkModel(const RadioParams& params) : params_(params) {}

  /// Radio time of trace time 0 (default 0: radio time is trace time).
  void setTraceOrigin(double radio_time) { trace_origin_ = radio_time; }
  /// Whether a and b, `distance` apart, try to start a communication in the step at radio time t.
  bool inRange(char a, char b, double t, double distance) const;
  /// Whether a and b, `distance` apart, are connected in the step at radio time t (see the file comment).
  bool connected(char a, char b, double t, double distance, bool both_on) const;
  /// The link of a and b in the step at radio time t; `u` uniform in [0, 1) from the radio's stream.
  LinkSample sample(char a, char b, double t, double distance, double u);

  /// Keep every sample (for RadioTrace::fromRecords).
  void setRecording(bool on) { recording_ = on; }
  const std::vector<LinkRecord>& records() const { return records_; }

 private:
  const TraceWindow* window(char a, char b, double t) const;

  RadioParams params_;
  double trace_origin_ = 0.0;
  bool recording_ = false;
  std::vector<LinkRecord> records_;
};

}  // namespace cosmo::comm
