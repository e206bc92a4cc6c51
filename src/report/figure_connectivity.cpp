// The connectivity timeline: per robot pair the intervals the link was up and its throughput per window against
// time, and the robots in range (connected pairs) below.
#include <algorithm>
#include <cstdio>

#include "cosmo/report/figures.hpp"
#include "cosmo/report/plot_frame.hpp"
#include "figure_style.hpp"

namespace cosmo::report {

namespace {

constexpr double kWidth = 1500.0, kLeft = 90.0, kRight = 40.0, kTop = 70.0;
constexpr double kPanel = 120.0, kGap = 62.0, kBand = 14.0;

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// Time axis of the panels: radio time to pixels.
struct TimeAxis {
  double t0, t1, left, width;
  double x(double t) const { return left + (t - t0) / std::max(t1 - t0, 1e-9) * width; }
};

/// Time ticks and grid lines over a panel [top, top + height], labels below it when `labels`.
void drawTimeGrid(Svg& svg, const TimeAxis& axis, double top, double height, bool labels) {
  const double step = niceStep((axis.t1 - axis.t0) / 12.0);
  const Stroke grid{"#dddddd", 0.6, 1.0, ""};
  for (double s = 0.0; axis.t0 + s <= axis.t1 + 1e-9; s += step) {
    const double px = axis.x(axis.t0 + s);
    svg.line({px, top}, {px, top + height}, grid);
    if (labels) svg.text(px, top + height + 16.0, format("%g", s), 12.0, "middle");
  }
}

/// A value per window as a step line in the panel (value 0 at the bottom, `vmax` at the top).
std::vector<Eigen::Vector2d> stepLine(const std::vector<double>& values, const TimeAxis& axis, double start,
                                      double window, double bottom, double height, double vmax) {
  std::vector<Eigen::Vector2d> pts;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double y = bottom - std::min(values[k] / vmax, 1.0) * height;
    const double a = start + static_cast<double>(k) * window;
    pts.emplace_back(axis.x(std::max(a, axis.t0)), y);
    pts.emplace_back(axis.x(std::min(a + window, axis.t1)), y);
  }
  return pts;
}

}  // namespace

std::string connectivitySvg(const comm::Connectivity& c, const std::string& title) {
  const std::size_t panels = c.pairs.size() + 1;  // the pairs, then the robots in range
  const double height = kTop + static_cast<double>(panels) * (kPanel + kGap) + 40.0;
  Svg svg(kWidth, height);
  svg.text(kLeft, 28.0, title + ": connectivity over time", 18.0, "start", true);
  svg.text(kLeft, 50.0,
           "green band: link up (" +
               (c.trace.empty() ? "within d_init " + format("%g", c.d_init) + " m"
                                : "trace " + c.trace + ", d_init outside") +
               ", both robots on); line: throughput per " + format("%g", c.window_s) + " s window",
           13.0);
  const TimeAxis axis{c.start_s, std::max(c.end_s, c.start_s + c.step_s), kLeft, kWidth - kLeft - kRight};
  double vmax = 1.0;
  for (const auto& p : c.pairs)
    for (double v : p.window_Bps) vmax = std::max(vmax, v);
  const double vtop = niceStep(vmax / 1000.0) * std::ceil(vmax / 1000.0 / niceStep(vmax / 1000.0)) * 1000.0;

  double top = kTop + 20.0;
  for (std::size_t i = 0; i < c.pairs.size(); ++i, top += kPanel + kGap) {
    const comm::PairConnectivity& p = c.pairs[i];
    const double bottom = top + kPanel;
    svg.text(kLeft, top - 8.0,
             std::string(1, p.a) + "–" + p.b + ": " + format("%.1f %% connected", 100.0 * c.connectedFraction(p)) +
                 ", " + std::to_string(p.disconnections) + " disconnection" + (p.disconnections == 1 ? "" : "s") +
                 ", scans delivered / dropped " + p.a + "→" + p.b + " " + std::to_string(p.delivered_ab) + " / " +
                 std::to_string(p.dropped_ab) + ", " + p.b + "→" + p.a + " " + std::to_string(p.delivered_ba) + " / " +
                 std::to_string(p.dropped_ba) + ", " +
                 format("%.0f kB/s while connected", p.throughputConnectedBps() / 1000.0),
             14.0, "start", true);
    drawTimeGrid(svg, axis, top, kPanel, i + 1 == c.pairs.size());
    for (const auto& [s, e] : p.up) {
      const double x0 = axis.x(s), x1 = axis.x(e);
      svg.rect(x0, bottom - kBand, std::max(x1 - x0, 0.5), kBand, "#7fcf7f");
    }
    svg.polyline(stepLine(p.window_Bps, axis, c.start_s, c.window_s, bottom - kBand, kPanel - kBand - 4.0, vtop),
                 Stroke{robotColor(i), 1.4, 1.0, ""});
    svg.rect(kLeft, top, axis.width, kPanel, "none", "#444444");
    svg.text(kLeft - 6.0, top + 8.0, format("%g", vtop / 1000.0), 12.0, "end");
    svg.text(kLeft - 6.0, bottom - kBand + 4.0, "0", 12.0, "end");
    svg.text(kLeft - 6.0, top + 0.5 * kPanel, "kB/s", 12.0, "end");
  }
  // robots in range
  const double npairs = static_cast<double>(std::max<std::size_t>(c.pairs.size(), 1));
  const double bottom = top + kPanel;
  svg.text(kLeft, top - 8.0, "pairs connected (mean over each window)", 14.0, "start", true);
  drawTimeGrid(svg, axis, top, kPanel, true);
  svg.polyline(stepLine(c.pairs_connected, axis, c.start_s, c.window_s, bottom, kPanel - 4.0, npairs),
               Stroke{"#333333", 1.4, 1.0, ""});
  svg.rect(kLeft, top, axis.width, kPanel, "none", "#444444");
  svg.text(kLeft - 6.0, top + 8.0, format("%g", npairs), 12.0, "end");
  svg.text(kLeft - 6.0, bottom + 4.0, "0", 12.0, "end");
  svg.text(kLeft + 0.5 * axis.width, bottom + 36.0, "time since the run's start [s]", 13.0, "middle");
  return svg.str();
}

}  // namespace cosmo::report
