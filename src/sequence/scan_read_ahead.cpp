#include "cosmo/sequence/scan_read_ahead.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::sequence {

namespace {

std::string describe(const std::vector<StampNs>& stamps) {
  std::string s;
  for (std::size_t i = 0; i < stamps.size() && i < 6; ++i) s += (i ? ", " : "") + std::to_string(stamps[i]);
  if (stamps.size() > 6) s += ", ... (" + std::to_string(stamps.size()) + ")";
  return "[" + s + "]";
}

}  // namespace

ScanReadAhead::ScanReadAhead(std::size_t capacity) : capacity_(capacity < 2 ? 2 : capacity) {}

bool ScanReadAhead::add(Scan scan) {
  if (!increasing_.accept(scan.stamp)) {
    ++dropped_;
    return false;
  }
  held_.push_back(std::move(scan));
  return true;
}

std::vector<StampNs> ScanReadAhead::stamps() const {
  std::vector<StampNs> s;
  for (const Scan& scan : held_) s.push_back(scan.stamp);
  return s;
}

bool ScanReadAhead::passOver(StampNs stamp) {
  while (!held_.empty() && held_.front().stamp < stamp) {
    held_.pop_front();
    ++skipped_;
  }
  return !held_.empty();
}

Scan ScanReadAhead::take(StampNs stamp) {
  passOver(stamp);
  if (held_.empty() || held_.front().stamp != stamp)
    throw std::runtime_error("asked for the scan stamped " + std::to_string(stamp) + " ns, which " +
                             (held_.empty() && ended_ ? std::string("is past the trial's end")
                                                      : "is not among those read ahead " + describe(stamps())));
  Scan scan = std::move(held_.front());
  held_.pop_front();
  return scan;
}

void AnnouncedStamps::announce(const std::vector<StampNs>& window, bool end) {
  for (std::size_t i = 1; i < window.size(); ++i)
    if (window[i] <= window[i - 1])
      throw std::runtime_error("announced stamps do not increase: " + describe(window));
  // The window holds every scan read and not played, so every stamp announced and not taken yet.
  if (!pending_.empty() && (window.empty() || window.front() > pending_.front()))
    throw std::runtime_error("announced stamps " + describe(window) + " leave out the scan stamped " +
                             std::to_string(pending_.front()) + " ns, announced before and not played");
  heard_ = true;
  for (StampNs s : window)
    if (!last_ || s > *last_) {
      pending_.push_back(s);
      last_ = s;
    }
  if (end) end_ = true;
}

std::optional<StampNs> AnnouncedStamps::take() {
  if (pending_.empty()) return std::nullopt;
  const StampNs s = pending_.front();
  pending_.pop_front();
  ++taken_;
  return s;
}

}  // namespace cosmo::sequence
