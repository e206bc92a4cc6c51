#pragma once
// sensor_msgs/PointCloud2 in ROS 1's serialization (what a ROS 1 bag stores), read without ROS: little-endian,
// no alignment — header (uint32 seq, uint32 sec, uint32 nsec, string frame_id), height, width, fields (uint32
// count; per field string name, uint32 offset, uint8 datatype, uint32 count), uint8 is_bigendian, point_step,
// row_step, uint8[] data (uint32 length + bytes), uint8 is_dense; a string is a uint32 length and the bytes.
// Truncated or malformed messages throw std::runtime_error naming `source`, the member and its byte offset;
// nothing reads outside the buffer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

CloudView parseRos1PointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source);

/// Parses and decodes into `scan` (see decodeCloud); `layout` receives the message's layout.
DecodeCounts decodeRos1PointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                   const std::string& source, Scan& scan, CloudLayout& layout);

}  // namespace cosmo::trials
