#include "cosmo/pipeline/team_drain.hpp"

#include <tuple>

namespace cosmo::pipeline {

namespace {
auto counters(const FrontendProgress& p) { return std::tie(p.scans, p.received, p.keyframes, p.loop_closures, p.seq); }
}  // namespace

void TeamDrain::reported(char robot, const FrontendProgress& progress, std::uint32_t queued, double now) {
  const auto it = robots_.find(robot);
  Robot& r = robots_[robot];
  if (it == robots_.end() || counters(r.progress) != counters(progress) || queued > 0) r.changed_at = now;
  r.progress = progress;
  r.queued = queued;
  r.reported_at = now;
}

bool TeamDrain::drained(char robot, std::uint64_t recorder_acked, double now) const {
  const auto it = robots_.find(robot);
  if (it == robots_.end()) return false;
  const Robot& r = it->second;
  return now - r.reported_at < fresh_ && r.queued == 0 && now - r.changed_at >= quiet_ &&
         recorder_acked >= r.progress.seq;
}

std::uint64_t TeamDrain::lastSeq(char robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? 0 : it->second.progress.seq;
}

}  // namespace cosmo::pipeline
