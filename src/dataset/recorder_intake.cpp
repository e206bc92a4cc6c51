#include "cosmo/dataset/recorder_intake.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "cosmo/jrl/dataset.hpp"

namespace cosmo::dataset {

RecorderIntake::RecorderIntake(const std::vector<char>& robots) : robots_(robots) {
  for (char r : robots_) state_[r];
}

const RecorderIntake::Robot& RecorderIntake::at(char robot) const {
  const auto it = state_.find(robot);
  if (it == state_.end())
    throw std::invalid_argument(std::string("recorder intake: robot '") + robot + "' is not in the robot list");
  return it->second;
}

RecorderIntake::Robot& RecorderIntake::at(char robot) {
  return const_cast<Robot&>(static_cast<const RecorderIntake*>(this)->at(robot));
}

bool RecorderIntake::holds(char robot, std::uint64_t seq) const {
  const Robot& r = at(robot);
  return seq > 0 && (seq <= r.acked || r.above.count(seq) > 0);
}

void RecorderIntake::advance(Robot& r) {
  while (!r.above.empty() && *r.above.begin() <= r.acked + 1) {
    r.acked = std::max(r.acked, *r.above.begin());
    r.above.erase(r.above.begin());
  }
}

void RecorderIntake::seeIndex(char robot, std::uint64_t index) {
  const auto it = state_.find(robot);
  if (it == state_.end()) return;
  it->second.next_index = std::max<std::uint32_t>(it->second.next_index, static_cast<std::uint32_t>(index + 1));
}

bool RecorderIntake::take(const MeasurementRecord& record) {
  if (record.seq == 0)
    throw std::invalid_argument(std::string("recorder intake: robot ") + record.robot + ": seq 0 (they start at 1)");
  Robot& r = at(record.robot);
  if (holds(record.robot, record.seq)) return false;
  r.above.insert(record.seq);
  r.highest = std::max(r.highest, record.seq);
  if (const KeyframeMeasurement* k = record.keyframe()) {
    ++r.keyframes;
    r.scans_skipped = std::max(r.scans_skipped, k->scans_skipped);
    seeIndex(record.robot, k->index);
    if (k->bridge_from) {
      ++r.restarts;
      r.acked = std::max(r.acked, record.seq - 1);  // what the dead process sent before is settled
    }
  } else if (const LoopClosureMeasurement* lc = record.loopClosure()) {
    ++r.loop_closures;
    seeIndex(jrl::robotOf(lc->key1), jrl::indexOf(lc->key1));
    seeIndex(jrl::robotOf(lc->key2), jrl::indexOf(lc->key2));
  }
  advance(r);
  return true;
}

}  // namespace cosmo::dataset
