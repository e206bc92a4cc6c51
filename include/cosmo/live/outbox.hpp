#pragma once
// A front-end's outbox of the measurements it sends the recorder (measurement_record.hpp): each gets the robot's
// next sequence number and is kept until the recorder acknowledges it (RecorderProgress.acked), so that a recorder
// that was down, or missed a message, gets it again. What is due to be sent again:
// - everything kept, when the recorder's session changes (a respawned recorder; also the first session heard);
// - a message sent `resend_after` s ago (wall time, passed in) and still not acknowledged.
// Memory: what is not acknowledged.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cosmo::live {

template <typename T>
class Outbox {
 public:
  explicit Outbox(double resend_after = 1.0) : resend_after_(resend_after) {}

  /// Numbers from `first` (a restarted front-end continues above what the recorder holds); before the first add().
  void numberFrom(std::uint64_t first) { next_ = first; }
  /// Keeps `message`, sent at `now`, under the next number, which it returns.
  std::uint64_t add(T message, double now) {
    const std::uint64_t seq = next_++;
    kept_.emplace(seq, Kept{std::move(message), now});
    return seq;
  }
  /// The recorder of `session` holds every number <= `acked`.
  void acknowledged(const std::string& session, std::uint64_t acked) {
    kept_.erase(kept_.begin(), kept_.upper_bound(acked));
    if (session != session_)
      for (auto& [seq, k] : kept_) k.sent = -1e300;  // due at once
    session_ = session;
  }
  /// What to send again at `now` (numbers and messages, in order); they count as sent at `now`.
  std::vector<std::pair<std::uint64_t, const T*>> due(double now) {
    std::vector<std::pair<std::uint64_t, const T*>> out;
    for (auto& [seq, k] : kept_)
      if (now - k.sent >= resend_after_) {
        out.emplace_back(seq, &k.message);
        k.sent = now;
      }
    return out;
  }
  /// The last number given (0: none).
  std::uint64_t lastSeq() const { return next_ - 1; }
  std::size_t size() const { return kept_.size(); }
  const std::string& session() const { return session_; }

 private:
  struct Kept {
    T message;
    double sent = 0.0;
  };
  double resend_after_;
  std::uint64_t next_ = 1;
  std::map<std::uint64_t, Kept> kept_;
  std::string session_;
};

}  // namespace cosmo::live
