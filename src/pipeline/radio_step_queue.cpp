#include "cosmo/pipeline/radio_step_queue.hpp"

namespace cosmo::pipeline {

bool QueuedRadioStep::on(char robot) const {
  for (std::size_t i = 0; i < order.robots.size(); ++i)
    if (order.robots[i] == robot) return i < order.on.size() && order.on[i];
  return false;
}

std::optional<QueuedRadioStep> RadioStepQueue::popReady() {
  if (!started_ || requests_.empty()) return std::nullopt;
  const RadioStepOrder& order = requests_.front().order;
  for (std::size_t i = 0; i < order.robots.size() && i < order.keyframes.size(); ++i)
    if (offers_[order.robots[i]] < order.keyframes[i]) return std::nullopt;  // an offer is on its way
  QueuedRadioStep request = std::move(requests_.front());
  requests_.pop_front();
  return request;
}

}  // namespace cosmo::pipeline
