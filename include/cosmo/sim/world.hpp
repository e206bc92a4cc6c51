#pragma once
// The synthetic world a simulated LiDAR looks at: terrain + solid primitives in a BVH.
#include <memory>
#include <vector>

#include "cosmo/sim/bvh.hpp"
#include "cosmo/sim/path_network.hpp"
#include "cosmo/sim/terrain.hpp"

namespace cosmo::sim {

class World {
 public:
  World() = default;
  World(Terrain terrain, std::vector<Primitive> primitives, PathNetwork network = {});

  /// Nearest surface along the ray within (t_min, t_max); false when the ray hits nothing.
  bool intersect(const Ray& ray, double t_min, double t_max, Hit& hit) const;
  /// Distance from a point to the nearest surface (terrain: along its normal; brute force over primitives).
  double surfaceDistance(const Eigen::Vector3d& p) const;

  const Terrain& terrain() const { return terrain_; }
  const Bvh& objects() const { return bvh_; }
  const PathNetwork& network() const { return network_; }

 private:
  Terrain terrain_;
  Bvh bvh_;
  PathNetwork network_;
};

}  // namespace cosmo::sim
