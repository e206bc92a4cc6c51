#include "cosmo/sim/trajectory_generator.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "cosmo/common/pose.hpp"

namespace cosmo::sim {

#define COSMO_SIM_MOTION_FIELDS(X)                                                                                     \
  X(cruise_speed)                                                                                                      \
  X(speed_variation)                                                                                                   \
  X(max_accel) X(max_decel) X(max_lateral_accel) X(corner_radius) X(lateral_offset) X(body_height) X(axle_half_length) \
      X(track_half_width) X(bob_amplitude) X(bob_frequency) X(sway_deg) X(start_still) X(end_still) X(rate_hz)

MotionParams MotionParams::preset(const std::string& platform) {
  MotionParams m;
  if (platform == "handheld") {
    m.cruise_speed = 1.4;
    m.speed_variation = 0.1;
    m.max_accel = 0.5;
    m.max_decel = 0.7;
    m.max_lateral_accel = 0.6;
    m.corner_radius = 2.5;
    m.lateral_offset = 0.5;
    m.body_height = 1.4;
    m.axle_half_length = 0.3;
    m.track_half_width = 0.3;
    m.bob_amplitude = 0.02;
    m.sway_deg = 1.5;
  } else if (platform == "atv") {
    // defaults
  } else if (platform == "car") {
    m.cruise_speed = 7.0;
    m.max_accel = 1.2;
    m.max_decel = 1.8;
    m.max_lateral_accel = 2.0;
    m.corner_radius = 9.0;
    m.lateral_offset = 1.5;
    m.body_height = 1.6;
    m.axle_half_length = 1.4;
    m.track_half_width = 0.8;
  } else {
    throw std::runtime_error("unknown platform '" + platform + "' (known: handheld, atv, car)");
  }
  return m;
}

MotionParams MotionParams::fromConfig(const ConfigNode& node, const std::string& platform) {
  MotionParams m;
  try {
    m = preset(platform);
  } catch (const std::exception& e) { throw std::runtime_error(node.where + ": " + e.what()); }
#define X(f) node.read(#f, m.f);
  COSMO_SIM_MOTION_FIELDS(X)
#undef X
  if (!(m.cruise_speed > 0) || !(m.max_accel > 0) || !(m.max_decel > 0) || !(m.max_lateral_accel > 0) ||
      !(m.rate_hz >= 1))
    throw std::runtime_error(node.where + ": speeds, accelerations and rate_hz must be positive");
  std::vector<std::string> known;
#define X(f) known.emplace_back(#f);
  COSMO_SIM_MOTION_FIELDS(X)
#undef X
  node.rejectUnknownKeys(known);
  return m;
}

std::string MotionParams::describe() const {
  std::ostringstream os;
  os << std::setprecision(17);
#define X(f) os << #f << '=' << f << ';';
  COSMO_SIM_MOTION_FIELDS(X)
#undef X
  return os.str();
}

namespace {
using Eigen::Vector2d;

struct PathSample {
  Vector2d p;
  double heading;
  double curvature;  ///< |kappa|, 1/m
};

/// Polyline shifted sideways (right of travel for offset > 0), mitred at the vertices.
std::vector<Vector2d> offsetPolyline(const std::vector<Vector2d>& pts, double offset) {
  if (std::abs(offset) < 1e-9 || pts.size() < 2) return pts;
  std::vector<Vector2d> out(pts.size());
  auto right = [](const Vector2d& d) { return Vector2d(d.y(), -d.x()); };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vector2d din = i > 0 ? (pts[i] - pts[i - 1]).normalized() : (pts[1] - pts[0]).normalized();
    const Vector2d dout = i + 1 < pts.size() ? (pts[i + 1] - pts[i]).normalized() : din;
    Vector2d m = right(din) + right(dout);
    const double len = m.norm();
    if (len < 0.2) {
      out[i] = pts[i] + offset * right(din);
      continue;
    }  // near U-turn: no mitre
    m /= len;
    out[i] = pts[i] + m * (offset / std::max(0.3, m.dot(right(din))));
  }
  return out;
}

/// Densely sampled path with rounded corners.
std::vector<PathSample> roundedPath(const std::vector<Vector2d>& pts, double radius, double ds) {
  std::vector<PathSample> out;
  auto straight = [&](const Vector2d& a, const Vector2d& b) {
    const Vector2d d = b - a;
    const double len = d.norm();
    if (len < 1e-9) return;
    const double h = std::atan2(d.y(), d.x());
    const int n = std::max(1, static_cast<int>(std::ceil(len / ds)));
    for (int k = out.empty() ? 0 : 1; k <= n; ++k) out.push_back({a + d * (static_cast<double>(k) / n), h, 0.0});
  };
  Vector2d cur = pts.front();
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const Vector2d din = pts[i] - pts[i - 1], dout = pts[i + 1] - pts[i];
    const double lin = din.norm(), lout = dout.norm();
    if (lin < 1e-9 || lout < 1e-9) continue;
    const Vector2d uin = din / lin, uout = dout / lout;
    const double cross = uin.x() * uout.y() - uin.y() * uout.x();
    const double turn = std::atan2(cross, uin.dot(uout));  // signed turn angle
    if (std::abs(turn) < 1e-3) continue;
    double tlen = radius * std::tan(0.5 * std::abs(turn));
    tlen = std::min(tlen, 0.45 * std::min(lin, lout));
    const double r = tlen / std::tan(0.5 * std::abs(turn));
    const Vector2d a = pts[i] - tlen * uin, b = pts[i] + tlen * uout;
    straight(cur, a);
    const double side = turn > 0 ? 1.0 : -1.0;  // left turn: centre on the left
    const Vector2d c = a + side * r * Vector2d(-uin.y(), uin.x());
    const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
    const double h0 = std::atan2(uin.y(), uin.x());
    const int n = std::max(2, static_cast<int>(std::ceil(r * std::abs(turn) / ds)));
    for (int k = 1; k <= n; ++k) {
      const double f = static_cast<double>(k) / n;
      const double ang = a0 + turn * f;
      out.push_back({c + r * Vector2d(std::cos(ang), std::sin(ang)), h0 + turn * f, 1.0 / std::max(r, 1e-3)});
    }
    cur = b;
  }
  straight(cur, pts.back());
  if (out.empty()) out.push_back({pts.front(), 0.0, 0.0});
  return out;
}
}  // namespace

