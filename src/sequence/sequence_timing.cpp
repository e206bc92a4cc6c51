#include "cosmo/sequence/sequence_timing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cosmo/sequence/seed_streams.hpp"

namespace cosmo::sequence {

StampNs TrialTiming::toSequence(StampNs recorded) const {
  const std::int64_t s = static_cast<std::int64_t>(recorded) + offset_ns;
  return s < 0 ? 0 : static_cast<StampNs>(s);
}

StampNs TrialTiming::toRecorded(StampNs sequence) const {
  const std::int64_t s = static_cast<std::int64_t>(sequence) - offset_ns;
  return s < 0 ? 0 : static_cast<StampNs>(s);
}

SequenceTiming SequenceTiming::synchronize(const std::vector<TrialSpan>& spans, char anchor, double sigma_s,
                                           std::uint64_t seed) {
  if (spans.empty()) throw std::runtime_error("sequence timing: no trials");
  if (!(sigma_s >= 0.0)) throw std::runtime_error("sequence timing: time_offset_sigma must be >= 0");
  const auto anchor_it =
      std::find_if(spans.begin(), spans.end(), [&](const TrialSpan& s) { return s.robot == anchor; });
  if (anchor_it == spans.end())
    throw std::runtime_error(std::string("sequence timing: anchor robot '") + anchor + "' has no trial");
  const std::int64_t t_star = static_cast<std::int64_t>(anchor_it->first);

  std::mt19937_64 rng(deriveSeed(seed, "trial_offsets"));
  SequenceTiming timing;
  std::int64_t min_start = INT64_MAX;
  for (const auto& span : spans) {
    if (span.last < span.first)
      throw std::runtime_error(std::string("sequence timing: trial of robot '") + span.robot +
                               "' ends before it starts");
    TrialTiming t;
    t.robot = span.robot;
    t.first = span.first;
    t.last = span.last;
    std::int64_t start = t_star;
    if (span.robot != anchor) {
      const double delta_s = sigma_s * standardNormal(rng);
      start += static_cast<std::int64_t>(std::llround(delta_s * 1e3)) * 1000000LL;  // whole ms
    }
    t.offset_ns = start - static_cast<std::int64_t>(span.first);
    min_start = std::min(min_start, start);
    timing.trials_.push_back(t);
  }
  constexpr std::int64_t kFloor = 1000000000LL;  // keep every sequence stamp >= 1 s
  if (min_start < kFloor)
    for (auto& t : timing.trials_) t.offset_ns += kFloor - min_start;
  timing.start_ = timing.trials_.front().start();
  timing.end_ = timing.trials_.front().end();
  for (const auto& t : timing.trials_) {
    timing.start_ = std::min(timing.start_, t.start());
    timing.end_ = std::max(timing.end_, t.end());
  }
  return timing;
}

const TrialTiming& SequenceTiming::of(char robot) const {
  for (const auto& t : trials_)
    if (t.robot == robot) return t;
  throw std::runtime_error(std::string("sequence timing: unknown robot '") + robot + "'");
}

}  // namespace cosmo::sequence
