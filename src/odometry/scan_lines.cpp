#include "cosmo/odometry/scan_lines.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cosmo::odometry {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kTwoPi = 2.0f * kPi;
constexpr float kDeg = kPi / 180.0f;

/// Angle difference wrapped into (-pi, pi].
float wrapAngle(float a) {
  if (a > kPi) return a - kTwoPi;
  if (a <= -kPi) return a + kTwoPi;
  return a;
}

struct ValidPoint {
  std::uint32_t index;  ///< index in the scan
  float azimuth;
};

/// Line index per valid point when the cloud is an ordered sweep (ring after ring, each by azimuth): a new
/// line starts at every wrap of the azimuth. Empty when the order does not look like that.
std::vector<std::uint16_t> linesFromOrder(const std::vector<ValidPoint>& pts) {
  if (pts.size() < 1000) return {};
  std::size_t small_steps = 0, wraps = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const float d = pts[i].azimuth - pts[i - 1].azimuth;
    if (std::abs(d) > kPi)
      ++wraps;
    else if (std::abs(d) < 5.0f * kDeg)
      ++small_steps;
  }
  if (small_steps < 0.95 * static_cast<double>(pts.size()) || wraps < 8 || wraps > 256) return {};
  // A new line at an azimuth wrap once the current line has swept most of a turn (jitter of the points near
  // the seam can cross it back and forth).
  std::vector<std::uint16_t> line(pts.size(), 0);
  std::uint16_t current = 0;
  float travel = 0.0f;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const float d = pts[i].azimuth - pts[i - 1].azimuth;
    if (std::abs(d) > kPi && travel > 1.5f * kPi) {
      ++current;
      travel = 0.0f;
    } else {
      travel += std::abs(wrapAngle(d));
    }
    line[i] = current;
  }
  if (current < 8 || current > 256) return {};
  return line;
}

}  // namespace

std::size_t ScanLines::numPoints() const {
  std::size_t n = 0;
  for (const auto& l : lines) n += l.points.size();
  return n;
}

float fastAtan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float mx = std::max(ax, ay);
  if (mx == 0.0f) return 0.0f;
  const float a = std::min(ax, ay) / mx;
  const float s = a * a;
  // Minimax polynomial for atan on [0, 1] (Abramowitz-Stegun style), max error about 1e-5 rad.
  float r = ((((0.0208351f * s - 0.0851330f) * s + 0.1801410f) * s - 0.3302995f) * s + 0.9998660f) * a;
  if (ay > ax) r = 0.5f * kPi - r;
  if (x < 0.0f) r = kPi - r;
  if (y < 0.0f) r = -r;
  return r;
}

std::vector<float> estimateBeamElevations(const std::vector<float>& elevations) {
  if (elevations.size() < 1000) return {};
  std::vector<float> sorted = elevations;
  const std::size_t lo_i = sorted.size() / 1000, hi_i = sorted.size() - 1 - sorted.size() / 1000;
  std::nth_element(sorted.begin(), sorted.begin() + lo_i, sorted.end());
  const float lo = sorted[lo_i];
  std::nth_element(sorted.begin(), sorted.begin() + hi_i, sorted.end());
  const float hi = sorted[hi_i];
  const float bin = 0.02f * kDeg;
  const int nbins = static_cast<int>((hi - lo) / bin) + 3;
  if (nbins < 10 || nbins > 20000) return {};
  std::vector<double> hist(nbins, 0.0);
  for (float e : elevations) {
    const int b = static_cast<int>((e - lo) / bin) + 1;
    if (b >= 0 && b < nbins) hist[b] += 1.0;
  }
  // Smooth (box of 5 bins = 0.1 deg).
  std::vector<double> h(nbins, 0.0);
  for (int i = 0; i < nbins; ++i)
    for (int k = -2; k <= 2; ++k)
      if (i + k >= 0 && i + k < nbins) h[i] += hist[i + k];
  // Local maxima, then keep only maxima separated from their neighbour by a deep valley (< 50 % of the lower
  // of the two peaks); otherwise the lower peak is merged into the higher one.
  std::vector<int> peaks;
  for (int i = 1; i + 1 < nbins; ++i)
    if (h[i] > 0 && h[i] >= h[i - 1] && h[i] > h[i + 1]) peaks.push_back(i);
  bool merged = true;
  while (merged && peaks.size() > 1) {
    merged = false;
    std::vector<int> kept{peaks[0]};
    for (std::size_t k = 1; k < peaks.size(); ++k) {
      const int a = kept.back(), b = peaks[k];
      const double valley = *std::min_element(h.begin() + a, h.begin() + b + 1);
      if (valley < 0.5 * std::min(h[a], h[b])) {
        kept.push_back(b);
      } else {
        if (h[b] > h[a]) kept.back() = b;
        merged = true;
      }
    }
    peaks.swap(kept);
  }
  // Drop tiny peaks (noise): below 10 % of the median peak height.
  if (peaks.empty()) return {};
  std::vector<double> heights;
  for (int p : peaks) heights.push_back(h[p]);
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  const double median_height = heights[heights.size() / 2];
  std::vector<float> centres;
  for (int p : peaks)
    if (h[p] >= 0.1 * median_height) centres.push_back(lo + (static_cast<float>(p) - 0.5f) * bin);
  if (centres.size() < 8 || centres.size() > 256) return {};
  return centres;
}

