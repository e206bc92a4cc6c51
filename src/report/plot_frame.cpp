#include "cosmo/report/plot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cosmo::report {

void Bounds::add(double x, double y) {
  if (empty) {
    xmin = xmax = x;
    ymin = ymax = y;
    empty = false;
    return;
  }
  xmin = std::min(xmin, x);
  xmax = std::max(xmax, x);
  ymin = std::min(ymin, y);
  ymax = std::max(ymax, y);
}

double niceStep(double raw) {
  if (!(raw > 0.0)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= raw) return m * p;
  return p;
}

namespace {

std::string metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-9 ? 0.0 : v);
  return buf;
}

}  // namespace

PlotFrame::PlotFrame(const Bounds& world, double left, double top, double width, double height)
    : left_(left), top_(top), width_(width), height_(height) {
  const double dx = std::max(world.empty ? 1.0 : world.xmax - world.xmin, 1.0);
  const double dy = std::max(world.empty ? 1.0 : world.ymax - world.ymin, 1.0);
  scale_ = std::min(width / (1.06 * dx), height / (1.06 * dy));
  cx_ = world.empty ? 0.0 : 0.5 * (world.xmin + world.xmax);
  cy_ = world.empty ? 0.0 : 0.5 * (world.ymin + world.ymax);
}

Eigen::Vector2d PlotFrame::map(double x, double y) const {
  return {left_ + 0.5 * width_ + (x - cx_) * scale_, top_ + 0.5 * height_ - (y - cy_) * scale_};
}

void PlotFrame::drawTitle(Svg& svg, const std::string& title) const {
  svg.text(left_, top_ - 10.0, title, 16.0, "start", true);
}

void PlotFrame::drawAxes(Svg& svg) const {
  svg.rect(left_, top_, width_, height_, "none", "#444444");
  const double step = niceStep(100.0 / scale_);  // a tick every >= 100 px
  const double x0 = cx_ - 0.5 * width_ / scale_, x1 = cx_ + 0.5 * width_ / scale_;
  const double y0 = cy_ - 0.5 * height_ / scale_, y1 = cy_ + 0.5 * height_ / scale_;
  const double bottom = top_ + height_;
  Stroke grid{"#dddddd", 0.6, 1.0, ""};
  for (double x = std::ceil(x0 / step) * step; x <= x1; x += step) {
    const double px = map(x, 0.0).x();
    svg.line({px, top_}, {px, bottom}, grid);
    svg.text(px, bottom + 16.0, metres(x), 12.0, "middle");
  }
  for (double y = std::ceil(y0 / step) * step; y <= y1; y += step) {
    const double py = map(0.0, y).y();
    svg.line({left_, py}, {left_ + width_, py}, grid);
    svg.text(left_ - 6.0, py + 4.0, metres(y), 12.0, "end");
  }
  svg.text(left_ + 0.5 * width_, bottom + 34.0, "x [m]", 13.0, "middle");
  svg.text(left_ - 6.0, top_ - 6.0, "y [m]", 13.0, "end");
}

void PlotFrame::drawScaleBar(Svg& svg) const {
  const double bottom = top_ + height_;
  const double bar_m = niceStep(0.2 * width_ / scale_);
  const double bx = left_ + 20.0, by = bottom - 20.0, len = bar_m * scale_;
  svg.rect(bx - 6.0, by - 22.0, len + 12.0, 30.0, "#ffffff");
  Stroke bar{"#000000", 3.0, 1.0, ""};
  svg.line({bx, by}, {bx + len, by}, bar);
  svg.line({bx, by - 5.0}, {bx, by + 5.0}, Stroke{"#000000", 1.5, 1.0, ""});
  svg.line({bx + len, by - 5.0}, {bx + len, by + 5.0}, Stroke{"#000000", 1.5, 1.0, ""});
  svg.text(bx + 0.5 * len, by - 7.0, metres(bar_m) + " m", 12.0, "middle", true);
}

}  // namespace cosmo::report
