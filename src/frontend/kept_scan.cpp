#include "cosmo/frontend/kept_scan.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace cosmo::frontend {

namespace {

// Spilled layout: four counts (points, intensity, time, ring; uint64), then the arrays in that order.
constexpr std::size_t kHeader = 4 * sizeof(std::uint64_t);

template <typename T>
void put(std::vector<char>& out, std::size_t& at, const std::vector<T>& v) {
  if (!v.empty()) std::memcpy(out.data() + at, v.data(), sizeof(T) * v.size());
  at += sizeof(T) * v.size();
}

template <typename T>
void take(const std::vector<char>& in, std::size_t& at, std::size_t n, std::vector<T>& v) {
  v.resize(n);
  if (n > 0) std::memcpy(static_cast<void*>(v.data()), in.data() + at, sizeof(T) * n);
  at += sizeof(T) * n;
}

}  // namespace

std::size_t scanBytes(const Scan& scan) {
  return sizeof(Eigen::Vector3f) * scan.points.size() + sizeof(float) * (scan.intensity.size() + scan.time.size()) +
         sizeof(std::uint16_t) * scan.ring.size();
}

KeptScan::KeptScan(std::shared_ptr<const Scan> scan, std::shared_ptr<SpillFile> spill) : spill_(std::move(spill)) {
  if (!scan) throw std::invalid_argument("kept scan: null scan");
  stamp_ = scan->stamp;
  points_ = scan->size();
  bytes_ = scanBytes(*scan);
  if (!spill_) {
    held_ = std::move(scan);
    return;
  }
  const std::uint64_t counts[4] = {scan->points.size(), scan->intensity.size(), scan->time.size(), scan->ring.size()};
  std::vector<char> block(kHeader + bytes_);
  std::memcpy(block.data(), counts, kHeader);
  std::size_t at = kHeader;
  put(block, at, scan->points);
  put(block, at, scan->intensity);
  put(block, at, scan->time);
  put(block, at, scan->ring);
  extent_ = spill_->append(block.data(), block.size());
  in_use_ = scan;
}

std::shared_ptr<const Scan> KeptScan::get() const {
  if (held_) return held_;
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto s = in_use_.lock()) return s;
  std::vector<char> block(extent_.size);
  spill_->read(extent_, block.data());
  std::uint64_t counts[4];
  std::memcpy(counts, block.data(), kHeader);
  auto scan = std::make_shared<Scan>();
  scan->stamp = stamp_;
  std::size_t at = kHeader;
  take(block, at, counts[0], scan->points);
  take(block, at, counts[1], scan->intensity);
  take(block, at, counts[2], scan->time);
  take(block, at, counts[3], scan->ring);
  if (at != block.size()) throw std::runtime_error("kept scan: spilled block of the wrong size");
  std::shared_ptr<const Scan> out = std::move(scan);
  in_use_ = out;
  return out;
}

std::size_t KeptScan::bytesInMemory() const {
  if (held_) return bytes_;
  std::lock_guard<std::mutex> lock(mutex_);
  return in_use_.expired() ? 0 : bytes_;
}

}  // namespace cosmo::frontend