ScanLines organizeScanLines(const Scan& scan, const LoamParams& params) {
  ScanLines out;
  const bool has_time = scan.hasTime();
  const bool has_ring = scan.hasRing();
  const float min_r2 = static_cast<float>(params.min_range * params.min_range);
  const float max_r2 = static_cast<float>(params.max_range * params.max_range);

  std::vector<ValidPoint> pts;
  pts.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const auto& p = scan.points[i];
    if (!p.allFinite()) continue;
    const float r2 = p.squaredNorm();
    if (r2 < min_r2 || r2 > max_r2) continue;
    pts.push_back({static_cast<std::uint32_t>(i), fastAtan2(p.y(), p.x())});
  }
  if (pts.empty()) return out;

  // Line index per valid point.
  std::vector<std::uint16_t> line_of;
  int num_lines = 0;
  if (has_ring) {
    line_of.resize(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      line_of[k] = scan.ring[pts[k].index];
      num_lines = std::max(num_lines, static_cast<int>(line_of[k]) + 1);
    }
    out.method = "ring";
  } else if (auto by_order = linesFromOrder(pts); !by_order.empty()) {
    line_of = std::move(by_order);
    num_lines = static_cast<int>(line_of.back()) + 1;
    out.method = "order";
  } else {
    std::vector<float> elev(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const auto& p = scan.points[pts[k].index];
      elev[k] = fastAtan2(p.z(), std::sqrt(p.x() * p.x() + p.y() * p.y()));
    }
    std::vector<float> centres = estimateBeamElevations(elev);
    if (centres.empty()) {
      // No visible beam structure: equal elevation bins.
      const auto [mn, mx] = std::minmax_element(elev.begin(), elev.end());
      const int n = std::max(1, params.fallback_scan_lines);
      for (int b = 0; b < n; ++b)
        centres.push_back(*mn + (*mx - *mn) * (n == 1 ? 0.5f : static_cast<float>(b) / static_cast<float>(n - 1)));
    }
    line_of.resize(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      auto it = std::lower_bound(centres.begin(), centres.end(), elev[k]);
      std::size_t b = static_cast<std::size_t>(it - centres.begin());
      if (b == centres.size() || (b > 0 && elev[k] - centres[b - 1] < centres[b] - elev[k])) --b;
      line_of[k] = static_cast<std::uint16_t>(b);
    }
    num_lines = static_cast<int>(centres.size());
    out.method = "elevation";
  }

  // Bucket the points per line (keeping the scan order), then order each line by azimuth when needed.
  std::vector<std::vector<std::uint32_t>> members(num_lines);
  for (std::size_t k = 0; k < pts.size(); ++k) members[line_of[k]].push_back(static_cast<std::uint32_t>(k));
  out.lines.reserve(num_lines);
  std::vector<float> steps;
  for (auto& m : members) {
    if (m.empty()) continue;
    std::size_t small = 0;
    for (std::size_t j = 1; j < m.size(); ++j)
      if (std::abs(wrapAngle(pts[m[j]].azimuth - pts[m[j - 1]].azimuth)) < 5.0f * kDeg) ++small;
    if (static_cast<double>(small) < 0.9 * static_cast<double>(m.size() - 1))
      std::sort(m.begin(), m.end(), [&](std::uint32_t a, std::uint32_t b) { return pts[a].azimuth < pts[b].azimuth; });
    ScanLine line;
    line.points.reserve(m.size());
    if (has_time) line.time.reserve(m.size());
    for (std::uint32_t k : m) {
      line.points.push_back(scan.points[pts[k].index]);
      if (has_time) line.time.push_back(scan.time[pts[k].index]);
    }
    // Gaps: azimuth steps far above the line's median step are line ends for the curvature.
    line.break_before.assign(m.size(), 0);
    steps.clear();
    for (std::size_t j = 1; j < m.size(); ++j)
      steps.push_back(std::abs(wrapAngle(pts[m[j]].azimuth - pts[m[j - 1]].azimuth)));
    // The gap is at least 1 degree: a line whose steps all stay below that (no missing returns) has no gap,
    // whatever its median step, and needs no median.
    if (!steps.empty() && *std::max_element(steps.begin(), steps.end()) > 1.0f * kDeg) {
      std::vector<float> tmp = steps;
      std::nth_element(tmp.begin(), tmp.begin() + tmp.size() / 2, tmp.end());
      const float gap = std::max(5.0f * tmp[tmp.size() / 2], 1.0f * kDeg);
      for (std::size_t j = 1; j < m.size(); ++j) line.break_before[j] = steps[j - 1] > gap ? 1 : 0;
    }
    out.lines.push_back(std::move(line));
  }
  return out;
}

}  // namespace cosmo::odometry
