#pragma once
// Simulates one LiDAR sweep along a continuous trajectory: every column is cast from the sensor pose at its
// own time (real motion distortion), points are expressed in the sensor frame at that time, the scan is
// stamped at the end of the sweep and `time` holds each point's offset (<= 0 s). Rays run in parallel (TBB);
// noise comes from a counter-based generator keyed by (seed, stamp, ray index), so the output does not
// depend on thread scheduling. The seed also fixes the sensor's beam calibration errors (one sensor per seed).
// Optional physics (LidarModel): each return from a random point of the beam's footprint, late detection of weak
// pulses (range walk), canopies as a volume of leaves that rays scatter inside or pass through.
#include <cstdint>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sim/lidar_model.hpp"
#include "cosmo/sim/world.hpp"

namespace cosmo::sim {

class ScanSimulator {
 public:
  ScanSimulator(const World& world, LidarModel lidar);

  /// The sweep ending at `stamp`; `body` is the body trajectory in the world, `T_body_lidar` the extrinsic.
  /// Points are ordered ring by ring (ring 0 = top beam), columns in firing order.
  Scan simulate(const Trajectory& body, const Pose3& T_body_lidar, StampNs stamp, std::uint64_t seed) const;
  /// Same, with the sensor pose of every column given (columns() poses of T_world_lidar).
  Scan simulate(const std::vector<Pose3>& column_poses, StampNs stamp, std::uint64_t seed) const;

  /// Unit direction of (beam, column) in the sensor frame.
  const Eigen::Vector3d& direction(int beam, int column) const {
    return dirs_[static_cast<std::size_t>(beam) * lidar_.columns + column];
  }
  const LidarModel& lidar() const { return lidar_; }
  /// Directions the rays of a sensor with noise seed `seed` really leave along (sensor frame): the nominal ones
  /// turned by the beam's calibration error (LidarModel::beam_angle_sigma_deg; none: the nominal ones).
  std::vector<Eigen::Vector3d> castDirections(std::uint64_t seed) const;

 private:
  const World& world_;
  LidarModel lidar_;
  std::vector<Eigen::Vector3d> dirs_;  ///< beams x columns
};

/// SplitMix64 step, the building block of the per-ray noise.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace cosmo::sim
