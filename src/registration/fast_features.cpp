#include "cosmo/registration/fast_features.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "cosmo/registration/kdtree.hpp"

namespace cosmo {

namespace {

constexpr int kBins = 11;

/// atan2 within 2e-4 rad (odd minimax polynomial of atan on [0, 1] plus octant folding): the angle is only
/// binned into 11 bins, so libm's exact atan2f (a third of the SPFH time) is not needed. Deterministic.
inline float fastAtan2(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float mx = std::max(ax, ay), mn = std::min(ax, ay);
  if (mx == 0.f) return 0.f;
  const float a = mn / mx, s = a * a;
  float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
  if (ay > ax) r = 1.57079637f - r;
  if (x < 0.f) r = 3.14159274f - r;
  return y < 0.f ? -r : r;
}

/// PCL's pair feature (pcl::computePairFeatures): f1 = theta in [-pi, pi], f2 = alpha in [-1, 1],
/// f3 = phi in [-1, 1]; false for a degenerate pair.
inline bool pairFeature(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                        const Eigen::Vector3f& n2, float& f1, float& f2, float& f3) {
  Eigen::Vector3f dp = p2 - p1;
  const float d = dp.norm();
  if (d == 0.f) return false;
  dp /= d;
  const float a1 = n1.dot(dp), a2 = n2.dot(dp);
  Eigen::Vector3f u = n1, nb = n2;
  if (std::fabs(a1) < std::fabs(a2)) {  // acos(|a1|) > acos(|a2|): take the more parallel normal as the source
    u = n2, nb = n1, dp = -dp;
    f3 = -a2;
  } else {
    f3 = a1;
  }
  Eigen::Vector3f v = dp.cross(u);
  const float vn = v.norm();
  if (vn == 0.f) return false;
  v /= vn;
  const Eigen::Vector3f w = u.cross(v);
  f2 = v.dot(nb);
  f1 = fastAtan2(w.dot(nb), u.dot(nb));
  return true;
}

inline int bin(float x, float lo, float hi) {
  const int b = static_cast<int>(std::floor(kBins * (x - lo) / (hi - lo)));
  return b < 0 ? 0 : (b >= kBins ? kBins - 1 : b);
}

}  // namespace

FastFeatures computeFastFeatures(const std::vector<Eigen::Vector3f>& points, const FastFeatureParams& params) {
  FastFeatures out;
  const std::size_t n = points.size();
  if (n == 0) {
    out.features = FpfhMatrix(kFpfhDim, 0);
    return out;
  }
  const KdTree<3> tree(points.front().data(), n);
  const float rf = static_cast<float>(params.fpfh_radius);
  const float rf2 = rf * rf;
  const double spfh_r = params.spfh_radius > 0.0 ? params.spfh_radius : params.fpfh_radius;
  const float rs2 = static_cast<float>(spfh_r * spfh_r);
  const float rn2 = static_cast<float>(params.normal_radius * params.normal_radius);
  const float rsearch = static_cast<float>(std::max(spfh_r, params.normal_radius));
  // Neighbour lists (CSR) at max(normal, SPFH) radius.
  std::vector<std::uint32_t> offsets(n + 1, 0);
  std::vector<std::uint32_t> nbr;
  std::vector<float> nbr_d2;
  nbr.reserve(n * 48), nbr_d2.reserve(n * 48);
  std::vector<std::pair<std::uint32_t, float>> found;
  std::vector<Eigen::Vector3f> normals(n, Eigen::Vector3f::Zero());
  std::vector<unsigned char> valid(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    tree.radius(points[i].data(), rsearch, found);  // the tree's order: deterministic for the same cloud
    // Moments relative to the query point (small numbers: float accumulation is accurate enough).
    Eigen::Vector3f m1 = Eigen::Vector3f::Zero();
    float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    std::size_t k = 0;
    const Eigen::Vector3f pi = points[i];
    for (const auto& [j, d2] : found) {
      nbr.push_back(j);
      nbr_d2.push_back(d2);
      if (d2 <= rn2) {
        const Eigen::Vector3f q = points[j] - pi;
        m1 += q;
        xx += q.x() * q.x(), xy += q.x() * q.y(), xz += q.x() * q.z();
        yy += q.y() * q.y(), yz += q.y() * q.z(), zz += q.z() * q.z();
        ++k;
      }
    }
    offsets[i + 1] = static_cast<std::uint32_t>(nbr.size());
    if (k < std::max<std::size_t>(params.min_neighbors, 3)) continue;
    const Eigen::Vector3d mean = m1.cast<double>() / static_cast<double>(k);
    Eigen::Matrix3d cov;
    cov << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    cov = cov / static_cast<double>(k) - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    const Eigen::Vector3d ev = es.eigenvalues();  // ascending
    if (!(ev(2) > 0.0)) continue;
    const double linearity = (ev(2) - ev(1)) / ev(2);
    if (linearity > params.max_linearity) continue;
    Eigen::Vector3f nrm = es.eigenvectors().col(0).cast<float>();
    if (!nrm.allFinite()) continue;
    nrm.normalize();
    if (nrm.dot(-points[i]) < 0.f) nrm = -nrm;
    normals[i] = nrm;
    valid[i] = 1;
  }
  // SPFH of every valid point over its valid neighbours. PCL's pair feature is symmetric (swapping the two
  // points selects the same source normal and gives bit-identical values), so each unordered pair is computed
  // once and counted in both histograms.
  std::vector<float> spfh(n * kFpfhDim, 0.f);
  std::vector<int> spfh_count(n, 0);
  const float lo1 = -static_cast<float>(M_PI), hi1 = static_cast<float>(M_PI);
  for (std::size_t i = 0; i < n; ++i) {
    if (!valid[i]) continue;
    float* hi = &spfh[i * kFpfhDim];
    for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
      const std::uint32_t j = nbr[e];
      if (j <= i || !valid[j] || nbr_d2[e] > rs2) continue;
      float f1, f2, f3;
      if (!pairFeature(points[i], normals[i], points[j], normals[j], f1, f2, f3)) continue;
      const int b1 = bin(f1, lo1, hi1), b2 = kBins + bin(f2, -1.f, 1.f), b3 = 2 * kBins + bin(f3, -1.f, 1.f);
      float* hj = &spfh[j * kFpfhDim];
      ++hi[b1], ++hi[b2], ++hi[b3];
      ++hj[b1], ++hj[b2], ++hj[b3];
      ++spfh_count[i], ++spfh_count[j];
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (spfh_count[i] > 0) {
      const float s = 100.f / static_cast<float>(spfh_count[i]);
      for (int b = 0; b < kFpfhDim; ++b) spfh[i * kFpfhDim + b] *= s;
    }
  // Keypoints: the first valid point (in input order) of each keypoint voxel, or every valid point.
  std::vector<int> kept_index(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if (valid[i]) {
      kept_index[i] = static_cast<int>(out.kept.size());
      out.kept.push_back(static_cast<int>(i));
      out.normals.push_back(normals[i]);
    }
  if (params.keypoint_voxel > 0.0) {
    std::vector<std::pair<std::uint64_t, int>> keyed;
    const double inv = 1.0 / params.keypoint_voxel;
    for (const int i : out.kept) {
      const Eigen::Vector3f& p = points[static_cast<std::size_t>(i)];
      const auto key = [&](float x) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x * inv)) + (1 << 20)) & 0x1FFFFF; };
      keyed.emplace_back((key(p.x()) << 42) | (key(p.y()) << 21) | key(p.z()), kept_index[static_cast<std::size_t>(i)]);
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t b = 0; b < keyed.size(); ++b)
      if (b == 0 || keyed[b].first != keyed[b - 1].first) out.keypoints.push_back(keyed[b].second);
    std::sort(out.keypoints.begin(), out.keypoints.end());
  } else {
    out.keypoints.resize(out.kept.size());
    for (std::size_t c = 0; c < out.kept.size(); ++c) out.keypoints[c] = static_cast<int>(c);
  }
  // FPFH = own SPFH + distance-weighted mean of the neighbours' SPFH; sub-histograms normalised to 100.
  out.features = FpfhMatrix::Zero(kFpfhDim, static_cast<Eigen::Index>(out.keypoints.size()));
  Eigen::Matrix<float, kFpfhDim, 1> acc;
  for (std::size_t c = 0; c < out.keypoints.size(); ++c) {
    const auto i = static_cast<std::size_t>(out.kept[static_cast<std::size_t>(out.keypoints[c])]);
    acc.setZero();
    int k = 0;
    auto add = [&](std::uint32_t j, float d2) {
      if (j == i || !valid[j] || d2 <= 0.f || d2 > rf2) return;
      acc += Eigen::Map<const Eigen::Matrix<float, kFpfhDim, 1>>(&spfh[j * kFpfhDim]) / std::sqrt(d2);
      ++k;
    };
    if (rf <= rsearch) {
      for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) add(nbr[e], nbr_d2[e]);
    } else {
      tree.radius(points[i].data(), rf, found);
      for (const auto& [j, d2] : found) add(j, d2);
    }
    if (k > 0) acc /= static_cast<float>(k);
    acc += Eigen::Map<const Eigen::Matrix<float, kFpfhDim, 1>>(&spfh[i * kFpfhDim]);
    for (int s = 0; s < 3; ++s) {
      const float sum = acc.segment<kBins>(s * kBins).sum();
      if (sum > 0.f) acc.segment<kBins>(s * kBins) *= 100.f / sum;
    }
    out.features.col(static_cast<Eigen::Index>(c)) = acc;
  }
  return out;
}

}  // namespace cosmo
