#include "cosmo/sequence/scan_stream.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::sequence {

MergedScanStream::MergedScanStream(std::map<char, std::unique_ptr<ScanSource>> sources, SequenceTiming timing)
    : sources_(std::move(sources)), timing_(std::move(timing)) {
  for (auto& [robot, source] : sources_) {
    if (!source) throw std::invalid_argument(std::string("scan stream: robot '") + robot + "' has no source");
    timing_.of(robot);  // throws for a robot without a trial
    refill(robot);
  }
}

void MergedScanStream::refill(char robot) {
  pending_.erase(robot);
  Scan scan;
  while (sources_[robot]->next(scan)) {
    scan.stamp = timing_.of(robot).toSequence(scan.stamp);
    if (!increasing_[robot].accept(scan.stamp)) {
      ++dropped_[robot];
      continue;
    }
    pending_[robot] = std::move(scan);
    return;
  }
}

StampNs MergedScanStream::peekStamp() const {
  StampNs best = 0;
  bool any = false;
  for (const auto& [robot, scan] : pending_)
    if (!any || scan.stamp < best) {
      best = scan.stamp;
      any = true;
    }
  return best;
}

bool MergedScanStream::next(char& robot, Scan& scan) {
  if (pending_.empty()) return false;
  auto best = pending_.begin();  // map order = robot id order: ties go to the lower id
  for (auto it = pending_.begin(); it != pending_.end(); ++it)
    if (it->second.stamp < best->second.stamp) best = it;
  robot = best->first;
  scan = std::move(best->second);
  ++delivered_;
  refill(robot);
  return true;
}

}  // namespace cosmo::sequence
