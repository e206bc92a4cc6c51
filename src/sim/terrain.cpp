#include "cosmo/sim/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cosmo/sim/material.hpp"

namespace cosmo::sim {

Terrain::Terrain(const Eigen::Vector2d& origin, double cell, int nx, int ny, double material_cell)
    : origin_(origin), cell_(cell), nx_(std::max(1, nx)), ny_(std::max(1, ny)) {
  h_.assign(static_cast<std::size_t>(nx_ + 1) * (ny_ + 1), 0.0);
  mat_cell_ = material_cell > 0 ? material_cell : cell;
  mx_ = static_cast<int>(std::ceil(nx_ * cell_ / mat_cell_));
  my_ = static_cast<int>(std::ceil(ny_ * cell_ / mat_cell_));
  materials_.assign(static_cast<std::size_t>(mx_) * my_, kGrass);
  finalize();
}

Terrain Terrain::generate(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const TerrainParams& params,
                          std::mt19937_64& rng) {
  const double cell = params.cell > 0 ? params.cell : 2.0;
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell));
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell));
  Terrain t(lo, cell, nx, ny, params.material_cell);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  struct Wave {
    double kx, ky, phase, amp;
  };
  std::vector<Wave> waves;
  const int n = std::max(0, params.waves);
  for (int k = 0; k < n; ++k) {
    const double dir = 2.0 * M_PI * u01(rng);
    const double lambda = params.wavelength * (0.6 + 0.8 * u01(rng));
    const double kk = 2.0 * M_PI / std::max(lambda, 1.0);
    waves.push_back({kk * std::cos(dir), kk * std::sin(dir), 2.0 * M_PI * u01(rng),
                     params.amplitude / std::sqrt(static_cast<double>(n))});
  }
  for (int j = 0; j <= t.ny_; ++j)
    for (int i = 0; i <= t.nx_; ++i) {
      const double x = lo.x() + i * cell, y = lo.y() + j * cell;
      double h = 0.0;
      for (const auto& w : waves) h += w.amp * std::sin(w.kx * x + w.ky * y + w.phase);
      t.h_[static_cast<std::size_t>(j) * (t.nx_ + 1) + i] = h;
    }
  t.finalize();
  return t;
}

void Terrain::finalize() {
  cell_lo_.assign(static_cast<std::size_t>(nx_) * ny_, 0.f);
  cell_hi_.assign(static_cast<std::size_t>(nx_) * ny_, 0.f);
  h_min_ = std::numeric_limits<double>::infinity();
  h_max_ = -h_min_;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const double a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1), d = vertex(i + 1, j + 1);
      const double lo = std::min({a, b, c, d}), hi = std::max({a, b, c, d});
      cell_lo_[static_cast<std::size_t>(j) * nx_ + i] = static_cast<float>(lo);
      cell_hi_[static_cast<std::size_t>(j) * nx_ + i] = static_cast<float>(hi);
      h_min_ = std::min(h_min_, lo);
      h_max_ = std::max(h_max_, hi);
    }
  tx_ = (nx_ + kTile - 1) / kTile;
  ty_ = (ny_ + kTile - 1) / kTile;
  tile_lo_.assign(static_cast<std::size_t>(tx_) * ty_, std::numeric_limits<float>::infinity());
  tile_hi_.assign(static_cast<std::size_t>(tx_) * ty_, -std::numeric_limits<float>::infinity());
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      const std::size_t t = static_cast<std::size_t>(j / kTile) * tx_ + i / kTile;
      tile_lo_[t] = std::min(tile_lo_[t], cell_lo_[c]);
      tile_hi_[t] = std::max(tile_hi_[t], cell_hi_[c]);
    }
}

namespace {
/// 2-D grid walk (Amanatides & Woo) over cells of size `cell` from `origin`, starting at ray parameter t0.
struct GridWalk {
  int i, j, step_i, step_j;
  double next_i, next_j, dt_i, dt_j;
  GridWalk(const Ray& ray, double t0, const Eigen::Vector2d& origin, double cell, int i_lo, int i_hi, int j_lo,
           int j_hi) {
    const double inf = std::numeric_limits<double>::infinity();
    const double px = ray.o.x() + t0 * ray.d.x(), py = ray.o.y() + t0 * ray.d.y();
    i = std::clamp(static_cast<int>(std::floor((px - origin.x()) / cell)), i_lo, i_hi);
    j = std::clamp(static_cast<int>(std::floor((py - origin.y()) / cell)), j_lo, j_hi);
    step_i = ray.d.x() >= 0 ? 1 : -1;
    step_j = ray.d.y() >= 0 ? 1 : -1;
    dt_i = std::abs(ray.d.x()) > 1e-15 ? cell / std::abs(ray.d.x()) : inf;
    dt_j = std::abs(ray.d.y()) > 1e-15 ? cell / std::abs(ray.d.y()) : inf;
    next_i = dt_i == inf ? inf : (origin.x() + (i + (step_i > 0 ? 1 : 0)) * cell - ray.o.x()) * ray.inv_d.x();
    next_j = dt_j == inf ? inf : (origin.y() + (j + (step_j > 0 ? 1 : 0)) * cell - ray.o.y()) * ray.inv_d.y();
  }
  double exit() const { return std::min(next_i, next_j); }
  /// Steps to the next cell; returns the entry parameter of that cell.
  double advance() {
    if (next_i < next_j) {
      i += step_i;
      const double t = next_i;
      next_i += dt_i;
      return t;
    }
    j += step_j;
    const double t = next_j;
    next_j += dt_j;
    return t;
  }
};
}  // namespace

