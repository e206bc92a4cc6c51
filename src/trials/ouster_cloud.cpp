#include "cosmo/trials/ouster_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace cosmo::trials {

namespace {
double columnNs(const OusterSweep& s) { return 1e9 / (s.columns * s.rate_hz); }
}  // namespace

CloudLayout ousterLayout(const OusterSweep& sweep) {
  CloudLayout L;
  L.frame_id = sweep.frame_id;
  L.height = static_cast<std::uint32_t>(sweep.beams);
  L.width = static_cast<std::uint32_t>(sweep.columns);
  auto type = [](PointType t) { return static_cast<std::uint8_t>(t); };
  L.fields = {{"x", 0, type(PointType::Float32), 1},
              {"y", 4, type(PointType::Float32), 1},
              {"z", 8, type(PointType::Float32), 1},
              {"intensity", 16, type(PointType::Float32), 1},
              {"t", 20, type(PointType::UInt32), 1},
              {"reflectivity", 24, type(PointType::UInt16), 1},
              {"ring", 26, type(sweep.ring_uint16 ? PointType::UInt16 : PointType::UInt8), 1},
              {"ambient", 28, type(PointType::UInt16), 1},
              {"range", 32, type(PointType::UInt32), 1}};
  L.point_step = 48;
  L.row_step = L.point_step * L.width;
  L.is_dense = false;
  return L;
}

StampNs ousterHeaderStamp(StampNs sim_stamp, const OusterSweep& sweep) {
  const auto start = sim_stamp - static_cast<StampNs>(std::llround((sweep.columns - 1) * columnNs(sweep)));
  return sweep.stamp_at_end ? start + static_cast<StampNs>(std::llround(1e9 / sweep.rate_hz)) : start;
}

RawCloud organisedOusterCloud(const Scan& scan, const OusterSweep& sweep) {
  if (!scan.hasRing() || !scan.hasTime())
    throw std::invalid_argument("organisedOusterCloud: the scan needs ring and time per point");
  RawCloud cloud;
  cloud.layout = ousterLayout(sweep);
  cloud.layout.stamp = ousterHeaderStamp(scan.stamp, sweep);
  const std::size_t B = static_cast<std::size_t>(sweep.beams), C = static_cast<std::size_t>(sweep.columns);
  const std::size_t step = cloud.layout.point_step;
  cloud.data.assign(B * C * step, 0);
  // Every pixel carries its column time and ring, returns or not.
  for (std::size_t b = 0; b < B; ++b)
    for (std::size_t c = 0; c < C; ++c) {
      std::uint8_t* p = cloud.data.data() + (b * C + c) * step;
      const auto t = static_cast<std::uint32_t>(std::llround(c * columnNs(sweep)));
      std::memcpy(p + 20, &t, 4);
      if (sweep.ring_uint16) {
        const auto ring = static_cast<std::uint16_t>(b);
        std::memcpy(p + 26, &ring, 2);
      } else {
        p[26] = static_cast<std::uint8_t>(b);
      }
    }
  const double per_column = static_cast<double>(C) * sweep.rate_hz;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const long c = static_cast<long>(C) - 1 + std::lround(scan.time[i] * per_column);
    const std::size_t b = scan.ring[i];
    if (c < 0 || c >= static_cast<long>(C) || b >= B)
      throw std::invalid_argument("organisedOusterCloud: point " + std::to_string(i) + " (ring " + std::to_string(b) +
                                  ", column " + std::to_string(c) + ") lies outside the " + std::to_string(B) + " x " +
                                  std::to_string(C) + " sweep");
    std::uint8_t* p = cloud.data.data() + (b * C + static_cast<std::size_t>(c)) * step;
    const Eigen::Vector3f& q = scan.points[i];
    std::memcpy(p, q.data(), 12);
    const float intensity = scan.hasIntensity() ? scan.intensity[i] : 0.0f;
    std::memcpy(p + 16, &intensity, 4);
    const auto reflectivity = static_cast<std::uint16_t>(std::clamp(std::lround(intensity), 0L, 65535L));
    std::memcpy(p + 24, &reflectivity, 2);
    const auto range = static_cast<std::uint32_t>(std::max(1L, std::lround(q.norm() * 1000.0)));
    std::memcpy(p + 32, &range, 4);
  }
  return cloud;
}

}  // namespace cosmo::trials
