#include "cosmo/sim/world.hpp"

#include <algorithm>
#include <cmath>

namespace cosmo::sim {

World::World(Terrain terrain, std::vector<Primitive> primitives, PathNetwork network)
    : terrain_(std::move(terrain)), bvh_(std::move(primitives)), network_(std::move(network)) {}

bool World::intersect(const Ray& ray, double t_min, double t_max, Hit& hit) const {
  hit.t = t_max;
  // Ground first: downward rays then give the object search a short range limit.
  bool found = terrain_.intersect(ray, t_min, hit);
  found |= bvh_.intersect(ray, t_min, hit);
  return found;
}

double World::surfaceDistance(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d n = terrain_.normal(p.x(), p.y());
  double d = std::abs(p.z() - terrain_.height(p.x(), p.y())) * n.z();
  for (const auto& prim : bvh_.primitives()) d = std::min(d, prim.surfaceDistance(p));
  return d;
}

}  // namespace cosmo::sim
