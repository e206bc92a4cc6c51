#pragma once
// sensor_msgs/msg/PointCloud2 in ROS 2's CDR serialization (what a ROS 2 bag stores), read and written without
// ROS 2: a 4-byte encapsulation header (00 01 00 00: little-endian CDR), then the message with every value
// aligned to its size counted from the end of that header — header (int32 sec, uint32 nanosec, string
// frame_id), height, width, fields (uint32 count; per field string name, uint32 offset, uint8 datatype,
// uint32 count), uint8 is_bigendian, point_step, row_step, uint8[] data (uint32 length + bytes), uint8 is_dense.
// A string is a uint32 length including its terminating NUL, then the bytes. Truncated or malformed messages
// throw std::runtime_error naming `source` and the member being read; nothing reads outside the buffer.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

CloudView parseCdrPointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source);

/// Parses and decodes into `scan` (see decodeCloud).
DecodeCounts decodeCdrPointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                  const std::string& source, Scan& scan);

/// Little-endian CDR of `cloud` (what parseCdrPointCloud2 reads back).
std::vector<std::uint8_t> encodeCdrPointCloud2(const RawCloud& cloud);

}  // namespace cosmo::trials
