#pragma once
// What the recorder holds of each robot's numbered measurements (measurement_record.hpp), and what it may
// acknowledge. A measurement whose seq is held already is a duplicate (a front-end sends again what was not
// acknowledged) and is dropped; arrival order does not matter (the DatasetRecorder's output depends only on the
// set of measurements it holds). acked(r) is the largest n such that every seq 1..n of r is held: a front-end may
// forget those.
// A restarted front-end (real time) continues above the highest seq held and starts with a bridged keyframe
// (KeyframeMeasurement::bridge_from): every seq below that keyframe's is settled then, held or not (what the dead
// process sent and the recorder never got is gone with it).
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "cosmo/dataset/measurement_record.hpp"

namespace cosmo::dataset {

class RecorderIntake {
 public:
  explicit RecorderIntake(const std::vector<char>& robots);

  /// Takes `record` when it is new (true), else drops it as a duplicate (false). Throws std::invalid_argument for
  /// a robot not in the list or seq 0.
  bool take(const MeasurementRecord& record);

  bool holds(char robot, std::uint64_t seq) const;
  /// Every seq 1..acked(robot) is held (or settled by a restart).
  std::uint64_t acked(char robot) const { return at(robot).acked; }
  /// The highest seq held (0: none).
  std::uint64_t highest(char robot) const { return at(robot).highest; }
  /// 1 + the highest keyframe index of `robot` in any held measurement, its own keyframes and every loop closure's
  /// keys (0: none): a restarted front-end numbers its keyframes from here, so no index names two poses.
  std::uint32_t nextIndex(char robot) const { return at(robot).next_index; }
  std::size_t keyframes(char robot) const { return at(robot).keyframes; }
  std::size_t loopClosures(char robot) const { return at(robot).loop_closures; }
  /// The largest count of skipped scans its keyframes reported.
  std::uint32_t scansSkipped(char robot) const { return at(robot).scans_skipped; }
  /// Bridged keyframes held: restarts of its front-end that took a keyframe.
  std::size_t restarts(char robot) const { return at(robot).restarts; }
  const std::vector<char>& robots() const { return robots_; }

 private:
  struct Robot {
    std::uint64_t acked = 0, highest = 0;
    std::set<std::uint64_t> above;  ///< held seqs above acked
    std::uint32_t next_index = 0, scans_skipped = 0;
    std::size_t keyframes = 0, loop_closures = 0, restarts = 0;
  };
  const Robot& at(char robot) const;
  Robot& at(char robot);
  void seeIndex(char robot, std::uint64_t index);
  static void advance(Robot& r);

  std::vector<char> robots_;
  std::map<char, Robot> state_;
};

}  // namespace cosmo::dataset
