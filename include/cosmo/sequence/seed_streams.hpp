#pragma once
// Independent, reproducible random streams derived from the one sequence seed: the trial offsets, the radio
// and anything else random get their own std::mt19937_64 seeded from (seed, purpose), so that adding a
// random choice in one place never changes the numbers drawn in another. mt19937_64 and the helpers below are
// fully specified (no std::normal_distribution, whose output differs between standard libraries).
#include <cmath>
#include <cstdint>
#include <random>
#include <string_view>

namespace cosmo::sequence {

/// SplitMix64 finaliser: a well-mixed 64-bit function of its input.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Seed of the stream named `purpose` (e.g. "trial_offsets", "radio") of sequence seed `seed`.
inline std::uint64_t deriveSeed(std::uint64_t seed, std::string_view purpose) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a of the purpose
  for (char c : purpose) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return splitmix64(seed ^ splitmix64(h));
}

/// Uniform double in (0, 1) from 53 random bits.
inline double uniformOpen01(std::mt19937_64& rng) {
  return (static_cast<double>(rng() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// Standard normal sample (Box-Muller, one output per call), identical on every platform.
inline double standardNormal(std::mt19937_64& rng) {
  const double u1 = uniformOpen01(rng), u2 = uniformOpen01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace cosmo::sequence
