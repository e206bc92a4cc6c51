#include "cosmo/live/frontend_continuation.hpp"

#include <algorithm>

namespace cosmo::live {

Continuation continueAfter(const RecorderHolding& recorder, std::optional<std::uint32_t> broker_next_index) {
  Continuation c;
  const std::uint32_t broker = broker_next_index.value_or(0);
  c.restart = recorder.highest_seq > 0 || recorder.next_index > 0 || broker > 0;
  if (!c.restart) return c;
  c.first_seq = recorder.highest_seq + 1;
  c.first_index = std::max(recorder.next_index, broker);
  c.bridge_from = recorder.chain_end;
  c.scans_skipped = recorder.scans_skipped;
  return c;
}

std::string Continuation::describe() const {
  if (!restart) return "starts afresh (keyframe 0, measurement 1)";
  std::string s = "continues its robot: keyframes from " + std::to_string(first_index) + ", measurements from " +
                  std::to_string(first_seq);
  s += bridge_from ? ", its first keyframe bridged from keyframe " + std::to_string(*bridge_from)
                   : ", no recorded keyframe 0 to bridge from (its keyframes stay out of the dataset)";
  return s;
}

}  // namespace cosmo::live
