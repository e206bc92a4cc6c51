#include "cosmo/odometry/kd_tree.hpp"

#include <algorithm>
#include <cmath>

namespace cosmo {

namespace {
/// Points per leaf: small leaves prune well for k = 5; the build is a few nth_element passes either way.
constexpr std::uint32_t kLeafSize = 12;
}  // namespace

void KnnResult::reset(int k, double max_dist) {
  k_ = std::clamp(k, 0, kMaxK);
  count_ = 0;
  max_d2_ = static_cast<float>(max_dist * max_dist);
}

void KnnResult::offer(float d2, std::uint32_t tree, std::uint32_t index) {
  if (k_ == 0) return;
  if (count_ < k_) {
    if (!(d2 <= max_d2_)) return;
    ++count_;
  } else if (!(d2 < d2_[k_ - 1])) {
    return;
  }
  // Insert after the entries with d2 <= this one (the last slot is free or the one dropped).
  int i = count_ - 1;
  while (i > 0 && d2_[i - 1] > d2) {
    d2_[i] = d2_[i - 1];
    tree_[i] = tree_[i - 1];
    index_[i] = index_[i - 1];
    --i;
  }
  d2_[i] = d2;
  tree_[i] = tree;
  index_[i] = index;
}

void KdTree3::build(std::vector<Eigen::Vector3d> points) {
  points_ = std::move(points);
  sorted_.clear();
  sorted_.reserve(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Eigen::Vector3d& p = points_[i];
    if (!p.allFinite()) continue;
    sorted_.push_back({{static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())},
                       static_cast<std::uint32_t>(i)});
  }
  nodes_.clear();
  if (sorted_.empty()) return;
  nodes_.reserve(4 * sorted_.size() / kLeafSize + 2);
  buildNode(0, static_cast<std::uint32_t>(sorted_.size()));
}

std::uint32_t KdTree3::buildNode(std::uint32_t begin, std::uint32_t end) {
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= kLeafSize) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  // Split the widest extent of this node's points at their median.
  float lo0 = sorted_[begin].c[0], lo1 = sorted_[begin].c[1], lo2 = sorted_[begin].c[2];
  float hi0 = lo0, hi1 = lo1, hi2 = lo2;  // scalars: kept in registers (an array was reloaded every point)
  for (std::uint32_t i = begin + 1; i < end; ++i) {
    const float* c = sorted_[i].c;
    lo0 = std::min(lo0, c[0]), hi0 = std::max(hi0, c[0]);
    lo1 = std::min(lo1, c[1]), hi1 = std::max(hi1, c[1]);
    lo2 = std::min(lo2, c[2]), hi2 = std::max(hi2, c[2]);
  }
  const float extent[3] = {hi0 - lo0, hi1 - lo1, hi2 - lo2};
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (extent[a] > extent[axis]) axis = a;
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(sorted_.begin() + begin, sorted_.begin() + mid, sorted_.begin() + end,
                   [axis](const SortedPoint& a, const SortedPoint& b) { return a.c[axis] < b.c[axis]; });
  const float split = sorted_[mid].c[axis];
  buildNode(begin, mid);  // left: coordinates <= split
  const std::uint32_t right = buildNode(mid, end);  // right: coordinates >= split
  nodes_[id].axis = axis;
  nodes_[id].split = split;
  nodes_[id].right = right;
  return id;
}

void KdTree3::searchNode(std::uint32_t n, const float q[3], float offset[3], float min_d2, KnnResult& result,
                         std::uint32_t tree) const {
  const Node& node = nodes_[n];
  if (node.axis < 0) {
    for (std::uint32_t i = node.begin; i < node.end; ++i) {
      const SortedPoint& p = sorted_[i];
      const float dx = q[0] - p.c[0], dy = q[1] - p.c[1], dz = q[2] - p.c[2];
      float d2 = 0.0f;
      d2 += dx * dx;
      d2 += dy * dy;
      d2 += dz * dz;
      if (d2 <= result.bound()) result.offer(d2, tree, p.index);
    }
    return;
  }
  // The far child's cell is at least |diff| away along the split axis: its squared distance lower bound is
  // min_d2 with this axis' term replaced (Arya & Mount's incremental distance).
  const int a = node.axis;
  const float diff = q[a] - node.split;
  const std::uint32_t near = diff < 0.0f ? n + 1 : node.right;
  const std::uint32_t far = diff < 0.0f ? node.right : n + 1;
  searchNode(near, q, offset, min_d2, result, tree);
  const float old_offset = offset[a];
  const float far_d2 = min_d2 - old_offset * old_offset + diff * diff;
  if (far_d2 <= result.bound()) {
    offset[a] = diff;
    searchNode(far, q, offset, far_d2, result, tree);
    offset[a] = old_offset;
  }
}

void KdTree3::search(const Eigen::Vector3d& query, KnnResult& result, std::uint32_t tree) const {
  if (nodes_.empty()) return;
  const float q[3] = {static_cast<float>(query.x()), static_cast<float>(query.y()), static_cast<float>(query.z())};
  float offset[3] = {0.0f, 0.0f, 0.0f};
  searchNode(0, q, offset, 0.0f, result, tree);
}

void KdTree3::knn(const Eigen::Vector3d& query, int k, double max_dist, std::vector<std::size_t>& indices) const {
  indices.clear();
  KnnResult result;
  result.reset(k, max_dist);
  search(query, result, 0);
  for (int i = 0; i < result.size(); ++i) indices.push_back(result.index(i));
}

}  // namespace cosmo
