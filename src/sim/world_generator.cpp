#include "cosmo/sim/world_generator.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "cosmo/sim/material.hpp"
#include "cosmo/sim/scan_simulator.hpp"

namespace cosmo::sim {

#define COSMO_SIM_WORLD_FIELDS(X)                                                                                   \
  X(blocks_x)                                                                                                       \
  X(blocks_y)                                                                                                       \
  X(block_min) X(block_max) X(street_half_width) X(sidewalk_width) X(footpath_half_width) X(footpath_fraction)      \
      X(diagonal_fraction) X(building_height_min) X(building_height_max) X(p_buildings) X(p_row) X(p_park)          \
          X(p_parking) X(tree_row_fraction) X(tree_spacing) X(pole_spacing) X(parked_car_fraction) X(wall_fraction) \
              X(outer_ring) X(terrain_margin)
#define COSMO_SIM_CHANGE_FIELDS(X) X(car_change) X(people_per_100m) X(foliage_change)
#define COSMO_SIM_LOOKALIKE_FIELDS(X) X(terrace_fraction) X(p_open)
#define COSMO_SIM_TERRAIN_FIELDS(X) X(cell) X(amplitude) X(wavelength) X(waves) X(material_cell)

namespace {

/// A key the world's lists do not name is a typo, not a silently kept default.
void rejectUnknownWorldKeys(const ConfigNode& node) {
  std::vector<std::string> world{"terrain", "hedge_fraction"}, terrain;
#define X(f) world.emplace_back(#f);
  COSMO_SIM_WORLD_FIELDS(X)
  COSMO_SIM_CHANGE_FIELDS(X)
  COSMO_SIM_LOOKALIKE_FIELDS(X)
#undef X
#define X(f) terrain.emplace_back(#f);
  COSMO_SIM_TERRAIN_FIELDS(X)
#undef X
  node.rejectUnknownKeys(world);
  if (node.has("terrain")) node["terrain"].rejectUnknownKeys(terrain);
}

}  // namespace

WorldParams WorldParams::fromConfig(const ConfigNode& node) {
  WorldParams p;
#define X(f) node.read(#f, p.f);
  COSMO_SIM_WORLD_FIELDS(X)
#undef X
  const ConfigNode t = node["terrain"];
#define X(f) t.read(#f, p.terrain.f);
  COSMO_SIM_TERRAIN_FIELDS(X)
#undef X
#define X(f) node.read(#f, p.f);
  COSMO_SIM_CHANGE_FIELDS(X)
  COSMO_SIM_LOOKALIKE_FIELDS(X)
#undef X
  node.read("hedge_fraction", p.hedge_fraction);
  if (p.hedge_fraction < 0.0 || p.hedge_fraction > 1.0)
    throw std::runtime_error(node.where + ".hedge_fraction: must be in [0, 1]");
  rejectUnknownWorldKeys(node);
  return p;
}

std::string WorldParams::describe() const {
  std::ostringstream os;
  os << std::setprecision(17);
#define X(f) os << #f << '=' << f << ';';
  COSMO_SIM_WORLD_FIELDS(X)
#undef X
#define X(f) os << "terrain." #f << '=' << terrain.f << ';';
  COSMO_SIM_TERRAIN_FIELDS(X)
#undef X
  if (changesPerTrial(*this)) {  // only when used: the cache keys of worlds without changes stay valid
#define X(f) os << #f << '=' << f << ';';
    COSMO_SIM_CHANGE_FIELDS(X)
#undef X
  }
  if (terrace_fraction > 0.0 || p_open > 0.0) {  // likewise: worlds without them keep their cache keys
#define X(f) os << #f << '=' << f << ';';
    COSMO_SIM_LOOKALIKE_FIELDS(X)
#undef X
  }
  if (hedge_fraction > 0.0) os << "hedge_fraction=" << hedge_fraction << ';';
  return os.str();
}

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

struct Rect {
  Vector2d lo, hi;
  Vector2d size() const { return hi - lo; }
  Vector2d center() const { return 0.5 * (lo + hi); }
};

struct TreeShape {
  double trunk_radius, trunk_height, canopy_rx, canopy_rz;
};

struct RowTemplate {
  double width, depth, height, gap;
};

/// The house every terrace of the world repeats: main body, a porch / bay on its street side, gap to the next.
struct TerraceTemplate {
  double width, depth, height, gap, porch_width, porch_depth, porch_height;
  double pitch() const { return width + gap; }
};

/// Sides of a block rectangle, each facing the street along it.
enum Side { kSouth = 1, kNorth = 2, kWest = 4, kEast = 8, kAllSides = 15 };

/// Box with its bottom buried below the local ground and z0..z1 measured from the ground at its centre
/// (z0 <= 0: down into the ground).
void addBox(const Terrain& terrain, std::vector<Primitive>& prims, const Vector2d& c, double lx, double ly, double z0,
            double z1, double yaw, std::uint8_t mat) {
  const double g = terrain.height(c.x(), c.y());
  const double bottom = z0 <= 0.0 ? terrain.minHeightAround(c.x(), c.y(), 0.5 * std::hypot(lx, ly)) - 0.3 : g + z0;
  const double top = g + z1;
  if (top <= bottom) return;
  prims.push_back(
      Primitive::box({c.x(), c.y(), 0.5 * (bottom + top)}, {0.5 * lx, 0.5 * ly, 0.5 * (top - bottom)}, yaw, mat));
}

void addCar(const Terrain& terrain, std::vector<Primitive>& prims, const ParkedCar& car) {
  const Vector2d c(car.x, car.y);
  addBox(terrain, prims, c, car.length, car.width, 0.25, car.body_top, car.yaw, kCarPaint);
  const Vector2d cab = c - 0.1 * car.length * Vector2d(std::cos(car.yaw), std::sin(car.yaw));
  addBox(terrain, prims, cab, 0.55 * car.length, car.width - 0.1, 0.9, car.cabin_top, car.yaw, kCarPaint);
}

class Builder {
 public:
  Builder(const WorldParams& p, std::mt19937_64& rng, Terrain& terrain, std::vector<Primitive>& prims,
          std::vector<ParkedCar>& cars, std::vector<Primitive>& canopies)
      : p_(p), rng_(rng), terrain_(terrain), prims_(prims), cars_(cars), canopies_(canopies) {
    row_tree_ = {0.25, 3.0, 2.3, 1.9};
    row_ = {uni(11.0, 15.0), uni(28.0, 36.0), uni(9.0, 15.0), uni(8.0, 12.0)};
    if (p_.terrace_fraction > 0.0)  // drawn only when used: worlds without terraces stay as they were
      terrace_ = {uni(9.0, 12.0), uni(10.0, 13.0), uni(10.0, 15.0), uni(0.8, 1.6),
                  uni(3.0, 4.5),  uni(1.2, 2.0),   uni(2.8, 3.6)};
  }

