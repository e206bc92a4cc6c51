#include "cosmo/registration/feature_cloud.hpp"

#include "cosmo/registration/stage_observer.hpp"
#include "cosmo/registration/voxel_downsample.hpp"

namespace cosmo {

FeatureCloud computeFeatureCloud(const Scan& scan, const RegistrationParams& params, StageObserver* observer) {
  FeatureCloud out;
  out.input_points = scan.size();
  std::vector<Eigen::Vector3f> down = voxelDownsample(scan.points, params.voxel_size, params.min_range, params.max_range);
  out.downsampled_points = down.size();
  notifyStage(observer, "downsample");
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
  notifyStage(observer, "fpfh");
  return out;
}

}  // namespace cosmo
