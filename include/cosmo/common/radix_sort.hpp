#pragma once
// Stable LSD radix sort of (64-bit key, payload) pairs by key, with 11-bit digits placed only where the keys'
// bits vary (bits that are the same in every key cannot change the order): packed voxel keys vary in a few low
// bits per axis, so three passes usually suffice. On input already ordered by payload, the result is the order
// std::sort gives the pairs (key first, then payload).
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace cosmo {

template <class Payload>
void radixSortByKey(std::vector<std::pair<std::uint64_t, Payload>>& v) {
  constexpr int kBits = 11;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kBits) - 1;
  const std::size_t n = v.size();
  if (n < 2) return;
  std::uint64_t all_or = 0, all_and = ~std::uint64_t{0};
  for (const auto& x : v) all_or |= x.first, all_and &= x.first;
  std::uint64_t varying = all_or ^ all_and;  // bits that differ between some keys
  std::vector<std::pair<std::uint64_t, Payload>> tmp(n);
  std::array<std::uint32_t, kMask + 1> count{};
  while (varying != 0) {
    const int shift = __builtin_ctzll(varying);  // the digit starts at the lowest varying bit left
    varying &= shift + kBits < 64 ? ~(kMask << shift) : (std::uint64_t{1} << shift) - 1;
    count.fill(0);
    for (const auto& x : v) ++count[(x.first >> shift) & kMask];
    std::uint32_t sum = 0;
    for (auto& c : count) {
      const std::uint32_t k = c;
      c = sum;
      sum += k;
    }
    for (const auto& x : v) tmp[count[(x.first >> shift) & kMask]++] = x;
    v.swap(tmp);
  }
}

}  // namespace cosmo
