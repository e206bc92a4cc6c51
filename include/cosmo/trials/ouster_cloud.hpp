#pragma once
// An Ouster sweep as the driver publishes it: an organised cloud (height = beams, width = columns, pixel
// (beam b, column c) at b * width + c) in which every pixel is present and a pixel without a return is
// (0, 0, 0) with range 0. `t` is uint32 ns from the sweep start (column c at c * period / columns); the
// header stamp is the sweep start or its end (start + period). Used to write trials in the real datasets'
// layouts (mcd_layout.hpp, cu_multi_layout.hpp) from simulated scans.
#include <cstdint>
#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

struct OusterSweep {
  int beams = 64;
  int columns = 1024;
  double rate_hz = 10.0;
  bool stamp_at_end = true;  ///< header stamp at the sweep end (MCD) or start (CU-Multi)
  bool ring_uint16 = false;  ///< ring as uint16 (ouster-ros 2) or uint8 (MCD's driver)
  std::string frame_id = "os_sensor";
};

/// The fields x y z (float32 at 0/4/8), intensity (float32, 16), t (uint32 ns, 20), reflectivity (uint16, 24),
/// ring (uint8 or uint16, 26), ambient (uint16, 28), range (uint32 mm, 32); point_step 48.
CloudLayout ousterLayout(const OusterSweep& sweep);

/// `scan`: a simulated sweep (sim::ScanSimulator) — ring = beam, time = the column's time relative to
/// scan.stamp, the last column at 0. Each point goes to its (beam, column) pixel; the header stamp follows
/// `sweep.stamp_at_end`. Throws when a point's beam or column lies outside the sweep.
RawCloud organisedOusterCloud(const Scan& scan, const OusterSweep& sweep);

/// Header stamp of the organised cloud of a simulated sweep stamped `sim_stamp` (its last column).
StampNs ousterHeaderStamp(StampNs sim_stamp, const OusterSweep& sweep);

}  // namespace cosmo::trials
