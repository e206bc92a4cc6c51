#include "cosmo/registration/feature_cloud.hpp"

#include "cosmo/registration/fast_features.hpp"
#include "cosmo/registration/stage_observer.hpp"
#include "cosmo/common/voxel_grid.hpp"

namespace cosmo::registration {

FeatureCloud computeFeatureCloud(const Scan& scan, const RegistrationParams& params, StageObserver* observer) {
  FeatureCloud out;
  out.input_points = scan.size();
  std::vector<Eigen::Vector3f> down =
      voxelDownsample(scan.points, params.voxel_size, params.min_range, params.max_range);
  out.downsampled_points = down.size();
  notifyStage(observer, "downsample");
  if (params.fast_features) {
    FastFeatureParams fp;
    fp.normal_radius = params.normal_radius;
    fp.fpfh_radius = params.fpfh_radius;
    fp.spfh_radius = params.spfh_radius;
    fp.min_neighbors = params.min_normal_neighbors;
    fp.max_linearity = params.max_linearity;
    fp.keypoint_voxel = params.keypoint_voxel;
    FastFeatures f = computeFastFeatures(down, fp, observer);
    out.points.reserve(f.kept.size());
    for (const int i : f.kept) out.points.push_back(down[static_cast<std::size_t>(i)]);
    out.normals = std::move(f.normals);
    out.keypoints = std::move(f.keypoints);
    out.features = std::move(f.features);
    return out;
  }
  const PointNormals normals = estimateNormals(down, params.normal_radius, params.min_normal_neighbors);
  out.points.reserve(down.size());
  out.normals.reserve(down.size());
  for (std::size_t i = 0; i < down.size(); ++i) {
    if (!normals.valid[i]) continue;
    out.points.push_back(down[i]);
    out.normals.push_back(normals.normals[i]);
  }
  notifyStage(observer, "normals");
  out.features = computeFpfh(out.points, out.normals, params.fpfh_radius);
  out.keypoints.resize(out.points.size());
  for (std::size_t i = 0; i < out.points.size(); ++i) out.keypoints[i] = static_cast<int>(i);
  notifyStage(observer, "fpfh");
  return out;
}

}  // namespace cosmo::registration