Trajectory makeTrajectory(const std::vector<Vector2d>& waypoints, const Terrain& terrain, const MotionParams& mp,
                          StampNs start, std::mt19937_64& rng) {
  if (waypoints.size() < 2) throw std::invalid_argument("makeTrajectory: need at least two waypoints");
  const double ds = 0.05;
  const auto path = roundedPath(offsetPolyline(waypoints, mp.lateral_offset), mp.corner_radius, ds);
  const std::size_t n = path.size();
  // Arc length.
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) s[i] = s[i - 1] + (path[i].p - path[i - 1].p).norm();
  // Speed limits, then acceleration-limited forward/backward passes.
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double phase = 2.0 * M_PI * u01(rng), wave = 60.0 + 60.0 * u01(rng);
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double cruise = mp.cruise_speed * (1.0 + mp.speed_variation * std::sin(2.0 * M_PI * s[i] / wave + phase));
    v[i] = path[i].curvature > 1e-9 ? std::min(cruise, std::sqrt(mp.max_lateral_accel / path[i].curvature)) : cruise;
  }
  v.front() = 0.0;
  v.back() = 0.0;
  for (std::size_t i = 1; i < n; ++i)
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * mp.max_accel * (s[i] - s[i - 1])));
  for (std::size_t i = n - 1; i-- > 0;)
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * mp.max_decel * (s[i + 1] - s[i])));
  // Time at each sample.
  std::vector<double> t(n, mp.start_still);
  for (std::size_t i = 1; i < n; ++i) {
    const double vm = 0.5 * (v[i] + v[i - 1]);
    t[i] = t[i - 1] + (vm > 1e-9 ? (s[i] - s[i - 1]) / vm : 0.0);
  }
  const double t_end = t.back() + mp.end_still;
  // Unwrapped headings for interpolation.
  std::vector<double> h(n);
  h[0] = path[0].heading;
  for (std::size_t i = 1; i < n; ++i) {
    double d = path[i].heading - path[i - 1].heading;
    d = std::remainder(d, 2.0 * M_PI);
    h[i] = h[i - 1] + d;
  }
  const double sway = mp.sway_deg * M_PI / 180.0;
  const double sway_phase = 2.0 * M_PI * u01(rng);
  Trajectory traj;
  const auto steps = static_cast<std::size_t>(std::floor(t_end * mp.rate_hz)) + 1;
  std::size_t k = 0;
  double dist_walked = 0.0;  // for the gait phase
  Vector2d last_p = path.front().p;
  for (std::size_t m = 0; m < steps; ++m) {
    const double tau = static_cast<double>(m) / mp.rate_hz;
    while (k + 1 < n && t[k + 1] <= tau) ++k;
    Vector2d p;
    double yaw;
    if (k + 1 >= n || tau <= t[k]) {
      p = path[k].p;
      yaw = h[k];
    } else {
      // Constant acceleration within the sample interval: position is C1 in time.
      const double seg = s[k + 1] - s[k], dt = tau - t[k];
      const double acc = seg > 1e-12 ? (v[k + 1] * v[k + 1] - v[k] * v[k]) / (2.0 * seg) : 0.0;
      const double f = seg > 1e-12 ? std::clamp((v[k] * dt + 0.5 * acc * dt * dt) / seg, 0.0, 1.0) : 0.0;
      p = path[k].p + f * (path[k + 1].p - path[k].p);
      yaw = h[k] + f * (h[k + 1] - h[k]);
    }
    dist_walked += (p - last_p).norm();
    last_p = p;
    const Vector2d fwd(std::cos(yaw), std::sin(yaw)), left(-fwd.y(), fwd.x());
    const double L = mp.axle_half_length, W = mp.track_half_width;
    const Vector2d pf = p + L * fwd, pb = p - L * fwd, pl = p + W * left, pr = p - W * left;
    const double pitch_terrain = -std::atan2(terrain.height(pf.x(), pf.y()) - terrain.height(pb.x(), pb.y()), 2.0 * L);
    const double roll_terrain = std::atan2(terrain.height(pl.x(), pl.y()) - terrain.height(pr.x(), pr.y()), 2.0 * W);
    // Gait: one bob per step (step length ~ 0.75 m at walking speed), sway per stride.
    const double gait = 2.0 * M_PI * dist_walked / std::max(mp.cruise_speed / mp.bob_frequency, 1e-3);
    const double z = 0.25 * (terrain.height(pf.x(), pf.y()) + terrain.height(pb.x(), pb.y()) +
                             terrain.height(pl.x(), pl.y()) + terrain.height(pr.x(), pr.y())) +
                     mp.body_height + mp.bob_amplitude * std::sin(gait);
    const double roll = roll_terrain + sway * std::sin(0.5 * gait + sway_phase);
    const double pitch = pitch_terrain + 0.5 * sway * std::sin(gait + 1.3 * sway_phase);
    yaw += 0.5 * sway * std::sin(0.5 * gait + 0.7 + sway_phase);
    traj.append(start + static_cast<StampNs>(std::llround(tau * 1e9)), makePose(p.x(), p.y(), z, roll, pitch, yaw));
  }
  return traj;
}

}  // namespace cosmo::sim
