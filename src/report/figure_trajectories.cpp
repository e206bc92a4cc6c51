// Fig. 1 style: reference trajectories, loop closures between ground-truth poses, metadata table.
#include <cstdio>
#include <stdexcept>

#include "cosmo/jrl/pose_graph.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/report/plot_frame.hpp"
#include "figure_style.hpp"

namespace cosmo::report {

namespace {

constexpr double kWidth = 1400.0, kHeight = 960.0;
constexpr double kPlotLeft = 70.0, kPlotTop = 50.0, kPlotSize = 860.0;
constexpr double kTableLeft = 980.0;

Bounds boundsOf(const jrl::PoseMap& poses) {
  Bounds b;
  for (const auto& [key, T] : poses) b.add(T.translation().x(), T.translation().y());
  return b;
}

void drawClosures(Svg& svg, const PlotFrame& frame, const jrl::PoseGraph& g, bool outliers) {
  for (const jrl::PoseFactor& f : g.factors) {
    if (!f.isLoopClosure() || f.outlier != outliers) continue;
    const auto a = g.groundtruth.find(f.key1), b = g.groundtruth.find(f.key2);
    if (a == g.groundtruth.end() || b == g.groundtruth.end()) continue;
    svg.line(frame.map(a->second.translation()), frame.map(b->second.translation()),
             closureStroke(f, robotColor(robotIndex(g.robots, f.robot))));
  }
}

void drawTrajectories(Svg& svg, const PlotFrame& frame, const jrl::PoseGraph& g, const jrl::PoseMap& poses,
                      double width) {
  for (std::size_t i = 0; i < g.robots.size(); ++i) {
    std::vector<Eigen::Vector2d> pts;
    for (jrl::Key k : g.ownKeys(g.robots[i])) {
      const auto it = poses.find(k);
      if (it != poses.end()) pts.push_back(frame.map(it->second.translation()));
    }
    svg.polyline(pts, Stroke{robotColor(i), width, 1.0, ""});
  }
}

std::string percent(std::size_t n, std::size_t outliers) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%zu (%.1f %% outliers)", n, n ? 100.0 * double(outliers) / double(n) : 0.0);
  return buf;
}

void drawTable(Svg& svg, const jrl::DatasetStats& s, const FigureOptions& options, double x, double y) {
  std::vector<std::pair<std::string, std::string>> rows;
  rows.emplace_back("name", s.name);
  if (!options.source.empty()) rows.emplace_back("source", options.source);
  std::string robots;
  for (char r : s.robots) robots += std::string(robots.empty() ? "" : " ") + r;
  rows.emplace_back("trials", std::to_string(s.robots.size()) + " (robots " + robots + ")");
  rows.emplace_back("duration", jrl::formatDuration(s.duration_s));
  char km[32];
  std::snprintf(km, sizeof km, "%.2f km", s.length_m / 1000.0);
  rows.emplace_back("length", km);
  rows.emplace_back("LC", percent(s.lc_count, s.lc_outliers));
  rows.emplace_back("IRLC", percent(s.irlc_count, s.irlc_outliers));
  if (!s.has_outlier_labels) rows.emplace_back("labels", "none in the file");
  const double row_h = 26.0, w = kWidth - x - 30.0;
  svg.rect(x, y, w, row_h * double(rows.size()) + 10.0, "#f7f7f7", "#999999");
  double ty = y + 24.0;
  for (const auto& [k, v] : rows) {
    svg.text(x + 12.0, ty, k, 14.0, "start", true);
    svg.text(x + 100.0, ty, v, 14.0);
    ty += row_h;
  }
}

}  // namespace

std::string trajectoriesSvg(const jrl::Dataset& dataset, const FigureOptions& options) {
  const jrl::PoseGraph g = jrl::poseGraph(dataset);
  if (g.groundtruth.empty()) throw std::runtime_error(dataset.name + ": no ground truth to draw");
  Svg svg(kWidth, kHeight);
  const PlotFrame frame(boundsOf(g.groundtruth), kPlotLeft, kPlotTop, kPlotSize, kPlotSize);
  frame.drawTitle(svg, dataset.name + ": reference trajectories and loop closures");
  frame.drawAxes(svg);
  drawClosures(svg, frame, g, false);
  drawTrajectories(svg, frame, g, g.groundtruth, 1.8);
  drawClosures(svg, frame, g, true);  // outliers on top
  frame.drawScaleBar(svg);

  drawTable(svg, jrl::computeStats(dataset), options, kTableLeft, kPlotTop);
  std::vector<LegendRow> legend;
  for (std::size_t i = 0; i < g.robots.size(); ++i)
    legend.push_back({Stroke{robotColor(i), 2.0, 1.0, ""}, std::string("robot ") + g.robots[i] + " (reference)"});
  jrl::PoseFactor intra, inter, outlier;
  intra.kind = jrl::FactorKind::LoopClosure;
  inter.kind = jrl::FactorKind::InterRobotLoopClosure;
  outlier.outlier = true;
  legend.push_back({closureStroke(intra, "#555555"), "intra-robot loop closure (robot's colour), inlier"});
  legend.push_back({closureStroke(inter, ""), "inter-robot loop closure, inlier"});
  legend.push_back({closureStroke(outlier, ""), "loop closure labelled outlier"});
  drawLegend(svg, kTableLeft, kPlotTop + 300.0, legend);
  return svg.str();
}

}  // namespace cosmo::report
