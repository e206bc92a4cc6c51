#pragma once
// The messages of some connections of a ROS 1 bag (trials/ros1_bag.hpp) one after the other, in rosbag's order,
// with the chunks they lie in decompressed ahead on worker threads: a bz2 bag's first read decompresses
// `threads` chunks at once while the caller decodes. The messages and their order do not depend on `threads`;
// a damaged chunk throws when the stream reaches it.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <vector>

#include "cosmo/trials/ros1_bag.hpp"

namespace cosmo::trials {

/// Worker threads for a bag's chunks: $COSMO_BAG_THREADS when set, else 0 (in the caller) for uncompressed
/// chunks and the machine's cores (at most 4) for compressed ones.
unsigned defaultChunkThreads(const Ros1Bag& bag);

class Ros1MessageStream {
 public:
  Ros1MessageStream(std::shared_ptr<const Ros1Bag> bag, std::vector<Ros1MessageRef> messages, unsigned threads);
  ~Ros1MessageStream();
  Ros1MessageStream(const Ros1MessageStream&) = delete;
  Ros1MessageStream& operator=(const Ros1MessageStream&) = delete;

  std::size_t size() const { return messages_.size(); }
  const Ros1Bag& bag() const { return *bag_; }
  /// The latest receive time of the messages (0 when there are none).
  StampNs lastReceived() const { return messages_.empty() ? 0 : messages_.back().received; }
  /// The next message and its serialized bytes (valid until the next call); false at the end.
  bool next(Ros1MessageRef& message, Ros1Bag::Bytes& bytes);
  /// Restarts at the first message received at or after `received`.
  void seek(StampNs received);

 private:
  void fill();  ///< starts the decompression of the chunks ahead

  std::shared_ptr<const Ros1Bag> bag_;
  std::vector<Ros1MessageRef> messages_;
  unsigned threads_;
  std::vector<std::uint32_t> visits_;   ///< the chunks in the order the messages need them (runs merged)
  std::vector<std::size_t> visit_of_;   ///< per message: its index in visits_
  std::size_t next_ = 0;                ///< next message
  std::size_t current_visit_ = SIZE_MAX;
  std::size_t next_visit_ = 0;          ///< first visit not started
  std::deque<std::future<std::vector<std::uint8_t>>> ahead_;  ///< visits [current+1, next_visit_)
  std::vector<std::uint8_t> chunk_;     ///< the current visit's data
  std::vector<std::vector<std::uint8_t>> spare_;
};

}  // namespace cosmo::trials
