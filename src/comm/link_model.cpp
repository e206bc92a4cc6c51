#include "cosmo/comm/link_model.hpp"

#include <algorithm>

namespace cosmo::comm {

const TraceWindow* LinkModel::window(char a, char b, double t) const {
  return params_.trace ? params_.trace->find(a, b, t - 0.5 * params_.step - trace_origin_) : nullptr;
}

bool LinkModel::inRange(char a, char b, double t, double distance) const {
  return window(a, b, t) != nullptr || distance <= params_.d_init;
}

bool LinkModel::connected(char a, char b, double t, double distance, bool both_on) const {
  if (!both_on) return false;
  if (const TraceWindow* w = window(a, b, t)) return w->connected;
  return distance <= params_.d_init;
}

LinkSample LinkModel::sample(char a, char b, double t, double distance, double u) {
  LinkSample s;
  if (const TraceWindow* w = window(a, b, t)) {
    s.connected = w->connected;
    s.throughput_Bps = w->throughput_Bps;
    s.latency = w->latency;
    s.from_trace = true;
  } else {
    s.connected = u < params_.phi(distance);
    s.throughput_Bps = params_.bandwidthBps();
  }
  if (recording_)
    records_.push_back(LinkRecord{std::min(a, b), std::max(a, b), t, s.connected, s.throughput_Bps, s.latency});
  return s;
}

}  // namespace cosmo::comm
