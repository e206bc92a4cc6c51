#include "cosmo/odometry/kd_tree.hpp"

#include <nanoflann.hpp>

namespace cosmo {

namespace {
/// nanoflann dataset adaptor over a flat x y z float array.
struct FlatCloud {
  const std::vector<float>* coords = nullptr;
  std::size_t kdtree_get_point_count() const { return coords->size() / 3; }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*coords)[3 * i + dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FlatCloud>, FlatCloud, 3,
                                                 std::uint32_t>;
}  // namespace

/// Points per leaf: larger leaves build faster (the tree is rebuilt every scan) at a slightly slower search.
constexpr std::size_t kLeafSize = 24;

struct KdTree3::Index {
  FlatCloud cloud;
  std::unique_ptr<Tree> tree;
};

KdTree3::KdTree3() = default;
KdTree3::~KdTree3() = default;
KdTree3::KdTree3(KdTree3&&) noexcept = default;
KdTree3& KdTree3::operator=(KdTree3&&) noexcept = default;

void KdTree3::build(const std::vector<Eigen::Vector3d>& points) {
  points_ = points;
  coords_.resize(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int d = 0; d < 3; ++d) coords_[3 * i + d] = static_cast<float>(points[i][d]);
  index_ = std::make_unique<Index>();
  index_->cloud.coords = &coords_;
  if (points.empty()) return;
  index_->tree = std::make_unique<Tree>(3, index_->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
  index_->tree->buildIndex();
}

void KdTree3::knn(const Eigen::Vector3d& query, int k, double max_dist, std::vector<std::size_t>& indices) const {
  indices.clear();
  if (!index_ || !index_->tree || k <= 0) return;
  const float q[3] = {static_cast<float>(query.x()), static_cast<float>(query.y()), static_cast<float>(query.z())};
  std::uint32_t idx[32];
  float d2[32];
  const int kk = std::min(k, 32);
  const std::size_t found = index_->tree->knnSearch(q, static_cast<std::size_t>(kk), idx, d2);
  const float max_d2 = static_cast<float>(max_dist * max_dist);
  for (std::size_t i = 0; i < found; ++i)
    if (d2[i] <= max_d2) indices.push_back(idx[i]);
}

}  // namespace cosmo
