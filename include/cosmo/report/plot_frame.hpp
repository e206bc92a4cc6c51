#pragma once
// A map panel of a figure: world x/y in metres drawn into a pixel rectangle with equal aspect (one scale for
// both axes, the data centred), y up; a frame with metre ticks on both axes and a scale bar.
#include <string>

#include <Eigen/Core>

#include "cosmo/report/svg.hpp"

namespace cosmo::report {

struct Bounds {
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;
  bool empty = true;
  void add(double x, double y);
};

class PlotFrame {
 public:
  /// `world` is padded by 3 %; the panel is the pixel rectangle (left, top, width, height).
  PlotFrame(const Bounds& world, double left, double top, double width, double height);

  /// Pixel position of the world point (x, y).
  Eigen::Vector2d map(double x, double y) const;
  template <typename V>
  Eigen::Vector2d map(const V& p) const {
    return map(p.x(), p.y());
  }
  double pixelsPerMetre() const { return scale_; }

  /// Frame, grid lines and tick labels in metres on both axes, axis titles (drawn before the data).
  void drawAxes(Svg& svg) const;
  /// A scale bar of a round length in the lower left, inside the frame (drawn after the data).
  void drawScaleBar(Svg& svg) const;
  /// Panel title above the frame.
  void drawTitle(Svg& svg, const std::string& title) const;

 private:
  double left_, top_, width_, height_;
  double scale_ = 1.0, cx_ = 0.0, cy_ = 0.0;  ///< pixels per metre, world centre
};

/// 1, 2 or 5 times a power of ten, the largest such step not above `raw`.
double niceStep(double raw);

}  // namespace cosmo::report
