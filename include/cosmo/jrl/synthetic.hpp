#pragma once
// A synthetic COSMO-like dataset (for benchmarks and tests): robots on random-walk ground-truth trajectories,
// one tight prior per robot, odometry with noise, intra- and inter-robot loop closures (all potential outliers,
// a share of them corrupted and listed as outliers), constant dense covariances, dead-reckoned initialization,
// teammate keys initialised through the first closure that refers to them (jrl.md §10). Deterministic in rng.
#include <cstddef>
#include <random>
#include <vector>

#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

struct SyntheticParams {
  std::vector<char> robots{'a', 'b', 'c'};
  std::size_t poses_per_robot = 600;  ///< ~4 MB with the defaults below
  double step_m = 1.5;                ///< mean distance between keyframes
  double lc_probability = 0.35;       ///< per new pose, chance of an intra-robot loop closure
  double irlc_probability = 0.25;     ///< per new pose, chance of an inter-robot loop closure
  double outlier_ratio = 0.1;         ///< share of loop closures corrupted (and listed in outlier_factors)
  StampNs first_stamp = 1666284719545345152ull;
  StampNs period_ns = 1'300'000'000ull;  ///< between a robot's entries
};

Dataset makeSyntheticDataset(const SyntheticParams& params, std::mt19937_64& rng);

}  // namespace cosmo::jrl
