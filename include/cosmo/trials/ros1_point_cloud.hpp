#pragma once
// sensor_msgs/PointCloud2 in ROS 1's serialization (what a ROS 1 bag stores), read without ROS: little-endian,
// no alignment — header (uint32 seq, uint32 sec, uint32 nsec, string frame_id), height, width, fields (uint32
// count; per field string name, uint32 offset, uint8 datatype, uint32 count), uint8 is_bigendian, point_step,
// row_step, uint8[] data (uint32 length + bytes), uint8 is_dense; a string is a uint32 length and the bytes.
// Truncated or malformed messages throw std::runtime_error naming `source`, the member and its byte offset;
// nothing reads outside the buffer.
//
// Livox's livox_ros_driver/CustomMsg (livox_ros_driver2's has the same definition and md5sum), what FAST-LIO users
// record: header, uint64 timebase (ns, the first point's time), uint32 point_num, uint8 lidar_id, uint8[3] rsvd,
// CustomPoint[] points (uint32 count; per point uint32 offset_time (ns after timebase), float32 x y z, uint8
// reflectivity, tag, line: 19 bytes, packed). Its points are read in place as a cloud of one row with those
// fields at those offsets and layout.time_base = timebase (point_cloud_decode.hpp: per-point time timebase +
// offset_time, ring line).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

struct Ros1Connection;

/// What a trial's topic in a ROS 1 bag holds.
enum class Ros1CloudType { PointCloud2, LivoxCustomMsg };

constexpr const char* kRos1PointCloud2 = "sensor_msgs/PointCloud2";
/// md5sum of livox_ros_driver/CustomMsg and livox_ros_driver2/CustomMsg (the definition above).
constexpr const char* kLivoxCustomMsgMd5 = "e4d6829bdfe657cb6c21a746c86b21a6";
/// The message definition a bag's connection record carries for it (as genmsg writes it).
extern const char* const kLivoxCustomMsgDefinition;

/// The type of a connection's messages; throws naming `where` (bag and topic), the type and its md5sum for any
/// other type, and for a Livox CustomMsg of another definition (another md5sum: an older driver's).
Ros1CloudType ros1CloudType(const Ros1Connection& connection, const std::string& where);

/// A Livox CustomMsg's points as a cloud (see above); data points into `message`.
CloudView parseLivoxCustomMsg(const std::uint8_t* message, std::size_t size, const std::string& source);

/// A message of `type` parsed (parseRos1PointCloud2 or parseLivoxCustomMsg).
CloudView parseRos1Cloud(Ros1CloudType type, const std::uint8_t* message, std::size_t size, const std::string& source);

/// A scan as a serialized Livox CustomMsg (what the simulator writes, cosmo_simulate --points livox-custom): one
/// point per return in the scan's order, `timebase` the earliest point's time, the header stamped at the scan's
/// stamp (its sweep end), reflectivity the intensity clamped to 0..255, tag 0, line the ring.
std::vector<std::uint8_t> serializeLivoxCustomMsg(const Scan& scan, const std::string& frame_id);

CloudView parseRos1PointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source);

/// Parses and decodes into `scan` (see decodeCloud); `layout` receives the message's layout.
DecodeCounts decodeRos1PointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                   const std::string& source, Scan& scan, CloudLayout& layout);
/// The same for a message of `type`.
DecodeCounts decodeRos1Cloud(Ros1CloudType type, const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                             const std::string& source, Scan& scan, CloudLayout& layout);

}  // namespace cosmo::trials
