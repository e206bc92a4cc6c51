#pragma once
// An organized Ouster-like scan of a room of random walls (benchmark input: every beam and column present).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo::test_support {

/// An organized Ouster-like scan (beams x 1024 columns, elevations +-22.5 deg) of a room of random walls.
inline Scan organizedRoomScan(int beams, int columns, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> wall(5.0, 70.0), wall_h(2.0, 20.0);
  const int blocks = 64;
  std::vector<double> dist(blocks), height(blocks);
  for (int b = 0; b < blocks; ++b) {
    dist[b] = wall(rng);
    height[b] = wall_h(rng);
  }
  const double h = 1.8;
  Scan scan;
  scan.points.reserve(static_cast<std::size_t>(beams) * columns);
  for (int r = 0; r < beams; ++r) {
    const double el = (-22.5 + 45.0 * r / (beams - 1)) * M_PI / 180.0;
    for (int c = 0; c < columns; ++c) {
      const double az = 2.0 * M_PI * c / columns;
      const int b = c * blocks / columns;
      double range = 120.0;  // no return: beyond max_range
      if (el < 0.0)
        range = std::min(dist[b] / std::cos(el), h / std::tan(-el) / std::cos(el));
      else if (dist[b] * std::tan(el) < height[b] - h)
        range = dist[b] / std::cos(el);
      scan.points.emplace_back(static_cast<float>(range * std::cos(el) * std::cos(az)),
                               static_cast<float>(range * std::cos(el) * std::sin(az)),
                               static_cast<float>(range * std::sin(el)));
    }
  }
  return scan;
}

}  // namespace cosmo::test_support
