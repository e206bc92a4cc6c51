#pragma once
// The radio's side of the lockstep (lockstep_schedule.hpp), without ROS: the step requests the player sent, run in
// order, each once the keyframe offers it names reached the radio (an offer and a request travel on different
// topics and may arrive in either order), and only once the radio is started (it learns its seed and grid from
// the player's sequence).
#include <cstdint>
#include <deque>
#include <map>
#include <optional>

#include "cosmo/pipeline/lockstep_schedule.hpp"

namespace cosmo::pipeline {

/// A step request as the radio runs it.
struct QueuedRadioStep {
  std::uint32_t seq = 0;  ///< answered with it
  RadioStepOrder order;
  /// Whether `robot` is on for the steps (robots the request does not name are off).
  bool on(char robot) const;
};

class RadioStepQueue {
 public:
  /// A keyframe offer of `robot` reached the radio (or was dropped: it is not waited for).
  void offerArrived(char robot) { ++offers_[robot]; }
  void push(QueuedRadioStep request) { requests_.push_back(std::move(request)); }
  /// The radio can run steps from now on.
  void start() { started_ = true; }
  bool started() const { return started_; }
  /// The oldest request, when the radio is started and every offer it names arrived; it leaves the queue.
  std::optional<QueuedRadioStep> popReady();
  std::size_t size() const { return requests_.size(); }

 private:
  bool started_ = false;
  std::map<char, std::uint32_t> offers_;
  std::deque<QueuedRadioStep> requests_;
};

}  // namespace cosmo::pipeline
