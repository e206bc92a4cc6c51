#pragma once
// A PointCloud2 as plain data (no ROS types), and its decoding into a Scan: the one place where point fields
// become a Scan, for ROS 1 messages (src/ros/point_cloud.cpp) and ROS 2 CDR messages (cdr_point_cloud.hpp).
//
// Fields x y z (float32 or float64) are required; intensity, a ring (any numeric type) and a per-point time are
// used when present (pointConventions() names which field is which, the one place that decides it). The time is
// `t` (ns from the sweep start, Ouster), `time` / `timestamp` (seconds, relative (Velodyne) or absolute (Hesai,
// Robosense); absolute nanoseconds when its values exceed 1e15 (Livox's PointCloud2)), `time_sec` + `time_nsec`
// (absolute, split), or `offset_time` (ns after the layout's `time_base`: Livox's CustomMsg, read by
// ros1_point_cloud.hpp; ns from the sweep start when there is no time base); the ring is `ring`, else Livox's
// `line`, else `laser_id`. docs/data.md tables them per LiDAR. Every scan comes out stamped at its sweep end,
// times <= 0 relative to it:
//  - the sweep lasts t_max * width / (width - 1) in an organised Ouster cloud (height > 1, `t` in ns: the
//    columns are evenly spaced), else up to the latest point (t_max); time = t - that duration;
//  - stamp at the sweep end (`stamp_at_end`, MCD): the stamp is kept, i.e. a point's time is stamp - period + t;
//  - stamp at the sweep start (CU-Multi): the stamp moves to stamp + duration (a start- and an end-stamped copy
//    of the same sweep decode to the same scan);
//  - absolute per-point stamps (> 1e6 s) are made relative to the message stamp, which is kept.
// Invalid returns — (0, 0, 0), or `range` 0 where that field exists — are dropped here, so no module sees
// them. Errors throw std::runtime_error naming `source` and the field.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo::trials {

/// sensor_msgs/PointField datatypes (same numbers in ROS 1 and ROS 2).
enum class PointType : std::uint8_t {
  Int8 = 1,
  UInt8 = 2,
  Int16 = 3,
  UInt16 = 4,
  Int32 = 5,
  UInt32 = 6,
  Float32 = 7,
  Float64 = 8
};
/// Bytes of one value of `datatype` (0 for an unknown type).
std::size_t pointTypeSize(std::uint8_t datatype);
/// "float32", "uint8", ... ("type N" for an unknown one).
std::string pointTypeName(std::uint8_t datatype);

struct PointField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};

/// Everything of a PointCloud2 but its point bytes.
struct CloudLayout {
  StampNs stamp = 0;
  std::string frame_id;
  std::uint32_t height = 1;
  std::uint32_t width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  bool is_dense = false;
  /// Livox CustomMsg's `timebase` (ns; 0 for a PointCloud2): a point's absolute time is time_base + offset_time.
  StampNs time_base = 0;

  const PointField* field(const std::string& name) const;
  std::size_t points() const { return static_cast<std::size_t>(width) * height; }
};

/// A parsed message (ROS 1 or CDR): its layout and where its point bytes lie inside the serialized buffer.
struct CloudView {
  CloudLayout layout;
  const std::uint8_t* data = nullptr;
  std::size_t bytes = 0;
};

/// "x:float32@0 y:float32@4 ..." (for pre-flight checks and error messages).
std::string describeFields(const CloudLayout& layout);

/// Which fields of a cloud hold each point's time and ring.
struct PointConventions {
  enum class Time {
    None,           ///< no usable per-point time: the sweep is not dewarped
    Nanoseconds,    ///< `t`: ns from the sweep start (Ouster)
    Seconds,        ///< `time` / `timestamp`: s, relative or absolute; absolute ns above 1e15 (Livox)
    SplitAbsolute,  ///< `time_sec` + `time_nsec`: absolute, split in two integers
    BaseOffset,     ///< `offset_time`: ns after the layout's time_base (Livox CustomMsg), absolute
  };
  Time time_kind = Time::None;
  const PointField* time = nullptr;       ///< t, time, timestamp, time_sec or offset_time
  const PointField* time_nsec = nullptr;  ///< with SplitAbsolute
  const PointField* ring = nullptr;       ///< ring, else line (Livox), else laser_id
  /// The layout recognised by its fields (docs/data.md): "Ouster", "Velodyne", "Hesai / Robosense", "Livox
  /// PointCloud2", "Livox CustomMsg", "split-time", "offset-time" (`offset_time` without a time base), "" (none).
  std::string layout;

  /// "Ouster layout: time t (ns from the sweep start), ring ring", "no per-point time (not dewarped), no ring", ...
  std::string describe() const;
};
PointConventions pointConventions(const CloudLayout& layout);

/// A cloud with its point bytes (what the simulator writes).
struct RawCloud {
  CloudLayout layout;
  std::vector<std::uint8_t> data;
};

/// What one decode saw.
struct DecodeCounts {
  std::size_t points = 0;   ///< points in the message (width * height)
  std::size_t invalid = 0;  ///< invalid returns dropped
};

/// Decodes `bytes` of point data laid out as `layout` into `scan` (reusing its vectors' capacity).
DecodeCounts decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t bytes, bool stamp_at_end,
                         const std::string& source, Scan& scan);

}  // namespace cosmo::trials
