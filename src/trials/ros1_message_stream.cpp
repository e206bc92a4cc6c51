#include "cosmo/trials/ros1_message_stream.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

namespace cosmo::trials {

unsigned defaultChunkThreads(const Ros1Bag& bag) {
  if (const char* env = std::getenv("COSMO_BAG_THREADS"); env && *env) return static_cast<unsigned>(std::atoi(env));
  bool compressed = false;
  for (const auto& c : bag.chunks()) compressed |= c.compression != Ros1Compression::None;
  return compressed ? std::clamp(std::thread::hardware_concurrency(), 1u, 4u) : 0u;
}

Ros1MessageStream::Ros1MessageStream(std::shared_ptr<const Ros1Bag> bag, std::vector<Ros1MessageRef> messages,
                                     unsigned threads)
    : bag_(std::move(bag)), messages_(std::move(messages)), threads_(threads) {
  visit_of_.reserve(messages_.size());
  for (const auto& m : messages_) {
    if (visits_.empty() || visits_.back() != m.chunk) visits_.push_back(m.chunk);
    visit_of_.push_back(visits_.size() - 1);
  }
}

Ros1MessageStream::~Ros1MessageStream() {
  for (auto& f : ahead_)
    if (f.valid()) f.wait();
}

void Ros1MessageStream::fill() {
  const std::size_t window = threads_;  // chunks decompressed ahead, one per worker
  while (next_visit_ < visits_.size() && ahead_.size() < window) {
    std::vector<std::uint8_t> buffer;
    if (!spare_.empty()) {
      buffer = std::move(spare_.back());
      spare_.pop_back();
    }
    const std::uint32_t chunk = visits_[next_visit_++];
    ahead_.push_back(std::async(std::launch::async, [bag = bag_, chunk, buffer = std::move(buffer)]() mutable {
      bag->readChunk(chunk, buffer);
      return std::move(buffer);
    }));
  }
}

bool Ros1MessageStream::next(Ros1MessageRef& message, Ros1Bag::Bytes& bytes) {
  if (next_ >= messages_.size()) return false;
  const Ros1MessageRef& m = messages_[next_];
  const std::size_t visit = visit_of_[next_];
  if (visit != current_visit_) {
    if (threads_ == 0) {
      bag_->readChunk(m.chunk, chunk_);
      next_visit_ = visit + 1;
    } else {
      if (ahead_.empty()) {  // after a seek
        next_visit_ = visit;
        fill();
      }
      std::vector<std::uint8_t> data = ahead_.front().get();  // rethrows a damaged chunk's error, in order
      ahead_.pop_front();
      spare_.push_back(std::move(chunk_));
      chunk_ = std::move(data);
      fill();
    }
    current_visit_ = visit;
  }
  bytes = bag_->messageData(m, chunk_);
  message = m;
  ++next_;
  return true;
}

void Ros1MessageStream::seek(StampNs received) {
  for (auto& f : ahead_)
    if (f.valid()) f.wait();
  ahead_.clear();
  current_visit_ = SIZE_MAX;
  next_ = static_cast<std::size_t>(std::find_if(messages_.begin(), messages_.end(),
                                                [&](const Ros1MessageRef& m) { return m.received >= received; }) -
                                   messages_.begin());
  next_visit_ = next_ < visit_of_.size() ? visit_of_[next_] : visits_.size();
}

}  // namespace cosmo::trials
