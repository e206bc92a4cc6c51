#include "cosmo/sim/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cosmo::sim {

Primitive Primitive::box(const Eigen::Vector3d& center, const Eigen::Vector3d& half, double yaw,
                         std::uint8_t material) {
  Primitive p;
  p.kind = Kind::Box;
  p.center = center;
  p.half = half;
  p.cos_yaw = std::cos(yaw);
  p.sin_yaw = std::sin(yaw);
  p.material = material;
  return p;
}

Primitive Primitive::cylinder(double x, double y, double z0, double z1, double radius, std::uint8_t material) {
  Primitive p;
  p.kind = Kind::Cylinder;
  p.center = {x, y, 0.5 * (z0 + z1)};
  p.half = {radius, radius, 0.5 * std::abs(z1 - z0)};
  p.material = material;
  return p;
}

Primitive Primitive::ellipsoid(const Eigen::Vector3d& center, const Eigen::Vector3d& radii, std::uint8_t material) {
  Primitive p;
  p.kind = Kind::Ellipsoid;
  p.center = center;
  p.half = radii;
  p.material = material;
  return p;
}

Aabb Primitive::bounds() const {
  Aabb b;
  Eigen::Vector3d e = half;
  if (kind == Kind::Box) {
    const double c = std::abs(cos_yaw), s = std::abs(sin_yaw);
    e = {c * half.x() + s * half.y(), s * half.x() + c * half.y(), half.z()};
  }
  b.lo = center - e;
  b.hi = center + e;
  return b;
}

namespace {
// World <-> box frame (rotation about z).
inline Eigen::Vector3d toLocal(const Primitive& p, const Eigen::Vector3d& v) {
  return {p.cos_yaw * v.x() + p.sin_yaw * v.y(), -p.sin_yaw * v.x() + p.cos_yaw * v.y(), v.z()};
}
inline Eigen::Vector3d toWorld(const Primitive& p, const Eigen::Vector3d& v) {
  return {p.cos_yaw * v.x() - p.sin_yaw * v.y(), p.sin_yaw * v.x() + p.cos_yaw * v.y(), v.z()};
}

bool intersectBox(const Primitive& p, const Ray& r, double t_min, Hit& hit) {
  const Eigen::Vector3d o = toLocal(p, r.o - p.center);
  const Eigen::Vector3d d = toLocal(p, r.d);
  double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
  int axis = -1;
  double sign = 1.0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (o[a] < -p.half[a] || o[a] > p.half[a]) return false;
      continue;
    }
    const double inv = 1.0 / d[a];
    double ta = (-p.half[a] - o[a]) * inv, tb = (p.half[a] - o[a]) * inv;
    double s = -1.0;  // entering through the -a face
    if (ta > tb) {
      std::swap(ta, tb);
      s = 1.0;
    }
    if (ta > t0) {
      t0 = ta;
      axis = a;
      sign = s;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0 || t0 <= t_min || t0 >= hit.t) return false;  // origin inside or too far
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axis] = sign;
  hit.t = t0;
  hit.exit = t1;
  hit.normal = toWorld(p, n);
  hit.material = p.material;
  return true;
}

bool intersectCylinder(const Primitive& p, const Ray& r, double t_min, Hit& hit) {
  const Eigen::Vector3d o = r.o - p.center;
  const Eigen::Vector3d& d = r.d;
  const double rad = p.half.x(), hz = p.half.z();
  double best = hit.t;
  Eigen::Vector3d n;
  bool found = false;
  // Side: (ox + t dx)^2 + (oy + t dy)^2 = rad^2.
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a > 1e-18) {
    const double b = o.x() * d.x() + o.y() * d.y();
    const double c = o.x() * o.x() + o.y() * o.y() - rad * rad;
    const double disc = b * b - a * c;
    if (disc >= 0.0) {
      const double t = (-b - std::sqrt(disc)) / a;
      if (t > t_min && t < best) {
        const double z = o.z() + t * d.z();
        if (z >= -hz && z <= hz) {
          best = t;
          n = Eigen::Vector3d(o.x() + t * d.x(), o.y() + t * d.y(), 0.0) / rad;
          found = true;
        }
      }
    }
  }
  // Caps.
  if (std::abs(d.z()) > 1e-15) {
    for (double zc : {hz, -hz}) {
      const double t = (zc - o.z()) / d.z();
      if (t <= t_min || t >= best) continue;
      const double x = o.x() + t * d.x(), y = o.y() + t * d.y();
      if (x * x + y * y <= rad * rad) {
        best = t;
        n = Eigen::Vector3d(0, 0, zc > 0 ? 1.0 : -1.0);
        found = true;
      }
    }
  }
  if (!found) return false;
  hit.t = best;
  hit.exit = best;
  hit.normal = n;
  hit.material = p.material;
  return true;
}

bool intersectEllipsoid(const Primitive& p, const Ray& r, double t_min, Hit& hit) {
  const Eigen::Vector3d o = (r.o - p.center).cwiseQuotient(p.half);
  const Eigen::Vector3d d = r.d.cwiseQuotient(p.half);
  const double a = d.squaredNorm();
  const double b = o.dot(d);
  const double c = o.squaredNorm() - 1.0;
  const double disc = b * b - a * c;
  if (disc < 0.0 || c < 0.0) return false;  // miss, or origin inside
  const double t = (-b - std::sqrt(disc)) / a;
  if (t <= t_min || t >= hit.t) return false;
  const Eigen::Vector3d q = o + t * d;  // on the unit sphere
  hit.t = t;
  hit.exit = (-b + std::sqrt(disc)) / a;
  hit.normal = q.cwiseQuotient(p.half).normalized();
  hit.material = p.material;
  return true;
}
}  // namespace

bool Primitive::intersect(const Ray& r, double t_min, Hit& hit) const {
  switch (kind) {
    case Kind::Box: return intersectBox(*this, r, t_min, hit);
    case Kind::Cylinder: return intersectCylinder(*this, r, t_min, hit);
    case Kind::Ellipsoid: return intersectEllipsoid(*this, r, t_min, hit);
  }
  return false;
}

double Primitive::surfaceDistance(const Eigen::Vector3d& p) const {
  switch (kind) {
    case Kind::Box: {
      const Eigen::Vector3d q = toLocal(*this, p - center).cwiseAbs() - half;
      const double outside = q.cwiseMax(0.0).norm();
      const double inside = std::min(q.maxCoeff(), 0.0);
      return std::abs(outside + inside);
    }
    case Kind::Cylinder: {
      const Eigen::Vector3d v = p - center;
      const double dr = std::hypot(v.x(), v.y()) - half.x();
      const double dz = std::abs(v.z()) - half.z();
      const double outside = std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
      return std::abs(outside + std::min(std::max(dr, dz), 0.0));
    }
    case Kind::Ellipsoid: {
      // First-order distance |f| / |grad f| with f = |q|^2 - 1 in scaled coordinates.
      const Eigen::Vector3d q = (p - center).cwiseQuotient(half);
      const double f = q.squaredNorm() - 1.0;
      const Eigen::Vector3d g = 2.0 * q.cwiseQuotient(half);
      return std::abs(f) / std::max(g.norm(), 1e-12);
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace cosmo::sim