namespace {
// Plane z = c0 + cu * u + cv * v of one of the two triangles of a cell (u, v in [0, 1]).
struct TrianglePlane {
  double c0, cu, cv;
};
inline TrianglePlane lowerPlane(double h00, double h10, double h01) { return {h00, h10 - h00, h01 - h00}; }
inline TrianglePlane upperPlane(double h10, double h01, double h11) { return {h01 + h10 - h11, h11 - h01, h11 - h10}; }
/// The triangle of a cell with vertex heights h00, h10, h01, h11 that holds the cell position (u, v).
inline TrianglePlane planeAt(double h00, double h10, double h01, double h11, double u, double v) {
  return u + v <= 1.0 ? lowerPlane(h00, h10, h01) : upperPlane(h10, h01, h11);
}
}  // namespace

void Terrain::locate(double x, double y, int& i, int& j, double& u, double& v) const {
  u = std::clamp((x - origin_.x()) / cell_, 0.0, static_cast<double>(nx_) - 1e-9);
  v = std::clamp((y - origin_.y()) / cell_, 0.0, static_cast<double>(ny_) - 1e-9);
  i = static_cast<int>(u);
  j = static_cast<int>(v);
  u -= i;
  v -= j;
}

double Terrain::height(double x, double y) const {
  int i = 0, j = 0;
  double u = 0.0, v = 0.0;
  locate(x, y, i, j, u, v);
  const TrianglePlane p = planeAt(vertex(i, j), vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1), u, v);
  return p.c0 + p.cu * u + p.cv * v;
}

Eigen::Vector3d Terrain::normal(double x, double y) const {
  int i = 0, j = 0;
  double u = 0.0, v = 0.0;
  locate(x, y, i, j, u, v);
  const TrianglePlane p = planeAt(vertex(i, j), vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1), u, v);
  return Eigen::Vector3d(-p.cu / cell_, -p.cv / cell_, 1.0).normalized();
}

double Terrain::minHeightAround(double x, double y, double radius) const {
  double m = height(x, y);
  const int n = 8;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    m = std::min(m, height(x + radius * std::cos(a), y + radius * std::sin(a)));
  }
  return m;
}

bool Terrain::intersectCell(int i, int j, const Ray& ray, double ta, double tb, double& t_out,
                            Eigen::Vector3d& n_out) const {
  const double x0 = origin_.x() + i * cell_, y0 = origin_.y() + j * cell_;
  const double inv_cell = 1.0 / cell_;
  const double u0 = (ray.o.x() - x0) * inv_cell, v0 = (ray.o.y() - y0) * inv_cell;
  const double du = ray.d.x() * inv_cell, dv = ray.d.y() * inv_cell;
  const double h00 = vertex(i, j), h10 = vertex(i + 1, j), h01 = vertex(i, j + 1), h11 = vertex(i + 1, j + 1);
  const double eps = 1e-9;
  double best = std::numeric_limits<double>::infinity();
  for (int tri = 0; tri < 2; ++tri) {
    const TrianglePlane p = tri == 0 ? lowerPlane(h00, h10, h01) : upperPlane(h10, h01, h11);
    const double denom = ray.d.z() - p.cu * du - p.cv * dv;
    if (std::abs(denom) < 1e-15) continue;
    const double t = (p.c0 + p.cu * u0 + p.cv * v0 - ray.o.z()) / denom;
    if (t < ta - 1e-9 || t > tb + 1e-9 || t >= best) continue;
    const double s = (u0 + t * du) + (v0 + t * dv);
    if (tri == 0 ? s > 1.0 + eps : s < 1.0 - eps) continue;
    best = t;
    n_out = Eigen::Vector3d(-p.cu * inv_cell, -p.cv * inv_cell, 1.0).normalized();
  }
  if (!std::isfinite(best)) return false;
  t_out = best;
  return true;
}

