// Fig. 2 style: (a) odometry against the reference with keyframe dots, (b) the loop-closure measurements.
#include <stdexcept>

#include "cosmo/jrl/pose_graph.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/report/plot_frame.hpp"
#include "figure_style.hpp"

namespace cosmo::report {

namespace {

constexpr double kWidth = 1800.0, kHeight = 1030.0;
constexpr double kTop = 70.0, kSize = 800.0, kLeftA = 70.0, kLeftB = 970.0;

void addOwnPoses(Bounds& b, const jrl::PoseGraph& g, const jrl::PoseMap& poses) {
  for (const auto& [k, T] : poses)
    if (g.stamps.count(k)) b.add(T.translation().x(), T.translation().y());
}

std::vector<Eigen::Vector2d> pathOf(const PlotFrame& frame, const jrl::PoseGraph& g, char robot,
                                    const jrl::PoseMap& poses) {
  std::vector<Eigen::Vector2d> pts;
  for (jrl::Key k : g.ownKeys(robot)) {
    const auto it = poses.find(k);
    if (it != poses.end()) pts.push_back(frame.map(it->second.translation()));
  }
  return pts;
}

void drawOdometryPanel(Svg& svg, const jrl::PoseGraph& g) {
  Bounds b;
  addOwnPoses(b, g, g.groundtruth);
  addOwnPoses(b, g, g.initialization);
  const PlotFrame frame(b, kLeftA, kTop, kSize, kSize);
  frame.drawTitle(svg, "(a) odometry (initialization) vs reference, keyframes");
  frame.drawAxes(svg);
  for (std::size_t i = 0; i < g.robots.size(); ++i)  // reference in the robot's colour, light
    svg.polyline(pathOf(frame, g, g.robots[i], g.groundtruth), Stroke{robotColor(i), 3.0, 0.3, ""});
  for (std::size_t i = 0; i < g.robots.size(); ++i) {
    const auto pts = pathOf(frame, g, g.robots[i], g.initialization);
    svg.polyline(pts, Stroke{robotColor(i), 1.2, 1.0, ""});
    for (const auto& p : pts) svg.circle(p, 1.6, robotColor(i));
  }
  frame.drawScaleBar(svg);
}

void drawMeasurementPanel(Svg& svg, const jrl::PoseGraph& g) {
  Bounds b;
  addOwnPoses(b, g, g.groundtruth);
  const PlotFrame frame(b, kLeftB, kTop, kSize, kSize);
  frame.drawTitle(svg, "(b) loop closures from key1's reference to where they put key2");
  frame.drawAxes(svg);
  svg.beginClip(kLeftB, kTop, kSize, kSize);
  for (std::size_t i = 0; i < g.robots.size(); ++i)
    svg.polyline(pathOf(frame, g, g.robots[i], g.groundtruth), Stroke{"#c8c8c8", 1.6, 1.0, ""});
  for (int pass = 0; pass < 2; ++pass)  // inliers, then outliers on top
    for (const jrl::PoseFactor& f : g.factors) {
      if (!f.isLoopClosure() || f.outlier != (pass == 1)) continue;
      const auto a = g.groundtruth.find(f.key1);
      if (a == g.groundtruth.end()) continue;
      const cosmo::Pose3 claimed = a->second * f.measured;
      svg.line(frame.map(a->second.translation()), frame.map(claimed.translation()),
               closureStroke(f, robotColor(robotIndex(g.robots, f.robot)), 1.3));
    }
  svg.endGroup();
  frame.drawScaleBar(svg);
}

}  // namespace

std::string frontendSvg(const jrl::Dataset& dataset) {
  const jrl::PoseGraph g = jrl::poseGraph(dataset);
  if (g.groundtruth.empty()) throw std::runtime_error(dataset.name + ": no ground truth to draw");
  if (g.initialization.empty()) throw std::runtime_error(dataset.name + ": no initialization to draw");
  Svg svg(kWidth, kHeight);
  svg.text(kLeftA, 26.0, dataset.name + ": the front-end's measurements", 18.0, "start", true);
  drawOdometryPanel(svg, g);
  drawMeasurementPanel(svg, g);

  std::vector<LegendRow> left;
  for (std::size_t i = 0; i < g.robots.size(); ++i)
    left.push_back({Stroke{robotColor(i), 1.2, 1.0, ""},
                    std::string("robot ") + g.robots[i] + " odometry, a dot per keyframe; light: reference"});
  jrl::PoseFactor intra, inter, outlier;
  intra.kind = jrl::FactorKind::LoopClosure;
  inter.kind = jrl::FactorKind::InterRobotLoopClosure;
  outlier.outlier = true;
  const std::vector<LegendRow> right{{closureStroke(intra, "#555555"), "intra-robot inlier (owner's colour)"},
                                     {closureStroke(inter, ""), "inter-robot inlier"},
                                     {closureStroke(outlier, ""), "labelled outlier"}};
  const double legend_top = kTop + kSize + 58.0;
  // Two columns per panel keep up to 5 robots within the figure's height.
  const std::size_t half = (left.size() + 1) / 2;
  drawLegend(svg, kLeftA, legend_top, std::vector<LegendRow>(left.begin(), left.begin() + half));
  drawLegend(svg, kLeftA + 420.0, legend_top, std::vector<LegendRow>(left.begin() + half, left.end()));
  drawLegend(svg, kLeftB, legend_top, right);
  return svg.str();
}

}  // namespace cosmo::report
