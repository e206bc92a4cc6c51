#pragma once
// Bounding-volume hierarchy over the world's primitives: median split on the longest centroid axis,
// flattened depth-first, nearest-first stack traversal with early exit.
#include <cstdint>
#include <vector>

#include "cosmo/sim/primitives.hpp"

namespace cosmo::sim {

class Bvh {
 public:
  Bvh() = default;
  /// Builds over `primitives` (reordered into leaf order).
  explicit Bvh(std::vector<Primitive> primitives, int max_leaf_size = 4);

  /// Nearest hit with t in (t_min, hit.t); `hit.t` holds the current limit on entry.
  bool intersect(const Ray& ray, double t_min, Hit& hit) const;
  const std::vector<Primitive>& primitives() const { return prims_; }
  std::size_t nodeCount() const { return nodes_.size(); }
  Aabb bounds() const;

 private:
  /// Node box in float (outward-rounded), half the memory traffic of doubles.
  struct Node {
    float lo[3], hi[3];
    std::uint32_t first = 0;  ///< leaf: first primitive; inner: index of the right child (left = this + 1)
    std::uint16_t count = 0;  ///< primitives in a leaf, 0 for an inner node
    std::uint8_t axis = 0;    ///< split axis of an inner node
  };
  std::uint32_t build(std::vector<std::uint32_t>& order, std::vector<Aabb>& boxes,
                      std::vector<Eigen::Vector3d>& centers, std::uint32_t begin, std::uint32_t end, int max_leaf);
  std::vector<Node> nodes_;
  std::vector<Primitive> prims_;
};

}  // namespace cosmo::sim
