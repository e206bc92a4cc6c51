#include "cosmo/trials/point_layouts.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace cosmo::trials {

namespace {

const std::vector<std::pair<std::string, PointLayout>>& layoutNames() {
  static const std::vector<std::pair<std::string, PointLayout>> names{{"ouster", PointLayout::Ouster},
                                                                      {"velodyne", PointLayout::Velodyne},
                                                                      {"hesai", PointLayout::Hesai},
                                                                      {"livox", PointLayout::Livox},
                                                                      {"livox-custom", PointLayout::LivoxCustom},
                                                                      {"split-time", PointLayout::SplitTime}};
  return names;
}

struct Field {
  const char* name;
  std::uint32_t offset;
  PointType type;
};

/// Fields and point_step of a layout (see the header).
std::pair<std::vector<Field>, std::uint32_t> fieldsOf(PointLayout layout) {
  using T = PointType;
  switch (layout) {
    case PointLayout::Velodyne:
      return {{{"x", 0, T::Float32},
               {"y", 4, T::Float32},
               {"z", 8, T::Float32},
               {"intensity", 16, T::Float32},
               {"ring", 20, T::UInt16},
               {"time", 24, T::Float32}},
              32};
    case PointLayout::Hesai:
      return {{{"x", 0, T::Float32},
               {"y", 4, T::Float32},
               {"z", 8, T::Float32},
               {"intensity", 16, T::Float32},
               {"timestamp", 24, T::Float64},
               {"ring", 32, T::UInt16}},
              48};
    case PointLayout::Livox:
      return {{{"x", 0, T::Float32},
               {"y", 4, T::Float32},
               {"z", 8, T::Float32},
               {"intensity", 12, T::Float32},
               {"tag", 16, T::UInt8},
               {"line", 17, T::UInt8},
               {"timestamp", 18, T::Float64}},
              26};
    case PointLayout::SplitTime:
      return {{{"x", 0, T::Float32},
               {"y", 4, T::Float32},
               {"z", 8, T::Float32},
               {"intensity", 16, T::Float32},
               {"time_sec", 20, T::UInt32},
               {"time_nsec", 24, T::UInt32},
               {"laser_id", 28, T::UInt16}},
              32};
    case PointLayout::Ouster:
    case PointLayout::LivoxCustom: break;
  }
  throw std::invalid_argument("pointLayoutCloud: the " + pointLayoutName(layout) + " layout is written elsewhere");
}

template <typename T>
void put(std::uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace

std::string pointLayoutName(PointLayout layout) {
  for (const auto& [name, l] : layoutNames())
    if (l == layout) return name;
  return "?";
}

std::string pointLayoutNames() {
  std::string s;
  for (const auto& [name, l] : layoutNames()) s += (s.empty() ? "" : "|") + name;
  return s;
}

std::optional<PointLayout> parsePointLayout(const std::string& name) {
  for (const auto& [n, l] : layoutNames())
    if (n == name) return l;
  return std::nullopt;
}

RawCloud pointLayoutCloud(const Scan& scan, PointLayout layout, const std::string& frame_id) {
  if (!scan.hasTime()) throw std::invalid_argument("pointLayoutCloud: the scan has no per-point times");
  const auto [fields, step] = fieldsOf(layout);
  RawCloud cloud;
  CloudLayout& L = cloud.layout;
  L.stamp = scan.stamp;
  L.frame_id = frame_id;
  L.height = 1;
  L.width = static_cast<std::uint32_t>(scan.size());
  for (const Field& f : fields) L.fields.push_back({f.name, f.offset, static_cast<std::uint8_t>(f.type), 1});
  L.point_step = step;
  L.row_step = step * L.width;
  L.is_dense = true;
  cloud.data.assign(static_cast<std::size_t>(L.row_step), 0);
  const float t_min = scan.empty() ? 0.0f : *std::min_element(scan.time.begin(), scan.time.end());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    std::uint8_t* p = cloud.data.data() + i * step;
    std::memcpy(p, scan.points[i].data(), 12);
    const float intensity = scan.hasIntensity() ? scan.intensity[i] : 0.0f;
    const std::uint16_t ring = scan.hasRing() ? scan.ring[i] : 0;
    // The point's absolute time in ns: the stamp plus its (negative) time.
    const StampNs at = scan.stamp - static_cast<StampNs>(std::llround(-static_cast<double>(scan.time[i]) * 1e9));
    switch (layout) {
      case PointLayout::Velodyne: put(p + 16, intensity), put(p + 20, ring), put(p + 24, scan.time[i] - t_min); break;
      case PointLayout::Hesai:
        put(p + 16, intensity), put(p + 32, ring);
        put(p + 24, static_cast<double>(at / 1000000000ULL) + static_cast<double>(at % 1000000000ULL) * 1e-9);
        break;
      case PointLayout::Livox:
        put(p + 12, intensity), put(p + 17, static_cast<std::uint8_t>(std::min<int>(ring, 255)));
        put(p + 18, static_cast<double>(at));
        break;
      case PointLayout::SplitTime:
        put(p + 16, intensity), put(p + 28, ring);
        put(p + 20, static_cast<std::uint32_t>(at / 1000000000ULL));
        put(p + 24, static_cast<std::uint32_t>(at % 1000000000ULL));
        break;
      case PointLayout::Ouster:
      case PointLayout::LivoxCustom: break;
    }
  }
  return cloud;
}

}  // namespace cosmo::trials
