// The only translation unit with PCL feature templates (NormalEstimation, FPFHEstimation, search::KdTree).
#include "cosmo/registration/point_features.hpp"

#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>

namespace cosmo::registration {

namespace {
pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const std::vector<Eigen::Vector3f>& points) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) (*cloud)[i].getVector3fMap() = points[i];
  cloud->width = static_cast<std::uint32_t>(points.size());
  cloud->height = 1;
  cloud->is_dense = true;
  return cloud;
}
}  // namespace

PointNormals estimateNormals(const std::vector<Eigen::Vector3f>& points, double radius, std::size_t min_neighbors) {
  PointNormals out;
  out.normals.assign(points.size(), Eigen::Vector3f::Zero());
  out.valid.assign(points.size(), false);
  if (points.empty()) return out;
  const auto cloud = toPcl(points);
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  tree->setInputCloud(cloud);
  std::vector<int> idx;
  std::vector<float> d2;
  for (std::size_t i = 0; i < points.size(); ++i) {
    idx.clear();
    const int k = tree->radiusSearch(static_cast<int>(i), radius, idx, d2);
    if (k < static_cast<int>(std::max<std::size_t>(min_neighbors, 3))) continue;
    Eigen::Vector4f plane;
    float curvature = 0.f;
    if (!pcl::computePointNormal(*cloud, idx, plane, curvature)) continue;
    Eigen::Vector3f n = plane.head<3>();
    if (!n.allFinite() || n.squaredNorm() < 1e-12f) continue;
    n.normalize();
    if (n.dot(-points[i]) < 0.f) n = -n;  // orient towards the sensor at the origin
    out.normals[i] = n;
    out.valid[i] = true;
  }
  return out;
}

FpfhMatrix computeFpfh(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                       double radius) {
  FpfhMatrix out = FpfhMatrix::Zero(kFpfhDim, static_cast<Eigen::Index>(points.size()));
  if (points.empty()) return out;
  const auto cloud = toPcl(points);
  auto cloud_normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  cloud_normals->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    (*cloud_normals)[i].getNormalVector3fMap() = normals[i];
    (*cloud_normals)[i].curvature = 0.f;
  }
  pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
  fpfh.setInputCloud(cloud);
  fpfh.setInputNormals(cloud_normals);
  fpfh.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  fpfh.setRadiusSearch(radius);
  pcl::PointCloud<pcl::FPFHSignature33> features;
  fpfh.compute(features);
  for (std::size_t i = 0; i < features.size(); ++i) {
    bool finite = true;
    for (int b = 0; b < kFpfhDim; ++b) finite = finite && std::isfinite(features[i].histogram[b]);
    if (!finite) continue;
    for (int b = 0; b < kFpfhDim; ++b) out(b, static_cast<Eigen::Index>(i)) = features[i].histogram[b];
  }
  return out;
}

}  // namespace cosmo::registration
