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

/// The value at `p` stored as `datatype` (int8 ... float64); NaN for an unknown datatype. Every stored type is
/// exactly representable in double, so converting the result to float rounds as converting the stored value would.
inline double readValue(const uint8_t* p, uint8_t datatype) {
  auto as = [p](auto zero) {
    decltype(zero) v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (datatype) {
    case sensor_msgs::PointField::INT8: return as(int8_t{});
    case sensor_msgs::PointField::UINT8: return as(uint8_t{});
    case sensor_msgs::PointField::INT16: return as(int16_t{});
    case sensor_msgs::PointField::UINT16: return as(uint16_t{});
    case sensor_msgs::PointField::INT32: return as(int32_t{});
    case sensor_msgs::PointField::UINT32: return as(uint32_t{});
    case sensor_msgs::PointField::FLOAT32: return as(float{});
    case sensor_msgs::PointField::FLOAT64: return as(double{});
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

std::size_t sizeOf(uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: case sensor_msgs::PointField::UINT8: return 1;
    case sensor_msgs::PointField::INT16: case sensor_msgs::PointField::UINT16: return 2;
    case sensor_msgs::PointField::FLOAT64: return 8;
    default: return 4;
  }
}
}  // namespace

Scan fromPointCloud2(const sensor_msgs::PointCloud2& msg, bool stamp_at_end, const std::string& source) {
  const auto* fx = findField(msg, "x");
  const auto* fy = findField(msg, "y");
  const auto* fz = findField(msg, "z");
  if (!fx || !fy || !fz) throw std::runtime_error(source + ": PointCloud2 has no x/y/z fields");
  const std::size_t n = static_cast<std::size_t>(msg.width) * msg.height;
  if (msg.point_step == 0 || msg.data.size() < n * msg.point_step)
    throw std::runtime_error(source + ": PointCloud2 data holds " + std::to_string(msg.data.size()) +
                             " bytes, expected " + std::to_string(n * msg.point_step) + " (width*height*point_step)");
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
  Scan scan;
  scan.stamp = static_cast<StampNs>(msg.header.stamp.sec) * 1000000000ULL + msg.header.stamp.nsec;
  // One pass over the points (a cloud is megabytes: a pass per field streamed it from memory six times).
  scan.points.resize(n);
  if (fi) scan.intensity.resize(n);
  if (fr) scan.ring.resize(n);
  std::vector<double> t(ft ? n : 0);  // in double until made relative (see below)
  const bool xyz_float = fx->datatype == sensor_msgs::PointField::FLOAT32 &&
                         fy->datatype == sensor_msgs::PointField::FLOAT32 &&
                         fz->datatype == sensor_msgs::PointField::FLOAT32;
  const uint8_t* base = msg.data.data();
  for (std::size_t i = 0; i < n; ++i, base += msg.point_step) {
    Eigen::Vector3f& p = scan.points[i];
    if (xyz_float) {
      std::memcpy(&p.x(), base + fx->offset, 4);
      std::memcpy(&p.y(), base + fy->offset, 4);
      std::memcpy(&p.z(), base + fz->offset, 4);
    } else {
      p = Eigen::Vector3f(static_cast<float>(readValue(base + fx->offset, fx->datatype)),
                          static_cast<float>(readValue(base + fy->offset, fy->datatype)),
                          static_cast<float>(readValue(base + fz->offset, fz->datatype)));
    }
    if (fi) scan.intensity[i] = static_cast<float>(readValue(base + fi->offset, fi->datatype));
    if (fr) {
      const double d = readValue(base + fr->offset, fr->datatype);  // a float ring field may hold NaN: line 0, never UB
      scan.ring[i] = static_cast<uint16_t>(std::isfinite(d) ? std::clamp(d, 0.0, 65535.0) : 0.0);
    }
    if (ft) t[i] = readValue(base + ft->offset, ft->datatype) * t_scale;
  }
  if (ft && n > 0) {
    // In double until made relative: absolute epoch seconds (Velodyne `time`) would lose minutes in float.
    double t_max = -std::numeric_limits<double>::infinity(), t_min = -t_max;
    for (double ti : t) {
      if (std::isfinite(ti)) { t_max = std::max(t_max, ti); t_min = std::min(t_min, ti); }
    }
    // Times relative to the stamp: with the stamp at the sweep end the latest point sits at 0; absolute stamps
    // are made relative to the message stamp.
    const bool absolute = t_min > 1e6;
    const double ref = absolute ? toSeconds(scan.stamp) : (stamp_at_end ? t_max : 0.0);
    scan.time.resize(n);
    for (std::size_t i = 0; i < n; ++i) scan.time[i] = static_cast<float>(t[i] - ref);
  }
  return scan;
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