bool Terrain::intersect(const Ray& ray, double t_min, Hit& hit) const {
  if (nx_ == 0) return false;
  // Clip the ray to the grid's xy rectangle and [t_min, hit.t].
  double t0 = t_min, t1 = hit.t;
  const Eigen::Vector2d lo = this->lo(), hi = this->hi();
  for (int a = 0; a < 2; ++a) {
    if (std::abs(ray.d[a]) < 1e-15) {
      if (ray.o[a] < lo[a] || ray.o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - ray.o[a]) * ray.inv_d[a], tb = (hi[a] - ray.o[a]) * ray.inv_d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 >= t1) return false;
  // Two-level walk: tiles of kTile x kTile cells are skipped when the ray passes above or below them.
  const double tile = cell_ * kTile;
  GridWalk tw(ray, t0, origin_, tile, 0, tx_ - 1, 0, ty_ - 1);
  double ta = t0;
  while (ta < t1) {
    const double tb = std::min(tw.exit(), t1);
    const double za = ray.o.z() + ta * ray.d.z(), zb = ray.o.z() + tb * ray.d.z();
    if (ray.d.z() >= 0.0 && za > h_max_) return false;  // climbing above all ground
    const std::size_t tc = static_cast<std::size_t>(tw.j) * tx_ + tw.i;
    if (std::min(za, zb) <= tile_hi_[tc] + 1e-6 && std::max(za, zb) >= tile_lo_[tc] - 1e-6) {
      const int i0 = tw.i * kTile, j0 = tw.j * kTile;
      GridWalk cw(ray, ta, origin_, cell_, i0, std::min(i0 + kTile, nx_) - 1, j0, std::min(j0 + kTile, ny_) - 1);
      double ca = ta;
      while (ca < tb) {
        const double cb = std::min(cw.exit(), tb);
        const double ya = ray.o.z() + ca * ray.d.z(), yb = ray.o.z() + cb * ray.d.z();
        const std::size_t c = static_cast<std::size_t>(cw.j) * nx_ + cw.i;
        if (std::min(ya, yb) <= cell_hi_[c] + 1e-6 && std::max(ya, yb) >= cell_lo_[c] - 1e-6) {
          double t;
          Eigen::Vector3d n;
          if (intersectCell(cw.i, cw.j, ray, ca, cb, t, n) && t > t_min && t < hit.t) {
            hit.t = t;
            hit.exit = t;
            hit.normal = n;
            hit.material = materialAt(ray.o.x() + t * ray.d.x(), ray.o.y() + t * ray.d.y());
            return true;
          }
        }
        ca = cw.advance();
        if (cw.i < i0 || cw.i >= std::min(i0 + kTile, nx_) || cw.j < j0 || cw.j >= std::min(j0 + kTile, ny_)) break;
      }
    }
    ta = tw.advance();
    if (tw.i < 0 || tw.i >= tx_ || tw.j < 0 || tw.j >= ty_) return false;
  }
  return false;
}

std::uint8_t Terrain::materialAt(double x, double y) const {
  const int i = static_cast<int>(std::floor((x - origin_.x()) / mat_cell_));
  const int j = static_cast<int>(std::floor((y - origin_.y()) / mat_cell_));
  if (i < 0 || j < 0 || i >= mx_ || j >= my_) return kGrass;
  return materials_[static_cast<std::size_t>(j) * mx_ + i];
}

void Terrain::setMaterial(double x, double y, std::uint8_t material) {
  const int i = static_cast<int>(std::floor((x - origin_.x()) / mat_cell_));
  const int j = static_cast<int>(std::floor((y - origin_.y()) / mat_cell_));
  if (i < 0 || j < 0 || i >= mx_ || j >= my_) return;
  materials_[static_cast<std::size_t>(j) * mx_ + i] = material;
}

void Terrain::paintSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double half_width,
                           std::uint8_t material) {
  const Eigen::Vector2d lo = a.cwiseMin(b).array() - half_width, hi = a.cwiseMax(b).array() + half_width;
  const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - origin_.x()) / mat_cell_)));
  const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - origin_.y()) / mat_cell_)));
  const int i1 = std::min(mx_ - 1, static_cast<int>(std::floor((hi.x() - origin_.x()) / mat_cell_)));
  const int j1 = std::min(my_ - 1, static_cast<int>(std::floor((hi.y() - origin_.y()) / mat_cell_)));
  const Eigen::Vector2d ab = b - a;
  const double len2 = std::max(ab.squaredNorm(), 1e-12);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Eigen::Vector2d p = origin_ + Eigen::Vector2d(i + 0.5, j + 0.5) * mat_cell_;
      const double s = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
      if ((a + s * ab - p).norm() <= half_width) materials_[static_cast<std::size_t>(j) * mx_ + i] = material;
    }
}

}  // namespace cosmo::sim
