#pragma once
// Turns a 2-D route into a smooth, time-stamped 6-DoF body trajectory: corners rounded with circular arcs,
// a speed profile limited by cruise speed, lateral acceleration and longitudinal acceleration (starting and
// ending at rest), height/roll/pitch following the terrain, and optional gait bob/sway for handheld use.
#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sim/terrain.hpp"

namespace cosmo::sim {

struct MotionParams {
  double cruise_speed = 4.0;       ///< m/s (handheld ~1.4, ATV/car 3-8)
  double speed_variation = 0.15;   ///< slow random variation of the cruise speed (fraction)
  double max_accel = 0.6;          ///< m/s^2
  double max_decel = 0.9;          ///< m/s^2
  double max_lateral_accel = 1.0;  ///< m/s^2, slows the platform in corners
  double corner_radius = 7.0;      ///< m, corner fillet radius (shrunk on short segments)
  double lateral_offset = 1.0;     ///< m to the right of the path centre line (keep right)
  double body_height = 1.0;        ///< m above the ground
  double axle_half_length = 1.0;   ///< m, terrain pitch is taken between front and rear contact points
  double track_half_width = 0.6;   ///< m, terrain roll between left and right contact points
  double bob_amplitude = 0.0;      ///< m, vertical gait oscillation (handheld)
  double bob_frequency = 1.8;      ///< Hz (steps)
  double sway_deg = 0.0;           ///< deg, roll/pitch/yaw sway of a hand-held sensor
  double start_still = 2.0;        ///< s at rest before moving
  double end_still = 1.0;          ///< s at rest after stopping
  double rate_hz = 200.0;          ///< reference trajectory rate (>= 100 Hz)

  /// Presets: "handheld", "atv", "car".
  static MotionParams preset(const std::string& platform);
  /// Overrides of the preset named by `platform`.
  static MotionParams fromConfig(const ConfigNode& node, const std::string& platform);
  std::string describe() const;
};

/// Trajectory along the polyline `waypoints`, starting at `start` (ns).
Trajectory makeTrajectory(const std::vector<Eigen::Vector2d>& waypoints, const Terrain& terrain,
                          const MotionParams& params, StampNs start, std::mt19937_64& rng);

}  // namespace cosmo::sim
