#pragma once
// Analytic solid primitives of the synthetic world and their ray intersections: boxes (rotated about z),
// vertical cylinders and axis-aligned ellipsoids. Each carries a material index (see material.hpp).
#include <Eigen/Core>
#include <cstdint>
#include <utility>

namespace cosmo::sim {

/// A ray o + t d, d of unit length; inv_d caches 1/d for slab tests.
struct Ray {
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  Eigen::Vector3d d = Eigen::Vector3d::UnitX();
  Eigen::Vector3d inv_d = Eigen::Vector3d::Ones();
  Ray() = default;
  Ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_dir)
      : o(origin), d(unit_dir), inv_d(1.0 / unit_dir.x(), 1.0 / unit_dir.y(), 1.0 / unit_dir.z()) {}
};

/// Axis-aligned bounding box.
struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1e300);
  void extend(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  Eigen::Vector3d center() const { return 0.5 * (lo + hi); }
  double area() const {
    const Eigen::Vector3d e = (hi - lo).cwiseMax(0.0);
    return 2.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
  }
  /// Slab test: true (and the entry distance) when the ray meets the box within [0, t_max].
  inline bool hit(const Ray& r, double t_max, double& t_enter) const {
    double t0 = 0.0, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      double ta = (lo[a] - r.o[a]) * r.inv_d[a];
      double tb = (hi[a] - r.o[a]) * r.inv_d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = ta > t0 ? ta : t0;  // NaN-safe for 0 * inf
      t1 = tb < t1 ? tb : t1;
      if (t0 > t1) return false;
    }
    t_enter = t0;
    return true;
  }
};

/// Nearest intersection: distance along the ray, outward unit normal, material.
struct Hit {
  double t = 0.0;
  double exit = 0.0;  ///< where the ray leaves the primitive it entered at t (boxes, ellipsoids; cylinders, terrain: t)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::uint8_t material = 0;
};

struct Primitive {
  enum class Kind : std::uint8_t { Box, Cylinder, Ellipsoid };
  Kind kind = Kind::Box;
  std::uint8_t material = 0;
  /// Box: centre; cylinder: axis midpoint; ellipsoid: centre.
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  /// Box: half extents in its own frame; cylinder: (radius, radius, half height); ellipsoid: semi-axes.
  Eigen::Vector3d half = Eigen::Vector3d::Ones();
  /// Box rotation about z (cos, sin of the yaw).
  double cos_yaw = 1.0, sin_yaw = 0.0;

  static Primitive box(const Eigen::Vector3d& center, const Eigen::Vector3d& half, double yaw, std::uint8_t material);
  /// Vertical cylinder from z0 to z1.
  static Primitive cylinder(double x, double y, double z0, double z1, double radius, std::uint8_t material);
  static Primitive ellipsoid(const Eigen::Vector3d& center, const Eigen::Vector3d& radii, std::uint8_t material);

  Aabb bounds() const;
  /// Nearest intersection with t in (t_min, hit.t); updates `hit` and returns true when closer.
  bool intersect(const Ray& r, double t_min, Hit& hit) const;
  /// Distance from a point to the primitive's surface (exact for boxes and cylinders, approximate for
  /// ellipsoids); used by tests and diagnostics.
  double surfaceDistance(const Eigen::Vector3d& p) const;
};

}  // namespace cosmo::sim
