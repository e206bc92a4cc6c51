#include "cosmo/ros/point_cloud.hpp"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

namespace cosmo::ros_glue {

namespace {
const sensor_msgs::PointField* findField(const sensor_msgs::PointCloud2& msg, const std::string& name) {
  for (const auto& f : msg.fields)
    if (f.name == name) return &f;
  return nullptr;
}

std::size_t sizeOf(uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: case sensor_msgs::PointField::UINT8: return 1;
    case sensor_msgs::PointField::INT16: case sensor_msgs::PointField::UINT16: return 2;
    case sensor_msgs::PointField::FLOAT64: return 8;
    default: return 4;
  }
}

/// Passes one field of every point to store(i, value) as a double (every stored type converts exactly, so a
/// float made from it rounds as from the stored value), the datatype dispatched once per cloud, not per point.
template <typename Store>
void readColumn(const uint8_t* data, std::size_t n, std::size_t step, const sensor_msgs::PointField& f, Store store) {
  auto loop = [&](auto zero) {
    using Stored = decltype(zero);
    const uint8_t* p = data + f.offset;
    for (std::size_t i = 0; i < n; ++i, p += step) {
      Stored v;
      std::memcpy(&v, p, sizeof v);
      store(i, static_cast<double>(v));
    }
  };
  switch (f.datatype) {
    case sensor_msgs::PointField::INT8: return loop(int8_t{});
    case sensor_msgs::PointField::UINT8: return loop(uint8_t{});
    case sensor_msgs::PointField::INT16: return loop(int16_t{});
    case sensor_msgs::PointField::UINT16: return loop(uint16_t{});
    case sensor_msgs::PointField::INT32: return loop(int32_t{});
    case sensor_msgs::PointField::UINT32: return loop(uint32_t{});
    case sensor_msgs::PointField::FLOAT32: return loop(float{});
    case sensor_msgs::PointField::FLOAT64: return loop(double{});
    default:
      for (std::size_t i = 0; i < n; ++i) store(i, std::numeric_limits<double>::quiet_NaN());
  }
}
}  // namespace

Scan fromPointCloud2(const sensor_msgs::PointCloud2& msg, bool stamp_at_end, const std::string& source) {
  Scan scan;
  decodePointCloud2(msg, msg.data.data(), msg.data.size(), stamp_at_end, source, scan);
  return scan;
}

void decodePointCloud2(const sensor_msgs::PointCloud2& msg, const uint8_t* data, std::size_t bytes, bool stamp_at_end,
                       const std::string& source, Scan& scan) {
  const auto* fx = findField(msg, "x");
  const auto* fy = findField(msg, "y");
  const auto* fz = findField(msg, "z");
  if (!fx || !fy || !fz) throw std::runtime_error(source + ": PointCloud2 has no x/y/z fields");
  const std::size_t n = static_cast<std::size_t>(msg.width) * msg.height;
  if (msg.point_step == 0 || bytes < n * msg.point_step)
    throw std::runtime_error(source + ": PointCloud2 data holds " + std::to_string(bytes) + " bytes, expected " +
                             std::to_string(n * msg.point_step) + " (width*height*point_step)");
  for (const auto* f : {fx, fy, fz})
    if (f->offset + sizeOf(f->datatype) > msg.point_step)
      throw std::runtime_error(source + ": field '" + f->name + "' lies outside point_step");
  const auto* fi = findField(msg, "intensity");
  const auto* fr = findField(msg, "ring");
  const auto* ft = findField(msg, "t");
  double t_scale = 1e-9;  // Ouster `t`: ns
  if (!ft) {
    ft = findField(msg, "time");
    if (!ft) ft = findField(msg, "timestamp");
    t_scale = 1.0;
  }
  for (const auto* f : {fi, fr, ft})
    if (f && f->offset + sizeOf(f->datatype) > msg.point_step)
      throw std::runtime_error(source + ": field '" + f->name + "' lies outside point_step");
  scan.stamp = static_cast<StampNs>(msg.header.stamp.sec) * 1000000000ULL + msg.header.stamp.nsec;
  const std::size_t step = msg.point_step;
  // A column per field, its datatype resolved once (a cloud of ~1 MB stays in the cache between the columns).
  scan.points.resize(n);
  const bool xyz_float = fx->datatype == sensor_msgs::PointField::FLOAT32 &&
                         fy->datatype == sensor_msgs::PointField::FLOAT32 &&
                         fz->datatype == sensor_msgs::PointField::FLOAT32;
  if (xyz_float) {
    const uint8_t* base = data;
    for (std::size_t i = 0; i < n; ++i, base += step) {
      Eigen::Vector3f& p = scan.points[i];
      std::memcpy(&p.x(), base + fx->offset, 4);
      std::memcpy(&p.y(), base + fy->offset, 4);
      std::memcpy(&p.z(), base + fz->offset, 4);
    }
  } else {
    readColumn(data, n, step, *fx, [&](std::size_t i, double v) { scan.points[i].x() = static_cast<float>(v); });
    readColumn(data, n, step, *fy, [&](std::size_t i, double v) { scan.points[i].y() = static_cast<float>(v); });
    readColumn(data, n, step, *fz, [&](std::size_t i, double v) { scan.points[i].z() = static_cast<float>(v); });
  }
  scan.intensity.resize(fi ? n : 0);
  if (fi)
    readColumn(data, n, step, *fi, [&](std::size_t i, double v) { scan.intensity[i] = static_cast<float>(v); });
  scan.ring.resize(fr ? n : 0);
  if (fr)
    readColumn(data, n, step, *fr, [&](std::size_t i, double d) {
      // A float ring field may hold NaN: line 0, never UB.
      scan.ring[i] = static_cast<uint16_t>(std::isfinite(d) ? std::clamp(d, 0.0, 65535.0) : 0.0);
    });
  scan.time.resize(ft ? n : 0);
  if (ft && n > 0) {
    // In double until made relative: absolute epoch seconds (Velodyne `time`) would lose minutes in float.
    std::vector<double> t(n);
    readColumn(data, n, step, *ft, [&](std::size_t i, double v) { t[i] = v * t_scale; });
    double t_max = -std::numeric_limits<double>::infinity(), t_min = -t_max;
    for (double ti : t) {
      if (std::isfinite(ti)) { t_max = std::max(t_max, ti); t_min = std::min(t_min, ti); }
    }
    // Times relative to the stamp: with the stamp at the sweep end the latest point sits at 0; absolute stamps
    // are made relative to the message stamp.
    const bool absolute = t_min > 1e6;
    const double ref = absolute ? toSeconds(scan.stamp) : (stamp_at_end ? t_max : 0.0);
    for (std::size_t i = 0; i < n; ++i) scan.time[i] = static_cast<float>(t[i] - ref);
  }
}

