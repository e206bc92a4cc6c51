#pragma once
// Shared look of the dataset figures: robot colours, loop-closure strokes, the legend.
#include <string>
#include <vector>

#include "cosmo/jrl/pose_graph.hpp"
#include "cosmo/report/svg.hpp"

namespace cosmo::report {

/// Colour of the i-th robot (no red: red marks outliers).
std::string robotColor(std::size_t i);
/// Stroke of a loop closure: intra-robot in `robot_color`, inter-robot grey; outliers red and dashed.
Stroke closureStroke(const jrl::PoseFactor& f, const std::string& robot_color, double scale = 1.0);
/// Legend rows (a swatch line and a label) from (x, y) down; returns the y below the last row.
struct LegendRow {
  Stroke stroke;
  std::string label;
  bool dot = false;  ///< a dot instead of a line
};
double drawLegend(Svg& svg, double x, double y, const std::vector<LegendRow>& rows);
/// Index of `robot` in `robots` (0 when absent).
std::size_t robotIndex(const std::vector<char>& robots, char robot);

}  // namespace cosmo::report
