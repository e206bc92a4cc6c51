#pragma once
// Random draws of the radio model, written out so that a seed gives the same numbers with any standard
// library (std::*_distribution algorithms are implementation-defined).
#include <cstdint>
#include <random>

namespace cosmo::comm::radio_random {

/// Uniform in [0, 1) from the top 53 bits.
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
/// true with probability p.
inline bool bernoulli(std::mt19937_64& rng, double p) { return uniform01(rng) < p; }
/// Uniform index in [0, n), n > 0.
inline std::size_t index(std::mt19937_64& rng, std::size_t n) {
  return static_cast<std::size_t>(uniform01(rng) * static_cast<double>(n)) % n;
}
/// Normal draw (Box-Muller).
double normal(std::mt19937_64& rng, double mean, double stddev);
/// A well-mixed 64-bit value of the inputs (splitmix64), for per-item seeds independent of call order.
std::uint64_t mixSeed(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0);

}  // namespace cosmo::comm::radio_random
