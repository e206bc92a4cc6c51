#include "cosmo/pipeline/feed.hpp"

namespace cosmo::pipeline {

void ComputedScans::keep(const frontend::AheadScan& s) {
  scans.push_back(s);
  if (!s.keyframe_scan) return;
  keyframes.push_back(std::make_shared<const frontend::KeptScan>(s.keyframe_scan, spill));
  scans.back().keyframe_scan = std::make_shared<const Scan>();  // a marker: the scan is kept above
}

namespace {

double now(const FeedPlan& plan) { return plan.wall_clock ? plan.wall_clock() : 0.0; }

void progressed(const FeedPlan& plan, StampNs stamp) {
  if (plan.progress) plan.progress(stamp);
}

FeedFigures replay(TeamRun& run, const FeedPlan& plan) {
  const ComputedScans& computed = *plan.computed;
  std::size_t next_keyframe = 0;
  for (const frontend::AheadScan& s : computed.scans) {
    run.add(s.robot, frontend::OwnScan::prepared(s.stamp, s.odometry,
                                       s.keyframe_scan ? computed.keyframes.at(next_keyframe++)->get() : nullptr));
    progressed(plan, s.stamp);
  }
  FeedFigures f;
  f.dropped = computed.dropped;
  return f;
}

FeedFigures runAhead(TeamRun& run, const FeedPlan& plan, const frontend::FrontendParams& params) {
  FeedFigures f;
  frontend::OdometryRunAhead ahead(plan.sources(), *plan.timing, params, *plan.references);
  frontend::AheadScan s;
  for (;;) {
    const double waited = now(plan);
    const bool more = ahead.next(s);
    f.wait_odometry_s += now(plan) - waited;
    if (!more || s.stamp > plan.end) break;
    if (plan.computed) plan.computed->keep(s);
    const double worked = now(plan);
    run.add(s.robot, frontend::OwnScan::prepared(s.stamp, s.odometry, std::move(s.keyframe_scan)));
    f.team_work_s += now(plan) - worked;
    progressed(plan, s.stamp);
  }
  ahead.stop();  // the workers may have run past the end
  f.dropped = ahead.dropped();
  if (plan.computed) {
    plan.computed->dropped = f.dropped;
    plan.computed->ready = true;
  }
  return f;
}

FeedFigures serial(TeamRun& run, const FeedPlan& plan) {
  sequence::MergedScanStream stream(plan.sources(), *plan.timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) {
    if (scan.stamp > plan.end) break;
    run.add(robot, frontend::OwnScan::of(scan));
    progressed(plan, scan.stamp);
  }
  FeedFigures f;
  f.dropped = stream.dropped();
  return f;
}

}  // namespace

FeedFigures feed(TeamRun& run, const FeedPlan& plan) {
  const frontend::FrontendParams& params = run.params().frontend;
  FeedFigures f = plan.computed && plan.computed->ready                       ? replay(run, plan)
                  : params.odometry == frontend::OdometryKind::Loam && !plan.serial ? runAhead(run, plan, params)
                                                                           : serial(run, plan);
  const double finishing = now(plan);
  run.finish(plan.end);
  f.finish_s = now(plan) - finishing;
  return f;
}

}  // namespace cosmo::pipeline