sensor_msgs::PointCloud2 toPointCloud2(const Scan& scan, const std::string& frame_id, PointTimeEncoding time_encoding) {
  const bool ouster_time = time_encoding == PointTimeEncoding::OusterNs;
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp.sec = static_cast<uint32_t>(scan.stamp / 1000000000ULL);
  msg.header.stamp.nsec = static_cast<uint32_t>(scan.stamp % 1000000000ULL);
  msg.height = 1;
  msg.width = static_cast<uint32_t>(scan.size());
  msg.is_dense = false;
  msg.is_bigendian = false;
  auto add = [&msg](const std::string& name, uint8_t type, uint32_t size) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = msg.point_step;
    f.datatype = type;
    f.count = 1;
    msg.fields.push_back(f);
    msg.point_step += size;
  };
  add("x", sensor_msgs::PointField::FLOAT32, 4);
  add("y", sensor_msgs::PointField::FLOAT32, 4);
  add("z", sensor_msgs::PointField::FLOAT32, 4);
  if (scan.hasIntensity()) add("intensity", sensor_msgs::PointField::FLOAT32, 4);
  if (scan.hasTime()) {
    if (ouster_time) add("t", sensor_msgs::PointField::UINT32, 4);
    else add("time", sensor_msgs::PointField::FLOAT32, 4);
  }
  if (scan.hasRing()) add("ring", sensor_msgs::PointField::UINT16, 2);
  msg.row_step = msg.point_step * msg.width;
  msg.data.resize(static_cast<std::size_t>(msg.row_step));
  float t_min = 0.0f;
  if (scan.hasTime()) t_min = *std::min_element(scan.time.begin(), scan.time.end());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    uint8_t* p = msg.data.data() + i * msg.point_step;
    std::memcpy(p, scan.points[i].data(), 12);
    std::size_t off = 12;
    if (scan.hasIntensity()) { std::memcpy(p + off, &scan.intensity[i], 4); off += 4; }
    if (scan.hasTime() && ouster_time) {
      const auto t = static_cast<uint32_t>(std::llround((scan.time[i] - t_min) * 1e9));
      std::memcpy(p + off, &t, 4);
      off += 4;
    } else if (scan.hasTime()) {
      std::memcpy(p + off, &scan.time[i], 4);
      off += 4;
    }
    if (scan.hasRing()) { std::memcpy(p + off, &scan.ring[i], 2); }
  }
  return msg;
}

}  // namespace cosmo::ros_glue
