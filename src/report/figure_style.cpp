#include "figure_style.hpp"

#include <algorithm>

namespace cosmo::report {

std::string robotColor(std::size_t i) {
  static const char* kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b",
                                  "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#393b79"};
  return kColors[i % (sizeof kColors / sizeof kColors[0])];
}

Stroke closureStroke(const jrl::PoseFactor& f, const std::string& robot_color, double scale) {
  if (f.outlier) return Stroke{"#d62728", 0.9 * scale, 0.75, "4,3"};
  if (f.kind == jrl::FactorKind::InterRobotLoopClosure) return Stroke{"#333333", 0.6 * scale, 0.4, ""};
  return Stroke{robot_color, 0.6 * scale, 0.45, ""};
}

double drawLegend(Svg& svg, double x, double y, const std::vector<LegendRow>& rows) {
  for (const auto& row : rows) {
    if (row.dot) {
      svg.circle({x + 14.0, y - 4.0}, 2.5, row.stroke.color);
    } else {
      Stroke s = row.stroke;
      s.width = std::max(s.width, 1.6);
      s.opacity = std::max(s.opacity, 0.8);
      svg.line({x, y - 4.0}, {x + 28.0, y - 4.0}, s);
    }
    svg.text(x + 36.0, y, row.label, 13.0);
    y += 20.0;
  }
  return y;
}

std::size_t robotIndex(const std::vector<char>& robots, char robot) {
  const auto it = std::find(robots.begin(), robots.end(), robot);
  return it == robots.end() ? 0 : static_cast<std::size_t>(it - robots.begin());
}

}  // namespace cosmo::report
