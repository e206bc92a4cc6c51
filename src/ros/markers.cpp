#include "cosmo/ros/markers.hpp"

#include <algorithm>

#include "cosmo/comm/radio_status.hpp"

namespace cosmo::ros_glue {

namespace {

geometry_msgs::Point pointMsg(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

visualization_msgs::Marker marker(const std::string& frame, const ros::Time& stamp, const std::string& ns, int type) {
  visualization_msgs::Marker m;
  m.header.stamp = stamp;
  m.header.frame_id = frame;
  m.ns = ns;
  m.type = type;
  m.pose.orientation.w = 1.0;
  m.action = visualization_msgs::Marker::ADD;
  return m;
}

// Closures join keyframes a few metres apart: lifted above the trajectories so that they stay visible.
constexpr double kClosureLift = 1.5;

visualization_msgs::Marker closureMarker(const frontend::FrontendMap& map, const std::string& ns,
                                         const std::string& frame, const ros::Time& stamp) {
  visualization_msgs::Marker lcs = marker(frame, stamp, ns + "/loop_closures", visualization_msgs::Marker::LINE_LIST);
  lcs.scale.x = 0.4;
  lcs.color = colorMsg(1, 1, 1);
  for (const frontend::ClosureSegment& c : map.closures()) {
    const std_msgs::ColorRGBA col = closureLabelColor(c.label);
    for (const Eigen::Vector3d& p : {c.from, c.to}) {
      geometry_msgs::Point q = pointMsg(p);
      q.z += kClosureLift;
      lcs.points.push_back(q);
      lcs.colors.push_back(col);
    }
  }
  if (lcs.points.empty()) lcs.action = visualization_msgs::Marker::DELETE;
  return lcs;
}

}  // namespace

std_msgs::ColorRGBA colorMsg(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA robotColor(char robot) {
  static const float palette[][3] = {{0.2f, 0.6f, 1.0f}, {1.0f, 0.5f, 0.1f}, {0.7f, 0.3f, 0.9f},
                                     {0.1f, 0.8f, 0.7f}, {0.9f, 0.8f, 0.1f}, {0.9f, 0.3f, 0.5f}};
  const auto& c = palette[static_cast<unsigned>(robot - 'a') % 6];
  return colorMsg(c[0], c[1], c[2]);
}

std_msgs::ColorRGBA closureLabelColor(frontend::ClosureLabel label) {
  switch (label) {
    case frontend::ClosureLabel::Rejected: return colorMsg(0.9f, 0.1f, 0.1f, 0.5f);
    case frontend::ClosureLabel::Inlier: return colorMsg(0.1f, 0.9f, 0.2f);
    case frontend::ClosureLabel::Outlier: return colorMsg(1.0f, 0.6f, 0.0f);
    case frontend::ClosureLabel::Unlabelled: break;
  }
  return colorMsg(0.2f, 0.4f, 1.0f);
}

std_msgs::ColorRGBA throughputColor(double fraction) {
  const double f = std::clamp(fraction, 0.0, 1.0);
  return colorMsg(static_cast<float>(f < 0.5 ? 1.0 : 2.0 * (1.0 - f)), static_cast<float>(f < 0.5 ? 2.0 * f : 1.0),
                  0.0f);
}

visualization_msgs::MarkerArray frontendMarkers(const frontend::FrontendMap& map, char robot, const std::string& frame,
                                                const ros::Time& stamp) {
  const std::string ns(1, robot);
  visualization_msgs::Marker traj = marker(frame, stamp, ns + "/trajectory", visualization_msgs::Marker::LINE_STRIP);
  traj.scale.x = 0.3;
  traj.color = robotColor(robot);
  visualization_msgs::Marker kfs = marker(frame, stamp, ns + "/keyframes", visualization_msgs::Marker::SPHERE_LIST);
  kfs.scale.x = kfs.scale.y = kfs.scale.z = 0.8;
  kfs.color = robotColor(robot);
  for (const Eigen::Vector3d& p : map.trajectory()) {
    traj.points.push_back(pointMsg(p));
    kfs.points.push_back(pointMsg(p));
  }
  if (traj.points.size() < 2) {
    traj.points.clear();
    traj.action = visualization_msgs::Marker::DELETE;
  }
  visualization_msgs::MarkerArray array;
  array.markers = {traj, kfs, closureMarker(map, ns, frame, stamp)};
  return array;
}

visualization_msgs::MarkerArray linkMarkers(const comm::RadioSimulator& radio,
                                            const std::map<std::pair<char, char>, comm::ActiveCommunication>& links,
                                            double t, const std::string& frame, const ros::Time& stamp) {
  visualization_msgs::Marker m = marker(frame, stamp, "comm_links", visualization_msgs::Marker::LINE_LIST);
  m.id = 0;
  m.scale.x = 0.5;
  for (const auto& [pair, c] : links) {
    const std_msgs::ColorRGBA color = throughputColor(linkThroughputFraction(c, t, radio.params()));
    for (char r : {c.sender, c.receiver}) {
      m.points.push_back(pointMsg(radio.position(r)));
      m.colors.push_back(color);
    }
  }
  if (links.empty()) {
    m.type = 0;
    m.scale.x = 0.0;
    m.action = visualization_msgs::Marker::DELETE;
  } else {
    m.color = m.colors.front();
  }
  visualization_msgs::MarkerArray array;
  array.markers.push_back(m);
  return array;
}

}  // namespace cosmo::ros_glue
