#include "cosmo/trials/point_cloud_decode.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace cosmo::trials {

std::size_t pointTypeSize(std::uint8_t datatype) {
  switch (static_cast<PointType>(datatype)) {
    case PointType::Int8:
    case PointType::UInt8: return 1;
    case PointType::Int16:
    case PointType::UInt16: return 2;
    case PointType::Int32:
    case PointType::UInt32:
    case PointType::Float32: return 4;
    case PointType::Float64: return 8;
  }
  return 0;
}

std::string pointTypeName(std::uint8_t datatype) {
  switch (static_cast<PointType>(datatype)) {
    case PointType::Int8: return "int8";
    case PointType::UInt8: return "uint8";
    case PointType::Int16: return "int16";
    case PointType::UInt16: return "uint16";
    case PointType::Int32: return "int32";
    case PointType::UInt32: return "uint32";
    case PointType::Float32: return "float32";
    case PointType::Float64: return "float64";
  }
  return "type " + std::to_string(datatype);
}

const PointField* CloudLayout::field(const std::string& name) const {
  for (const auto& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

std::string describeFields(const CloudLayout& layout) {
  std::string s;
  for (const auto& f : layout.fields)
    s += (s.empty() ? "" : " ") + f.name + ":" + pointTypeName(f.datatype) + "@" + std::to_string(f.offset);
  return s;
}

PointConventions pointConventions(const CloudLayout& L) {
  PointConventions c;
  using Time = PointConventions::Time;
  if ((c.time = L.field("t"))) {
    c.time_kind = Time::Nanoseconds;
    c.layout = "Ouster";
  } else if ((c.time = L.field("time")) || (c.time = L.field("timestamp"))) {
    c.time_kind = Time::Seconds;
    c.layout = c.time->name == "time" ? "Velodyne" : L.field("line") ? "Livox PointCloud2" : "Hesai / Robosense";
  } else if ((c.time = L.field("time_sec")) && (c.time_nsec = L.field("time_nsec"))) {
    c.time_kind = Time::SplitAbsolute;
    c.layout = "split-time";
  } else if ((c.time = L.field("offset_time"))) {  // after the time base, else after the sweep start (as `t`)
    c.time_kind = L.time_base != 0 ? Time::BaseOffset : Time::Nanoseconds;
    c.layout = L.time_base != 0 ? "Livox CustomMsg" : "offset-time";
  } else {
    c.time = c.time_nsec = nullptr;
  }
  for (const char* name : {"ring", "line", "laser_id"})
    if (!c.ring) c.ring = L.field(name);
  return c;
}

std::string PointConventions::describe() const {
  std::string s = layout.empty() ? "" : layout + " layout: ";
  switch (time_kind) {
    case Time::None: s += "no per-point time (not dewarped)"; break;
    case Time::Nanoseconds: s += "time " + time->name + " (ns from the sweep start)"; break;
    case Time::Seconds: s += "time " + time->name + " (s; absolute ns above 1e15)"; break;
    case Time::SplitAbsolute: s += "time " + time->name + " + " + time_nsec->name + " (absolute)"; break;
    case Time::BaseOffset: s += "time timebase + " + time->name + " (ns, absolute)"; break;
  }
  return s + (ring ? ", ring " + ring->name : ", no ring");
}

namespace {

/// Passes one field of every point to store(i, value) as a double (every stored type converts exactly, so a
/// float made from it rounds as from the stored value), the datatype dispatched once per cloud, not per point.
template <typename Store>
void readColumn(const std::uint8_t* data, std::size_t n, std::size_t step, const PointField& f, Store store) {
  if (n == 0) return;  // an empty cloud's data may be null: no pointer arithmetic on it
  auto loop = [&](auto zero) {
    using Stored = decltype(zero);
    const std::uint8_t* p = data + f.offset;
    for (std::size_t i = 0; i < n; ++i, p += step) {
      Stored v;
      std::memcpy(&v, p, sizeof v);
      store(i, static_cast<double>(v));
    }
  };
  switch (static_cast<PointType>(f.datatype)) {
    case PointType::Int8: return loop(std::int8_t{});
    case PointType::UInt8: return loop(std::uint8_t{});
    case PointType::Int16: return loop(std::int16_t{});
    case PointType::UInt16: return loop(std::uint16_t{});
    case PointType::Int32: return loop(std::int32_t{});
    case PointType::UInt32: return loop(std::uint32_t{});
    case PointType::Float32: return loop(float{});
    case PointType::Float64: return loop(double{});
  }
  for (std::size_t i = 0; i < n; ++i) store(i, std::numeric_limits<double>::quiet_NaN());
}

void checkInside(const CloudLayout& layout, const PointField* f, const std::string& source) {
  if (!f) return;
  const std::size_t size = pointTypeSize(f->datatype);
  if (size == 0)
    throw std::runtime_error(source + ": field '" + f->name + "' has unknown datatype " + std::to_string(f->datatype));
  if (static_cast<std::size_t>(f->offset) + size > layout.point_step)
    throw std::runtime_error(source + ": field '" + f->name + "' lies outside point_step " +
                             std::to_string(layout.point_step));
}

void readPoints(const CloudLayout& L, const std::uint8_t* data, std::size_t n, Scan& scan) {
  const PointField &fx = *L.field("x"), &fy = *L.field("y"), &fz = *L.field("z");
  const std::size_t step = L.point_step;
  scan.points.resize(n);
  const auto f32 = static_cast<std::uint8_t>(PointType::Float32);
  if (fx.datatype == f32 && fy.datatype == f32 && fz.datatype == f32) {
    const std::uint8_t* base = data;
    for (std::size_t i = 0; i < n; ++i, base += step) {
      Eigen::Vector3f& p = scan.points[i];
      std::memcpy(&p.x(), base + fx.offset, 4);
      std::memcpy(&p.y(), base + fy.offset, 4);
      std::memcpy(&p.z(), base + fz.offset, 4);
    }
    return;
  }
  readColumn(data, n, step, fx, [&](std::size_t i, double v) { scan.points[i].x() = static_cast<float>(v); });
  readColumn(data, n, step, fy, [&](std::size_t i, double v) { scan.points[i].y() = static_cast<float>(v); });
  readColumn(data, n, step, fz, [&](std::size_t i, double v) { scan.points[i].z() = static_cast<float>(v); });
}

/// Per-point times relative to the message stamp (see the header for the conventions).
void readTimes(const CloudLayout& L, const PointConventions& c, const std::uint8_t* data, std::size_t n,
               bool stamp_at_end, Scan& scan) {
  using Time = PointConventions::Time;
  scan.time.resize(c.time ? n : 0);
  if (!c.time || n == 0) return;
  // In double until made relative: absolute epoch seconds (Velodyne `time`) would lose minutes in float.
  std::vector<double> t(n);
  if (c.time_kind == Time::SplitAbsolute) {  // relative to the stamp from the start: no precision lost
    const double stamp_sec = static_cast<double>(scan.stamp / 1000000000ULL);
    const double stamp_nsec = static_cast<double>(scan.stamp % 1000000000ULL);
    readColumn(data, n, L.point_step, *c.time, [&](std::size_t i, double v) { t[i] = v - stamp_sec; });
    readColumn(data, n, L.point_step, *c.time_nsec, [&](std::size_t i, double v) { t[i] += (v - stamp_nsec) * 1e-9; });
    for (std::size_t i = 0; i < n; ++i) scan.time[i] = static_cast<float>(t[i]);
    return;
  }
  if (c.time_kind == Time::BaseOffset) {  // the time base's offset to the stamp in integers: no precision lost
    const double base = static_cast<double>(static_cast<std::int64_t>(L.time_base - scan.stamp)) * 1e-9;
    readColumn(data, n, L.point_step, *c.time,
               [&](std::size_t i, double v) { scan.time[i] = static_cast<float>(base + v * 1e-9); });
    return;
  }
  const double scale = c.time_kind == Time::Nanoseconds ? 1e-9 : 1.0;
  readColumn(data, n, L.point_step, *c.time, [&](std::size_t i, double v) { t[i] = v * scale; });
  double t_max = -std::numeric_limits<double>::infinity(), t_min = -t_max;
  for (double ti : t)
    if (std::isfinite(ti)) {
      t_max = std::max(t_max, ti);
      t_min = std::min(t_min, ti);
    }
  if (c.time_kind == Time::Seconds && t_min > 1e15) {  // absolute nanoseconds (Livox): no clock reads 1e15 s
    for (double& ti : t) ti *= 1e-9;
    t_max *= 1e-9;
    t_min *= 1e-9;
  }
  const bool absolute = t_min > 1e6;
  const bool organised_ouster = c.time_kind == Time::Nanoseconds && L.height > 1 && L.width > 1;
  // The sweep end relative to its start: one period for an organised Ouster cloud, else the latest point.
  const double sweep = organised_ouster ? t_max * L.width / (L.width - 1.0) : t_max;
  double ref = sweep;
  if (absolute) {
    ref = toSeconds(scan.stamp);
  } else if (!stamp_at_end && std::isfinite(sweep)) {  // stamped at the start: move the stamp to the end
    scan.stamp += static_cast<StampNs>(std::llround(std::max(0.0, sweep) * 1e9));
  }
  for (std::size_t i = 0; i < n; ++i) scan.time[i] = static_cast<float>(t[i] - ref);
}

/// Marks the invalid returns: (0, 0, 0), or `range` 0 where the field exists.
std::size_t markInvalid(const CloudLayout& L, const std::uint8_t* data, std::size_t n, const Scan& scan,
                        std::vector<char>& invalid) {
  invalid.assign(n, 0);
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (scan.points[i].x() == 0.0f && scan.points[i].y() == 0.0f && scan.points[i].z() == 0.0f) invalid[i] = 1;
  if (const PointField* fr = L.field("range"))
    readColumn(data, n, L.point_step, *fr, [&](std::size_t i, double v) {
      if (v == 0.0) invalid[i] = 1;
    });
  for (char c : invalid) count += c;
  return count;
}

template <typename T>
void compact(std::vector<T>& v, const std::vector<char>& invalid) {
  if (v.empty()) return;
  std::size_t k = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!invalid[i]) v[k++] = v[i];
  v.resize(k);
}

}  // namespace

DecodeCounts decodeCloud(const CloudLayout& L, const std::uint8_t* data, std::size_t bytes, bool stamp_at_end,
                         const std::string& source, Scan& scan) {
  const PointField *fx = L.field("x"), *fy = L.field("y"), *fz = L.field("z");
  if (!fx || !fy || !fz)
    throw std::runtime_error(source + ": PointCloud2 has no x/y/z fields (has: " + describeFields(L) + ")");
  if (L.is_bigendian) throw std::runtime_error(source + ": big-endian PointCloud2 is not supported");
  const std::size_t n = L.points();
  if (L.point_step == 0 || n > bytes / L.point_step)  // a division: width * height * point_step may overflow
    throw std::runtime_error(source + ": PointCloud2 data holds " + std::to_string(bytes) + " bytes, expected " +
                             std::to_string(L.width) + " x " + std::to_string(L.height) + " points of " +
                             std::to_string(L.point_step) + " bytes (width*height*point_step)");
  const PointConventions conventions = pointConventions(L);
  const PointField *fi = L.field("intensity"), *fr = conventions.ring, *frange = L.field("range");
  for (const PointField* f : {fx, fy, fz, fi, fr, conventions.time, conventions.time_nsec, frange})
    checkInside(L, f, source);

  scan.stamp = L.stamp;
  readPoints(L, data, n, scan);
  scan.intensity.resize(fi ? n : 0);
  if (fi)
    readColumn(data, n, L.point_step, *fi, [&](std::size_t i, double v) { scan.intensity[i] = static_cast<float>(v); });
  scan.ring.resize(fr ? n : 0);
  if (fr)
    readColumn(data, n, L.point_step, *fr, [&](std::size_t i, double d) {
      // A float ring field may hold NaN: line 0, never UB.
      scan.ring[i] = static_cast<std::uint16_t>(std::isfinite(d) ? std::clamp(d, 0.0, 65535.0) : 0.0);
    });
  readTimes(L, conventions, data, n, stamp_at_end, scan);

  DecodeCounts counts;
  counts.points = n;
  thread_local std::vector<char> invalid;
  counts.invalid = markInvalid(L, data, n, scan, invalid);
  if (counts.invalid > 0) {
    compact(scan.points, invalid);
    compact(scan.intensity, invalid);
    compact(scan.ring, invalid);
    compact(scan.time, invalid);
  }
  return counts;
}

}  // namespace cosmo::trials
