// The ScanContext descriptor distance: column-wise cosine distance minimised over column shifts.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "cosmo/place_recognition/scan_context.hpp"

namespace cosmo::place_recognition {
namespace {

void checkComparable(const ScanContext& a, const ScanContext& b) {
  if (a.descriptor.rows() != b.descriptor.rows() || a.descriptor.cols() != b.descriptor.cols() ||
      a.descriptor.size() == 0) {
    throw std::invalid_argument("scanContextDistance: descriptors of different or empty size (" +
                                std::to_string(a.descriptor.rows()) + "x" + std::to_string(a.descriptor.cols()) +
                                " vs " + std::to_string(b.descriptor.rows()) + "x" +
                                std::to_string(b.descriptor.cols()) + ")");
  }
}

/// Columns scaled to unit length (empty columns stay zero) and the occupancy of each column.
Eigen::MatrixXf unitColumns(const Eigen::MatrixXf& d, std::vector<char>& occupied) {
  Eigen::MatrixXf u = d;
  occupied.assign(static_cast<std::size_t>(d.cols()), 0);
  for (Eigen::Index j = 0; j < d.cols(); ++j) {
    const float n = d.col(j).norm();
    if (n > 0.0f) {
      u.col(j) /= n;
      occupied[static_cast<std::size_t>(j)] = 1;
    }
  }
  return u;
}

double wrappedYaw(int shift, int sectors) {
  int s = shift;
  if (2 * s > sectors) s -= sectors;  // (-sectors/2, sectors/2]
  return 2.0 * M_PI * static_cast<double>(s) / static_cast<double>(sectors);
}

}  // namespace

int sectorKeyShift(const ScanContext& query, const ScanContext& candidate) {
  checkComparable(query, candidate);
  const int n = static_cast<int>(query.descriptor.cols());
  const Eigen::VectorXf qk =
      query.sector_key.size() == n ? query.sector_key : Eigen::VectorXf(query.descriptor.colwise().mean());
  const Eigen::VectorXf ck =
      candidate.sector_key.size() == n ? candidate.sector_key : Eigen::VectorXf(candidate.descriptor.colwise().mean());
  int best_shift = 0;
  float best = std::numeric_limits<float>::infinity();
  for (int s = 0; s < n; ++s) {
    float diff = 0.0f;
    for (int i = 0; i < n; ++i) diff += std::abs(qk[i] - ck[(i + s) % n]);
    if (diff < best) {
      best = diff;
      best_shift = s;
    }
  }
  return best_shift;
}

DescriptorMatch scanContextDistance(const ScanContext& query, const ScanContext& candidate,
                                    EmptyColumnPolicy empty_columns, int coarse_search_radius) {
  checkComparable(query, candidate);
  const int n = static_cast<int>(query.descriptor.cols());
  std::vector<char> q_occ, c_occ;
  const Eigen::MatrixXf qu = unitColumns(query.descriptor, q_occ);
  const Eigen::MatrixXf cu = unitColumns(candidate.descriptor, c_occ);
  // similarity(i, k) = cosine between query column i and candidate column k.
  const Eigen::MatrixXf similarity = qu.transpose() * cu;

  std::vector<int> shifts;
  if (coarse_search_radius < 0 || 2 * coarse_search_radius + 1 >= n) {
    shifts.resize(static_cast<std::size_t>(n));
    for (int s = 0; s < n; ++s) shifts[static_cast<std::size_t>(s)] = s;
  } else {
    const int centre = sectorKeyShift(query, candidate);
    for (int d = -coarse_search_radius; d <= coarse_search_radius; ++d) shifts.push_back(((centre + d) % n + n) % n);
  }

  // Unit columns make an empty column's cosine 0, so the sum over all pairs is the sum over occupied pairs;
  // the number of pairs that count is the occupied pairs (both) or the pairs with any occupied column.
  const bool penalize = empty_columns == EmptyColumnPolicy::kPenalizeOneSided;
  int q_count = 0, c_count = 0;
  for (int i = 0; i < n; ++i) {
    q_count += q_occ[static_cast<std::size_t>(i)];
    c_count += c_occ[static_cast<std::size_t>(i)];
  }
  DescriptorMatch best;
  best.distance = std::numeric_limits<double>::infinity();
  for (const int s : shifts) {
    float sum = 0.0f;
    int both = 0;
    for (int i = 0; i < n; ++i) {
      const int k = i + s < n ? i + s : i + s - n;
      sum += similarity(i, k);
      both += q_occ[static_cast<std::size_t>(i)] & c_occ[static_cast<std::size_t>(k)];
    }
    const int count = penalize ? q_count + c_count - both : both;
    const double distance = count > 0 ? std::min(1.0, std::max(0.0, 1.0 - static_cast<double>(sum) / count)) : 1.0;
    if (distance < best.distance) {
      best.distance = distance;
      best.shift = s;
    }
  }
  best.yaw = wrappedYaw(best.shift, n);
  return best;
}

DescriptorMatch scanContextDistance(const ScanContext& query, const ScanContext& candidate) {
  return scanContextDistance(query, candidate, EmptyColumnPolicy::kPenalizeOneSided, -1);
}

}  // namespace cosmo::place_recognition
