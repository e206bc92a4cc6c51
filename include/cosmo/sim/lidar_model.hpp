#pragma once
// A spinning multi-beam LiDAR (Ouster OS1-like): beams fire column by column while the head turns; each
// column has one time stamp. Beam 0 (ring 0) is the top beam, as on Ouster sensors.
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"

namespace cosmo::sim {

struct LidarModel {
  std::string name = "os1_64";
  int beams = 64;                     ///< scan lines (rings)
  int columns = 1024;                 ///< firings per revolution
  double rate_hz = 10.0;              ///< revolutions per second
  double fov_up_deg = 16.6;           ///< elevation of the top beam
  double fov_down_deg = -16.6;        ///< elevation of the bottom beam
  double min_range = 0.3;             ///< m, closer returns are dropped
  double max_range = 120.0;           ///< m
  double range_sigma = 0.02;          ///< Gaussian range noise at zero range, m
  double range_sigma_per_m = 0.0;     ///< growth of the range noise with range (sigma = range_sigma + this * range)
  double beam_angle_sigma_deg = 0.0;  ///< intrinsic calibration error of each beam (elevation and azimuth
                                      ///< offsets, N(0, this), fixed per sensor = per noise seed): rays leave along
                                      ///< the true beam, points are reported along the nominal one, so the error
                                      ///< of a point grows with its range, as on a real sensor
  double grazing_cos = 0.06;          ///< no return below this cosine of the incidence angle (~86.5 deg)
  double detection_range = 90.0;      ///< range at which a surface of reflectivity 0.1 at normal incidence is
                                      ///< detected with probability 0.5; scales with sqrt(reflectivity * cos)
  double dropout = 0.002;             ///< random loss of any return
  double intensity_scale = 1000.0;    ///< intensity = scale * reflectivity * cos(incidence) (clamped)
  double foliage_spread = 1.0;        ///< scale of the extra range spread of porous materials (0: solid surfaces)
  // Sensor physics that make two scans of one place from different viewpoints disagree by centimetres (each 0:
  // off, the ideal sensor above):
  double beam_divergence_mrad = 0.0;  ///< full angle of the beam: each return comes from a random point of the
                                      ///< beam's footprint (r * divergence wide) but is reported along the beam's
                                      ///< axis, so edges bleed into the background and oblique surfaces spread in range
  double range_walk = 0.0;            ///< m, range bias of the weakest detectable return (a weak pulse crosses the
                                      ///< detection threshold late); falls linearly with log10 of the return's strength
                                      ///< to 0 at 1000x that; the strength falls with range^2, darkness and incidence
  double foliage_mean_free_path = 0.0;  ///< m: canopies are a volume of leaves, not a surface: a ray entering one
                                        ///< scatters after an exponential depth of this mean, or leaves it through a
                                        ///< gap and goes on (replaces foliage_spread)
  bool material_losses = true;          ///< the materials' own lost returns (their return_prob); false: every
                                        ///< surface returns each ray that reaches it (an ideal sensor for tests)
  bool clockwise = true;                ///< Ouster heads spin clockwise seen from above (azimuth decreases)

  static LidarModel os1_64();
  static LidarModel os1_128();  ///< 128 x 1024, +-22.5 deg (MCD NTU)
  static LidarModel os1_32();   ///< 32 x 1024, +-22.5 deg
  /// One of the names above; throws naming the name otherwise.
  static LidarModel byName(const std::string& name);
  /// `model:` picks the preset, every other key overrides one field.
  static LidarModel fromConfig(const ConfigNode& node);
  std::string describe() const;

  double period() const { return 1.0 / rate_hz; }
  std::size_t raysPerScan() const { return static_cast<std::size_t>(beams) * columns; }
  /// Beam elevations, radians, top (ring 0) first, evenly spaced.
  std::vector<double> elevations() const;
  /// Azimuth of column c, radians (column 0 faces the sensor's -x axis like Ouster's measurement id 0).
  double azimuth(int column) const;
  /// Time of column c relative to the scan stamp (the end of the sweep): the last column is at 0.
  double columnTime(int column) const { return -static_cast<double>(columns - 1 - column) / (columns * rate_hz); }
};

}  // namespace cosmo::sim
