#pragma once
// sensor_msgs/PointCloud2 <-> cosmo::Scan.
//
// Reading: fields x y z (float32 or float64) are required; intensity, ring (any integer type) and a per-point
// time are used when present. The per-point time is taken from `t` (uint32 ns, Ouster), `time` or
// `timestamp` (float seconds, Velodyne/Hesai); it is converted to seconds relative to the message stamp:
// with `stamp_at_end` (the Ouster/MCD convention) the latest point is at the stamp, otherwise the stamp is the
// sweep start. Errors throw std::runtime_error naming the topic (`source`) and field.
#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "cosmo/common/scan.hpp"

namespace cosmo::ros_glue {

Scan fromPointCloud2(const sensor_msgs::PointCloud2& msg, bool stamp_at_end = true,
                     const std::string& source = "PointCloud2");

/// The same for a cloud whose point bytes lie elsewhere (`data`, `bytes`; msg.data is not read): a message
/// parsed in place from its serialized form (ScanBagReader). Fills `scan`, reusing its vectors' capacity.
void decodePointCloud2(const sensor_msgs::PointCloud2& msg, const uint8_t* data, std::size_t bytes, bool stamp_at_end,
                       const std::string& source, Scan& scan);

/// How toPointCloud2 writes the per-point time.
enum class PointTimeEncoding {
  OusterNs,         ///< `t`, uint32 ns since the sweep start (what an Ouster driver publishes)
  RelativeSeconds,  ///< `time`, float32 seconds relative to the stamp, the Scan's own values: read back by
                    ///< fromPointCloud2(.., stamp_at_end = true) bit-exactly when the latest point is at 0
                    ///< (every scan read from a bag with stamp_at_end), the player's lockstep mode
};

/// x y z intensity t|time ring (stamped at the sweep end when the scan has times), only the fields the scan
/// has; frame and stamp from the arguments.
sensor_msgs::PointCloud2 toPointCloud2(const Scan& scan, const std::string& frame_id,
                                       PointTimeEncoding time_encoding = PointTimeEncoding::OusterNs);

}  // namespace cosmo::ros_glue