  double uni(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  bool chance(double prob) { return uni(0.0, 1.0) < prob; }

  void box(const Vector2d& c, double lx, double ly, double z0, double z1, double yaw, std::uint8_t mat) {
    addBox(terrain_, prims_, c, lx, ly, z0, z1, yaw, mat);
  }

  void tree(const Vector2d& c, const TreeShape& s) {
    const double g = terrain_.minHeightAround(c.x(), c.y(), s.trunk_radius);
    prims_.push_back(
        Primitive::cylinder(c.x(), c.y(), g - 0.3, g + s.trunk_height + 0.5 * s.canopy_rz, s.trunk_radius, kBark));
    canopies_.push_back(Primitive::ellipsoid({c.x(), c.y(), g + s.trunk_height + s.canopy_rz * 0.8},
                                             {s.canopy_rx, s.canopy_rx, s.canopy_rz}, kFoliage));
  }

  TreeShape randomTree() {
    const double r = uni(0.15, 0.35);
    return {r, uni(2.2, 4.5), uni(1.5, 3.5), uni(1.3, 3.0)};
  }

  void pole(const Vector2d& c, double height, double arm_yaw) {
    const double g = terrain_.minHeightAround(c.x(), c.y(), 0.1);
    prims_.push_back(Primitive::cylinder(c.x(), c.y(), g - 0.3, g + height, 0.08, kMetal));
    const Vector2d a = c + 0.7 * Vector2d(std::cos(arm_yaw), std::sin(arm_yaw));
    prims_.push_back(Primitive::box({a.x(), a.y(), g + height - 0.1}, {0.75, 0.12, 0.08}, arm_yaw, kMetal));
  }

  void car(const Vector2d& c, double yaw) {
    ParkedCar car;
    car.x = c.x();
    car.y = c.y();
    car.yaw = yaw;
    car.length = uni(4.0, 4.8);
    car.width = uni(1.7, 1.9);
    car.body_top = uni(0.95, 1.1);
    car.cabin_top = uni(1.4, 1.6);
    cars_.push_back(car);
  }

  /// Building of a random kind inside `lot` (axis-aligned lot, building rotated by yaw about the lot centre).
  void building(const Rect& lot, double yaw) {
    const Vector2d sz = lot.size();
    if (sz.minCoeff() < 8.0) return;
    const double h = uni(p_.building_height_min, p_.building_height_max);
    const double lx = sz.x() * uni(0.6, 0.95), ly = sz.y() * uni(0.6, 0.95);
    const Vector2d c = lot.center();
    const std::uint8_t mat = pickFacade();
    const double kind = uni(0.0, 1.0);
    const Eigen::Rotation2Dd R(yaw);
    auto part = [&](double ox, double oy, double px, double py, double ph) {
      box(c + R * Vector2d(ox, oy), px, py, 0.0, ph, yaw, mat);
    };
    if (kind < 0.45 || std::min(lx, ly) < 20.0) {
      part(0, 0, lx, ly, h);
      if (chance(0.4)) part(0.25 * lx, 0, 0.5 * lx, ly + 3.0, std::min(h, 4.5));  // podium / canopy wing
    } else if (kind < 0.8) {                                                      // L-shape: two wings sharing a corner
      const double w = std::min(uni(10.0, 16.0), 0.5 * std::min(lx, ly));
      const double sx = chance(0.5) ? 1 : -1, sy = chance(0.5) ? 1 : -1;
      part(0, sy * 0.5 * (ly - w), lx, w, h);
      part(sx * 0.5 * (lx - w), -sy * 0.5 * w, w, ly - w, h * uni(0.7, 1.0));
    } else {  // courtyard: four wings around an open yard, one gap for a gate
      const double w = std::min(uni(9.0, 13.0), 0.3 * std::min(lx, ly));
      part(0, 0.5 * (ly - w), lx, w, h);
      part(0, -0.5 * (ly - w), lx, w, h);
      const double gate = chance(0.5) ? 5.0 : 0.0;
      part(0.5 * (lx - w), 0.5 * gate, w, ly - 2 * w - gate, h);
      part(-0.5 * (lx - w), 0, w, ly - 2 * w, h);
    }
  }

  std::uint8_t pickFacade() {
    const double u = uni(0.0, 1.0);
    return u < 0.45 ? kConcrete : (u < 0.85 ? kBrick : kGlassFacade);
  }

  void fillBuildings(const Rect& r) {
    const Vector2d sz = r.size();
    const int nx = sz.x() > 55.0 ? 2 : 1, ny = sz.y() > 55.0 ? 2 : 1;
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        Rect lot{r.lo + Vector2d(i * sz.x() / nx, j * sz.y() / ny),
                 r.lo + Vector2d((i + 1) * sz.x() / nx, (j + 1) * sz.y() / ny)};
        lot.lo.array() += 2.0;
        lot.hi.array() -= 2.0;
        if (chance(0.12)) {  // an open lot: a few trees instead
          fillTrees(lot, 0.4);
          continue;
        }
        building(lot, 0.0);
      }
  }

