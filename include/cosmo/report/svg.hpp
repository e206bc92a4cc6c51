#pragma once
// A minimal SVG document builder for the dataset figures: lines, polylines, circles, rectangles and text, with
// coordinates printed at 0.1 px so that the same drawing gives the same bytes.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cosmo::report {

struct Stroke {
  std::string color = "#000000";
  double width = 1.0;
  double opacity = 1.0;
  std::string dash;  ///< SVG stroke-dasharray, empty = solid
};

class Svg {
 public:
  Svg(double width, double height);

  /// Start a group whose lines share `stroke` (drawing many lines in one style stays compact).
  void beginGroup(const Stroke& stroke);
  void endGroup();
  /// Start a group clipped to the rectangle (ends with endGroup()).
  void beginClip(double x, double y, double w, double h);
  /// A line; inside a group with no stroke of its own.
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Stroke& stroke);
  void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke);
  void circle(const Eigen::Vector2d& c, double radius, const std::string& fill, double opacity = 1.0);
  void rect(double x, double y, double w, double h, const std::string& fill, const std::string& stroke = "none");
  /// anchor: "start", "middle" or "end"; text is escaped.
  void text(double x, double y, const std::string& text, double size, const std::string& anchor = "start",
            bool bold = false, const std::string& fill = "#000000");

  std::string str() const;

 private:
  std::string body_;
  double width_, height_;
  int clips_ = 0;
};

/// "1.5" style number with one decimal.
std::string num(double v);

}  // namespace cosmo::report
