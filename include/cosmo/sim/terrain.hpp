#pragma once
// Ground of the synthetic world: a regular heightfield (two triangles per cell) with a material raster
// (grass, asphalt, paving). Ray casting walks the cells the ray crosses (2-D DDA) and tests the two triangle
// planes of cells whose height range the ray's height range overlaps.
#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "cosmo/sim/primitives.hpp"

namespace cosmo::sim {

struct TerrainParams {
  double cell = 4.0;           ///< heightfield cell size (m)
  double amplitude = 2.0;      ///< height amplitude of the undulations (m); 0 gives a flat plane
  double wavelength = 220.0;   ///< dominant wavelength (m); slopes ~ 2*pi*amplitude/wavelength
  int waves = 4;               ///< number of superposed sine waves
  double material_cell = 0.5;  ///< resolution of the material raster (m)
};

class Terrain {
 public:
  Terrain() = default;
  /// Flat-initialised grid of nx x ny cells starting at `origin` (lower-left corner).
  Terrain(const Eigen::Vector2d& origin, double cell, int nx, int ny, double material_cell);
  /// Random gentle undulations (seeded) over the grid of `lo`..`hi`.
  static Terrain generate(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const TerrainParams& params,
                          std::mt19937_64& rng);

  /// Height of the triangulated surface (clamped to the grid outside it).
  double height(double x, double y) const;
  /// Upward unit normal of the triangle under (x, y).
  Eigen::Vector3d normal(double x, double y) const;
  /// Nearest hit with t in (t_min, hit.t).
  bool intersect(const Ray& ray, double t_min, Hit& hit) const;

  std::uint8_t materialAt(double x, double y) const;
  void setMaterial(double x, double y, std::uint8_t material);
  /// Paint every material cell whose centre lies within `half_width` of the segment a-b.
  void paintSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double half_width, std::uint8_t material);

  Eigen::Vector2d lo() const { return origin_; }
  Eigen::Vector2d hi() const { return origin_ + cell_ * Eigen::Vector2d(nx_, ny_); }
  double minHeight() const { return h_min_; }
  double maxHeight() const { return h_max_; }
  /// Minimum / maximum height over a disc (sampled), to seat objects on the ground.
  double minHeightAround(double x, double y, double radius) const;

 private:
  double vertex(int i, int j) const { return h_[static_cast<std::size_t>(j) * (nx_ + 1) + i]; }
  /// The cell (i, j) under (x, y), clamped to the grid, and the point's position (u, v) in it (in [0, 1]).
  void locate(double x, double y, int& i, int& j, double& u, double& v) const;
  void finalize();  ///< per-cell height ranges
  bool intersectCell(int i, int j, const Ray& ray, double ta, double tb, double& t, Eigen::Vector3d& n) const;

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<double> h_;                 ///< (nx+1) x (ny+1) vertex heights
  std::vector<float> cell_lo_, cell_hi_;  ///< nx x ny
  static constexpr int kTile = 16;        ///< cells per tile side (coarse level of the two-level walk)
  int tx_ = 0, ty_ = 0;
  std::vector<float> tile_lo_, tile_hi_;  ///< tx x ty
  double h_min_ = 0.0, h_max_ = 0.0;
  double mat_cell_ = 1.0;
  int mx_ = 0, my_ = 0;
  std::vector<std::uint8_t> materials_;  ///< mx x my
};

}  // namespace cosmo::sim