  /// Identical buildings in rows (one template for the whole world): places that look alike.
  void fillRow(const Rect& r) {
    const Vector2d sz = r.size();
    const double pitch = row_.width + row_.gap;
    const int n = std::max(1, static_cast<int>((sz.x() + row_.gap) / pitch));
    const double x0 = r.center().x() - 0.5 * (n * pitch - row_.gap) + 0.5 * row_.width;
    const int rows = sz.y() > 2 * row_.depth + 10.0 ? 2 : 1;
    for (int k = 0; k < rows; ++k) {
      const double y =
          rows == 1 ? r.center().y() : (k == 0 ? r.lo.y() + 0.5 * row_.depth : r.hi.y() - 0.5 * row_.depth);
      for (int i = 0; i < n; ++i)
        box({x0 + i * pitch, y}, row_.width, std::min(row_.depth, sz.y()), 0.0, row_.height, 0.0, kConcrete);
    }
  }

  void fillTrees(const Rect& r, double density_per_100m2,
                 const std::vector<std::pair<Vector2d, Vector2d>>& avoid = {}) {
    const Vector2d sz = r.size();
    if (sz.minCoeff() <= 0) return;
    const int n = static_cast<int>(sz.x() * sz.y() / 100.0 * density_per_100m2);
    std::vector<Vector2d> placed;
    for (int k = 0, tries = 0; k < n && tries < 20 * n; ++tries) {
      const Vector2d c(uni(r.lo.x(), r.hi.x()), uni(r.lo.y(), r.hi.y()));
      bool ok = true;
      for (const auto& q : placed) ok = ok && (q - c).norm() > 5.0;
      for (const auto& [a, b] : avoid) {
        const Vector2d ab = b - a;
        const double s = std::clamp((c - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        ok = ok && (a + s * ab - c).norm() > 4.5;
      }
      if (!ok) continue;
      placed.push_back(c);
      tree(c, randomTree());
      ++k;
    }
  }

  void fillPark(const Rect& r, const std::vector<std::pair<Vector2d, Vector2d>>& paths) {
    fillTrees(r, 0.45, paths);
    if (chance(0.5)) {  // a pavilion, turned
      const Vector2d c = r.center() + Vector2d(uni(-0.2, 0.2) * r.size().x(), uni(-0.2, 0.2) * r.size().y());
      bool clear = true;
      for (const auto& [a, b] : paths) {
        const Vector2d ab = b - a;
        const double s = std::clamp((c - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        clear = clear && (a + s * ab - c).norm() > 14.0;
      }
      if (clear) box(c, uni(8, 14), uni(6, 10), 0.0, uni(3.5, 6.0), uni(0, M_PI), kConcrete);
    }
    for (const auto& [a, b] : paths) {
      const Vector2d ab = b - a;
      const double len = ab.norm();
      const Vector2d n = Vector2d(-ab.y(), ab.x()) / len;
      for (double s = 12.0; s < len - 12.0; s += 20.0)
        pole(a + ab * (s / len) + 2.2 * n, 4.5, std::atan2(-n.y(), -n.x()));
    }
  }

  void fillParking(const Rect& r) {
    const double row_pitch = 16.0, slot = 2.7;
    for (double y = r.lo.y() + 3.0; y + 5.0 <= r.hi.y(); y += row_pitch) {
      for (double x = r.lo.x() + 2.0; x + 2.0 <= r.hi.x(); x += slot)
        if (chance(0.7)) car({x, y + 2.5}, M_PI / 2 + (chance(0.5) ? 0.0 : M_PI) + uni(-0.05, 0.05));
      if (y + 5.0 + 8.0 < r.hi.y())
        for (double x = r.lo.x() + 8.0; x < r.hi.x() - 4.0; x += 25.0) pole({x, y + 8.0}, 8.0, 0.0);
    }
  }

  /// Identical houses along one side of `r`, centred on it, porches towards the street; `from`..`to` is the
  /// stretch of the side they may take (along x for south / north, along y for west / east).
  void terrace(const Rect& r, Side side, double from, double to) {
    const TerraceTemplate& t = terrace_;
    const int n = static_cast<int>((to - from + t.gap) / t.pitch());
    if (n < 1) return;
    const bool along_x = side == kSouth || side == kNorth;
    const double first = 0.5 * (from + to) - 0.5 * (n * t.pitch() - t.gap) + 0.5 * t.width;
    const double out = (side == kSouth || side == kWest) ? -1.0 : 1.0;  // towards the street
    const double edge = side == kSouth ? r.lo.y() : side == kNorth ? r.hi.y() : side == kWest ? r.lo.x() : r.hi.x();
    const double body = edge - out * 0.5 * t.depth, porch = edge + out * 0.5 * t.porch_depth;
    for (int i = 0; i < n; ++i) {
      const double s = first + i * t.pitch();
      const Vector2d c = along_x ? Vector2d(s, body) : Vector2d(body, s);
      const Vector2d q = along_x ? Vector2d(s, porch) : Vector2d(porch, s);
      box(c, along_x ? t.width : t.depth, along_x ? t.depth : t.width, 0.0, t.height, 0.0, kBrick);
      box(q, along_x ? t.porch_width : t.porch_depth, along_x ? t.porch_depth : t.porch_width, 0.0, t.porch_height, 0.0,
          kConcrete);
    }
  }

  /// Terraces on the sides of `r` that `allowed` names, each with probability terrace_fraction; returns what
  /// is left of `r` behind them.
  Rect terraces(const Rect& r, int allowed) {
    if (p_.terrace_fraction <= 0.0) return r;
    int sides = 0;
    for (Side s : {kSouth, kNorth, kWest, kEast})
      if ((allowed & s) && chance(p_.terrace_fraction)) sides |= s;
    const double d = terrace_.depth + terrace_.gap;  // the yard behind a terrace
    if (sides & kSouth) terrace(r, kSouth, r.lo.x(), r.hi.x());
    if (sides & kNorth) terrace(r, kNorth, r.lo.x(), r.hi.x());
    const double y0 = r.lo.y() + ((sides & kSouth) ? d : 0.0), y1 = r.hi.y() - ((sides & kNorth) ? d : 0.0);
    if (sides & kWest) terrace(r, kWest, y0, y1);
    if (sides & kEast) terrace(r, kEast, y0, y1);
    Rect inner = r;
    if (sides & kSouth) inner.lo.y() += d;
    if (sides & kNorth) inner.hi.y() -= d;
    if (sides & kWest) inner.lo.x() += d;
    if (sides & kEast) inner.hi.x() -= d;
    return inner;
  }

  /// An open plaza or lawn: little but a few benches (registration has almost only the ground to go by).
  void fillOpen(const Rect& r) {
    const Vector2d sz = r.size();
    if (sz.minCoeff() <= 2.0) return;
    const int n = std::max(1, static_cast<int>(sz.x() * sz.y() / 600.0));
    for (int k = 0; k < n; ++k)
      box({uni(r.lo.x() + 1.0, r.hi.x() - 1.0), uni(r.lo.y() + 1.0, r.hi.y() - 1.0)}, 1.8, 0.5, 0.0, 0.45, uni(0, M_PI),
          kWall);
  }

  void fillBlock(const Rect& block, int type, const std::vector<std::pair<Vector2d, Vector2d>>& paths) {
    const Rect r = type == 2 || type == 4 ? block : terraces(block, kAllSides);  // parks and open areas stay open
    if (r.size().minCoeff() < 6.0) return;
    switch (type) {
      case 0: fillBuildings(r); break;
      case 1: fillRow(r); break;
      case 2: fillPark(r, paths); break;
      case 3: fillParking(r); break;
      default: fillOpen(r); break;
    }
  }

  /// Kerbs, sidewalk, tree rows, poles, parked cars and walls along one street (a->b).
  void street(const Vector2d& a, const Vector2d& b, bool is_street) {
    const Vector2d ab = b - a;
    const double len = ab.norm();
    const Vector2d u = ab / len, n(-u.y(), u.x());
    const double yaw = std::atan2(u.y(), u.x());
    if (!is_street) {
      terrain_.paintSegment(a, b, p_.footpath_half_width, kPaving);
      for (double s = 15.0; s < len - 10.0; s += 30.0)
        pole(a + s * u + (p_.footpath_half_width + 0.8) * n, 4.5, yaw + M_PI / 2);
      return;
    }
    const double hw = p_.street_half_width;
    terrain_.paintSegment(a, b, hw + p_.sidewalk_width, kPaving);
    terrain_.paintSegment(a, b, hw, kAsphalt);
    const double clear = hw + p_.sidewalk_width + 1.0;  // keep junctions open
    for (int side : {-1, 1}) {
      const Vector2d off = side * n;
      const double s0 = clear, s1 = len - clear;
      // Kerb: short segments that follow the terrain.
      for (double s = s0; s < s1; s += 4.0) {
        const double l = std::min(4.0, s1 - s);
        box(a + (s + 0.5 * l) * u + (hw + 0.08) * off, l, 0.16, 0.0, 0.13, yaw, kConcrete);
      }
      if (chance(p_.tree_row_fraction))
        for (double s = s0 + 2.0; s < s1 - 1.0; s += p_.tree_spacing)
          tree(a + s * u + (hw + p_.sidewalk_width + 1.2) * off, row_tree_);
      if (p_.pole_spacing > 0 && side == 1)
        for (double s = s0 + 5.0; s < s1; s += p_.pole_spacing)
          pole(a + s * u + (hw + 0.5) * off, 7.0, std::atan2(-off.y(), -off.x()));
      if (chance(p_.parked_car_fraction))
        for (double s = s0 + 4.0; s < s1 - 4.0; s += 6.0)
          if (chance(0.75)) car(a + s * u + (hw - 1.2) * off, yaw + (side > 0 ? 0.0 : M_PI));
      if (p_.hedge_fraction > 0.0 && hedgeAlong(a, b, side))
        for (double s = s0; s < s1; s += 5.0) {
          const double l = std::min(5.0, s1 - s);
          box(a + (s + 0.5 * l) * u + (hw + p_.sidewalk_width + 1.1) * off, l, 1.0, 0.0, 1.4, yaw, kFoliage);
        }
      if (chance(p_.wall_fraction)) {
        const bool fence = chance(0.5);
        const double d = hw + p_.sidewalk_width + 2.8;
        for (double s = s0; s < s1; s += 5.0) {
          const double l = std::min(5.0, s1 - s);
          box(a + (s + 0.5 * l) * u + d * off, l, fence ? 0.06 : 0.3, 0.0, fence ? 1.8 : 2.2, yaw,
              fence ? kFence : kWall);
        }
      }
    }
  }

  /// Whether a street side has a hedge: a hash of the street and side, so that the main random stream (and with
  /// it every other object of the world) is the same with and without hedges.
  bool hedgeAlong(const Vector2d& a, const Vector2d& b, int side) const {
    std::uint64_t h = 0x6A09E667F3BCC909ULL;
    for (double v : {a.x(), a.y(), b.x(), b.y(), static_cast<double>(side)}) {
      h ^= static_cast<std::uint64_t>(std::llround(v * 100.0));
      h = splitmix64(h);
    }
    return static_cast<double>(splitmix64(h) >> 11) * 0x1.0p-53 < p_.hedge_fraction;
  }

  TreeShape row_tree_;
  RowTemplate row_;
  TerraceTemplate terrace_{};

 private:
  const WorldParams& p_;
  std::mt19937_64& rng_;
  Terrain& terrain_;
  std::vector<Primitive>& prims_;
  std::vector<ParkedCar>& cars_;
  std::vector<Primitive>& canopies_;
};

/// One trial's clutter: the cars that stay (some moved along their kerb), the canopies as they are that day.
void addTrialClutter(const WorldLayout& L, std::mt19937_64& rng, std::vector<Primitive>& prims) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const WorldParams& p = L.params;
  for (ParkedCar car : L.cars) {
    const double u = uni(0.0, 1.0);
    if (u < 0.5 * p.car_change) continue;  // gone that day
    if (u < p.car_change) {                // parked a little further along the kerb
      const double shift = (uni(0.0, 1.0) < 0.5 ? -1.0 : 1.0) * uni(1.0, 5.0);
      car.x += shift * std::cos(car.yaw);
      car.y += shift * std::sin(car.yaw);
    }
    addCar(L.terrain, prims, car);
  }
  for (Primitive canopy : L.canopies) {
    if (p.foliage_change > 0.0) {
      const double grow = 1.0 + uni(-p.foliage_change, p.foliage_change);
      canopy.half *= grow;
      canopy.center += Vector3d(uni(-1.0, 1.0), uni(-1.0, 1.0), 0.0) * (p.foliage_change * canopy.half.x());
    }
    prims.push_back(canopy);
  }
}

/// Pedestrians on the pavements (streets) and beside the footpaths, away from the junctions and the lanes the
/// platforms drive or walk in.
void addPeople(const WorldLayout& L, std::mt19937_64& rng, std::vector<Primitive>& prims) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const WorldParams& p = L.params;
  const auto& net = L.network;
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    const Vector2d a = net.nodes[net.edges[e].a], b = net.nodes[net.edges[e].b];
    const double len = (b - a).norm();
    const double clear = p.street_half_width + p.sidewalk_width + 2.0;
    if (len < 2.0 * clear) continue;
    const Vector2d u = (b - a) / len, n(-u.y(), u.x());
    const double expected = p.people_per_100m * len / 100.0;
    int count = static_cast<int>(expected);
    if (uni(0.0, 1.0) < expected - count) ++count;
    for (int k = 0; k < count; ++k) {
      const double s = uni(clear, len - clear);
      const double side = uni(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      const double off = net.edges[e].street ? p.street_half_width + uni(0.5, 0.9) * p.sidewalk_width
                                             : p.footpath_half_width + uni(1.0, 2.0);
      const Vector2d c = a + s * u + side * off * n;
      const double g = L.terrain.minHeightAround(c.x(), c.y(), 0.3);
      prims.push_back(Primitive::cylinder(c.x(), c.y(), g - 0.1, g + uni(1.55, 1.9), uni(0.2, 0.3), kBark));
    }
  }
}

}  // namespace

bool changesPerTrial(const WorldParams& p) {
  return p.car_change > 0.0 || p.people_per_100m > 0.0 || p.foliage_change > 0.0;
}

World layoutWorld(const WorldLayout& layout, std::optional<std::uint64_t> trial_seed) {
  std::vector<Primitive> prims = layout.fixed;
  if (!trial_seed) {
    for (const ParkedCar& car : layout.cars) addCar(layout.terrain, prims, car);
    prims.insert(prims.end(), layout.canopies.begin(), layout.canopies.end());
  } else {
    std::mt19937_64 rng(*trial_seed);
    addTrialClutter(layout, rng, prims);
    addPeople(layout, rng, prims);
  }
  return World(layout.terrain, std::move(prims), layout.network);
}

World generateWorld(const WorldParams& p, std::uint64_t seed) { return layoutWorld(generateLayout(p, seed)); }

WorldLayout generateLayout(const WorldParams& p, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int bx = std::max(1, p.blocks_x), by = std::max(1, p.blocks_y);
  std::vector<double> xs{0.0}, ys{0.0};
  for (int i = 0; i < bx; ++i) xs.push_back(xs.back() + uni(p.block_min, std::max(p.block_min, p.block_max)));
  for (int j = 0; j < by; ++j) ys.push_back(ys.back() + uni(p.block_min, std::max(p.block_min, p.block_max)));
  // Centre the campus on the origin.
  const double cx = 0.5 * xs.back(), cy = 0.5 * ys.back();
  for (auto& x : xs) x -= cx;
  for (auto& y : ys) y -= cy;

  const double pad = p.outer_ring + p.terrain_margin;
  Terrain terrain =
      Terrain::generate({xs.front() - pad, ys.front() - pad}, {xs.back() + pad, ys.back() + pad}, p.terrain, rng);
  std::vector<Primitive> prims;
  std::vector<ParkedCar> cars;
  std::vector<Primitive> canopies;
  Builder b(p, rng, terrain, prims, cars, canopies);

  PathNetwork net;
  auto node = [&](int i, int j) { return j * (bx + 1) + i; };
  for (int j = 0; j <= by; ++j)
    for (int i = 0; i <= bx; ++i) net.addNode({xs[i], ys[j]});
  // Streets along the grid; some interior ones become footpaths.
  struct Seg {
    int a, b;
    bool street;
  };
  std::vector<Seg> segs;
  for (int j = 0; j <= by; ++j)
    for (int i = 0; i < bx; ++i) {
      const bool interior = j > 0 && j < by;
      segs.push_back({node(i, j), node(i + 1, j), !(interior && b.chance(p.footpath_fraction))});
    }
  for (int i = 0; i <= bx; ++i)
    for (int j = 0; j < by; ++j) {
      const bool interior = i > 0 && i < bx;
      segs.push_back({node(i, j), node(i, j + 1), !(interior && b.chance(p.footpath_fraction))});
    }
  for (const auto& s : segs) net.addEdge(s.a, s.b, s.street);

  // Blocks.
  const double total = p.p_buildings + p.p_row + p.p_park + p.p_parking + p.p_open;
  auto pickType = [&]() {
    double u = uni(0.0, total > 0 ? total : 1.0);
    if ((u -= p.p_buildings) < 0) return 0;
    if ((u -= p.p_row) < 0) return 1;
    if ((u -= p.p_park) < 0) return 2;
    if ((u -= p.p_parking) < 0 || p.p_open <= 0.0) return 3;
    return 4;
  };
  const double inset = p.street_half_width + p.sidewalk_width + 2.0;
  for (int j = 0; j < by; ++j)
    for (int i = 0; i < bx; ++i) {
      const Rect r{{xs[i] + inset, ys[j] + inset}, {xs[i + 1] - inset, ys[j + 1] - inset}};
      const int type = pickType();
      std::vector<std::pair<Vector2d, Vector2d>> paths;
      if (type == 2 && b.chance(p.diagonal_fraction)) {
        const bool up = b.chance(0.5);
        const int na = up ? node(i, j) : node(i + 1, j), nb = up ? node(i + 1, j + 1) : node(i, j + 1);
        net.addEdge(na, nb, false);
        paths.emplace_back(net.nodes[na], net.nodes[nb]);
      }
      b.fillBlock(r, type, paths);
    }
  // The ring outside the outer streets: buildings or woods, so that the campus does not end in a void.
  const double ring = p.outer_ring;
  if (ring > inset + 5.0) {
    std::vector<std::pair<Rect, Side>> outer;  // each with its side along the campus's outer street
    for (int i = 0; i < bx; ++i) {
      outer.push_back({{{xs[i] + inset, ys.front() - ring}, {xs[i + 1] - inset, ys.front() - inset}}, kNorth});
      outer.push_back({{{xs[i] + inset, ys.back() + inset}, {xs[i + 1] - inset, ys.back() + ring}}, kSouth});
    }
    for (int j = 0; j < by; ++j) {
      outer.push_back({{{xs.front() - ring, ys[j] + inset}, {xs.front() - inset, ys[j + 1] - inset}}, kEast});
      outer.push_back({{{xs.back() + inset, ys[j] + inset}, {xs.back() + ring, ys[j + 1] - inset}}, kWest});
    }
    for (const auto& [r, side] : outer) {
      if (b.chance(0.55)) {
        const Rect inner = b.terraces(r, side);
        if (inner.size().minCoeff() >= 8.0) b.fillBuildings(inner);
      } else {
        b.fillTrees(r, 0.5);
      }
    }
  }
  for (const auto& s : segs) b.street(net.nodes[s.a], net.nodes[s.b], s.street);
  for (std::size_t e = segs.size(); e < net.edges.size(); ++e)
    terrain.paintSegment(net.nodes[net.edges[e].a], net.nodes[net.edges[e].b], p.footpath_half_width, kPaving);
  WorldLayout layout;
  layout.params = p;
  layout.terrain = std::move(terrain);
  layout.fixed = std::move(prims);
  layout.cars = std::move(cars);
  layout.canopies = std::move(canopies);
  layout.network = std::move(net);
  return layout;
}

}  // namespace cosmo::sim
