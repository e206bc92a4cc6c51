#pragma once
// sensor_msgs/PointCloud2 <-> cosmo::Scan.
//
// Reading is trials::decodeCloud (cosmo/trials/point_cloud_decode.hpp: fields, per-point time conventions,
// invalid returns dropped). Errors throw std::runtime_error naming the topic (`source`) and field.
#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::ros_glue {

Scan fromPointCloud2(const sensor_msgs::PointCloud2& msg, bool stamp_at_end = true,
                     const std::string& source = "PointCloud2");

/// The same for a cloud whose point bytes lie elsewhere (`data`, `bytes`; msg.data is not read): a message
/// parsed in place from its serialized form (trials::Ros1ScanSource). Fills `scan`, reusing its vectors' capacity.
trials::DecodeCounts decodePointCloud2(const sensor_msgs::PointCloud2& msg, const uint8_t* data, std::size_t bytes,
                                       bool stamp_at_end, const std::string& source, Scan& scan);

/// A plain cloud (e.g. the simulator's organised Ouster cloud) as a message, fields and bytes unchanged.
sensor_msgs::PointCloud2 toPointCloud2(const trials::RawCloud& cloud);

/// How toPointCloud2 writes the per-point time.
enum class PointTimeEncoding {
  OusterNs,         ///< `t`, uint32 ns since the sweep start (what an Ouster driver publishes)
  RelativeSeconds,  ///< `time`, float32 seconds relative to the stamp, the Scan's own values: read back by
                    ///< fromPointCloud2(.., stamp_at_end = true) bit-exactly when the latest point is at 0
                    ///< (every scan read from a bag with stamp_at_end), the player's lockstep mode
};

/// How a played scan's points carry their times: lockstep keeps the scan's own values (bit-exact, so the launch
/// writes the offline driver's JRL), real time writes what an Ouster driver publishes.
inline PointTimeEncoding playedPointTimes(bool lockstep) {
  return lockstep ? PointTimeEncoding::RelativeSeconds : PointTimeEncoding::OusterNs;
}

/// x y z intensity t|time ring (stamped at the sweep end when the scan has times), only the fields the scan
/// has; frame and stamp from the arguments.
sensor_msgs::PointCloud2 toPointCloud2(const Scan& scan, const std::string& frame_id,
                                       PointTimeEncoding time_encoding = PointTimeEncoding::OusterNs);

}  // namespace cosmo::ros_glue
