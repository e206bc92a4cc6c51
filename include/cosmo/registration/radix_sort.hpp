#pragma once
// Stable LSD radix sort of (64-bit key, payload) pairs by key: 11-bit digits, digits that are the same for every
// element skipped (voxel keys differ only in a few low bits per axis). On input already ordered by payload, the
// result is the order std::sort gives the pairs (key first, then payload), in a few linear passes.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace cosmo {

template <class Payload>
void radixSortByKey(std::vector<std::pair<std::uint64_t, Payload>>& v) {
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  const std::size_t n = v.size();
  if (n < 2) return;
  std::vector<std::pair<std::uint64_t, Payload>> tmp(n);
  std::array<std::uint32_t, kBuckets> count{};
  for (int shift = 0; shift < 64; shift += kBits) {
    count.fill(0);
    for (const auto& x : v) ++count[(x.first >> shift) & (kBuckets - 1)];
    if (count[(v.front().first >> shift) & (kBuckets - 1)] == n) continue;  // one digit value: order unchanged
    std::uint32_t sum = 0;
    for (auto& c : count) {
      const std::uint32_t k = c;
      c = sum;
      sum += k;
    }
    for (const auto& x : v) tmp[count[(x.first >> shift) & (kBuckets - 1)]++] = x;
    v.swap(tmp);
  }
}

}  // namespace cosmo
