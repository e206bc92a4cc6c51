#include "cosmo/report/svg.hpp"

#include <cmath>
#include <cstdio>

namespace cosmo::report {

std::string num(double v) {
  char buf[32];
  const double r = std::round(v * 10.0) / 10.0;
  std::snprintf(buf, sizeof buf, "%.1f", r == 0.0 ? 0.0 : r);  // no "-0.0"
  return buf;
}

namespace {

std::string fraction(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string strokeAttributes(const Stroke& s) {
  std::string a = "stroke=\"" + s.color + "\" stroke-width=\"" + fraction(s.width) + "\"";
  if (s.opacity < 1.0) a += " stroke-opacity=\"" + fraction(s.opacity) + "\"";
  if (!s.dash.empty()) a += " stroke-dasharray=\"" + s.dash + "\"";
  return a;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string xy(const Eigen::Vector2d& p) { return num(p.x()) + "," + num(p.y()); }

}  // namespace

Svg::Svg(double width, double height) : width_(width), height_(height) {}

void Svg::beginGroup(const Stroke& stroke) { body_ += "<g fill=\"none\" " + strokeAttributes(stroke) + ">\n"; }
void Svg::endGroup() { body_ += "</g>\n"; }

void Svg::beginClip(double x, double y, double w, double h) {
  const std::string id = "clip" + std::to_string(clips_++);
  body_ += "<clipPath id=\"" + id + "\"><rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) +
           "\" height=\"" + num(h) + "\"/></clipPath>\n<g clip-path=\"url(#" + id + ")\">\n";
}

void Svg::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  body_ += "<line x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) + "\" y2=\"" + num(b.y()) +
           "\"/>\n";
}

void Svg::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Stroke& stroke) {
  body_ += "<line x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) + "\" y2=\"" + num(b.y()) +
           "\" " + strokeAttributes(stroke) + "/>\n";
}

void Svg::polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  body_ += "<polyline fill=\"none\" stroke-linejoin=\"round\" " + strokeAttributes(stroke) + " points=\"";
  for (std::size_t i = 0; i < points.size(); ++i) body_ += (i ? " " : "") + xy(points[i]);
  body_ += "\"/>\n";
}

void Svg::circle(const Eigen::Vector2d& c, double radius, const std::string& fill, double opacity) {
  body_ +=
      "<circle cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" + num(radius) + "\" fill=\"" + fill + "\"";
  if (opacity < 1.0) body_ += " fill-opacity=\"" + fraction(opacity) + "\"";
  body_ += "/>\n";
}

void Svg::rect(double x, double y, double w, double h, const std::string& fill, const std::string& stroke) {
  body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
           "\" fill=\"" + fill + "\" stroke=\"" + stroke + "\"/>\n";
}

void Svg::text(double x, double y, const std::string& text, double size, const std::string& anchor, bool bold,
               const std::string& fill) {
  body_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\" text-anchor=\"" + anchor +
           "\" fill=\"" + fill + "\"" + (bold ? " font-weight=\"bold\"" : "") + ">" + escaped(text) + "</text>\n";
}

std::string Svg::str() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
         num(width_) + "\" height=\"" + num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " + num(height_) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"#ffffff\"/>\n" +
         body_ + "</svg>\n";
}

}  // namespace cosmo::report
