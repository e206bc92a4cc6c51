#include "cosmo/ros/point_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

namespace cosmo::ros_glue {

namespace {
/// Everything of the message but its point bytes, as the core's plain layout.
trials::CloudLayout layoutOf(const sensor_msgs::PointCloud2& msg) {
  trials::CloudLayout L;
  L.stamp = static_cast<StampNs>(msg.header.stamp.sec) * 1000000000ULL + msg.header.stamp.nsec;
  L.frame_id = msg.header.frame_id;
  L.height = msg.height;
  L.width = msg.width;
  L.fields.reserve(msg.fields.size());
  for (const auto& f : msg.fields) L.fields.push_back({f.name, f.offset, f.datatype, f.count});
  L.is_bigendian = msg.is_bigendian;
  L.point_step = msg.point_step;
  L.row_step = msg.row_step;
  L.is_dense = msg.is_dense;
  return L;
}
}  // namespace

Scan fromPointCloud2(const sensor_msgs::PointCloud2& msg, bool stamp_at_end, const std::string& source) {
  Scan scan;
  decodePointCloud2(msg, msg.data.data(), msg.data.size(), stamp_at_end, source, scan);
  return scan;
}

trials::DecodeCounts decodePointCloud2(const sensor_msgs::PointCloud2& msg, const uint8_t* data, std::size_t bytes,
                                       bool stamp_at_end, const std::string& source, Scan& scan) {
  return trials::decodeCloud(layoutOf(msg), data, bytes, stamp_at_end, source, scan);
}

sensor_msgs::PointCloud2 toPointCloud2(const trials::RawCloud& cloud) {
  sensor_msgs::PointCloud2 msg;
  const auto& L = cloud.layout;
  msg.header.frame_id = L.frame_id;
  msg.header.stamp.sec = static_cast<uint32_t>(L.stamp / 1000000000ULL);
  msg.header.stamp.nsec = static_cast<uint32_t>(L.stamp % 1000000000ULL);
  msg.height = L.height;
  msg.width = L.width;
  for (const auto& f : L.fields) {
    sensor_msgs::PointField pf;
    pf.name = f.name;
    pf.offset = f.offset;
    pf.datatype = f.datatype;
    pf.count = f.count;
    msg.fields.push_back(pf);
  }
  msg.is_bigendian = L.is_bigendian;
  msg.point_step = L.point_step;
  msg.row_step = L.row_step;
  msg.data = cloud.data;
  msg.is_dense = L.is_dense;
  return msg;
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
    if (ouster_time)
      add("t", sensor_msgs::PointField::UINT32, 4);
    else
      add("time", sensor_msgs::PointField::FLOAT32, 4);
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
    if (scan.hasIntensity()) {
      std::memcpy(p + off, &scan.intensity[i], 4);
      off += 4;
    }
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
