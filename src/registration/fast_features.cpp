#include "cosmo/registration/fast_features.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "cosmo/registration/neighbour_pairs.hpp"
#include "cosmo/registration/stage_observer.hpp"

namespace cosmo {

namespace {

constexpr int kBins = 11;
constexpr int kBlock = 8;  ///< pairs per vectorised block of the pair-feature loop
using Lane = Eigen::Array<float, kBlock, 1>;
using LaneI = Eigen::Array<int, kBlock, 1>;

/// atan2 within 2e-4 rad (odd minimax polynomial of atan on [0, 1] plus octant folding), branch-free over a
/// block: the angle is only binned into 11 bins, so libm's exact atan2f is not needed. Deterministic.
inline Lane fastAtan2(const Lane& y, const Lane& x) {
  const Lane ax = x.abs(), ay = y.abs();
  const Lane mx = ax.max(ay), mn = ax.min(ay);
  const Lane a = (mx > 0.f).select(mn / mx.max(1e-30f), Lane::Zero());
  const Lane s = a * a;
  Lane r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
  r = (ay > ax).select(1.57079637f - r, r);
  r = (x < 0.f).select(3.14159274f - r, r);
  return (y < 0.f).select(-r, r);
}

/// Bin of x in [lo, hi] into kBins (PCL's floor(kBins (x - lo) / (hi - lo)), clamped); x - lo > -1 bin here,
/// so truncation equals floor after the clamp.
inline LaneI binOf(const Lane& x, float lo, float hi) {
  const LaneI b = (Lane::Constant(static_cast<float>(kBins)) * (x - lo) / (hi - lo)).cast<int>();
  return b.max(0).min(kBins - 1);
}

/// One block of PCL's pair feature (pcl::computePairFeatures) over structure-of-arrays input: the source
/// normal is the one more parallel to the connecting line; f1 = theta (bin over [-pi, pi]), f2 = alpha,
/// f3 = phi (over [-1, 1]). `ok` is false for degenerate pairs (coincident points, normal along the line).
struct PairBlock {
  Lane p1[3], n1[3], p2[3], n2[3];
  LaneI b1, b2, b3;
  Eigen::Array<bool, kBlock, 1> ok;
  __attribute__((flatten)) void compute() {
    Lane dp[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
    const Lane d = (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]).sqrt();
    const Lane inv_d = (d > 0.f).select(1.f / d.max(1e-30f), Lane::Zero());
    for (auto& c : dp) c *= inv_d;
    const Lane a1 = n1[0] * dp[0] + n1[1] * dp[1] + n1[2] * dp[2];
    const Lane a2 = n2[0] * dp[0] + n2[1] * dp[1] + n2[2] * dp[2];
    const auto swap = a1.abs() < a2.abs();
    Lane u[3], nb[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = swap.select(n2[k], n1[k]);
      nb[k] = swap.select(n1[k], n2[k]);
      dp[k] = swap.select(-dp[k], dp[k]);
    }
    const Lane f3 = swap.select(-a2, a1);
    Lane v[3] = {dp[1] * u[2] - dp[2] * u[1], dp[2] * u[0] - dp[0] * u[2], dp[0] * u[1] - dp[1] * u[0]};
    const Lane vn = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    const Lane inv_vn = (vn > 0.f).select(1.f / vn.max(1e-30f), Lane::Zero());
    for (auto& c : v) c *= inv_vn;
    const Lane w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const Lane f2 = v[0] * nb[0] + v[1] * nb[1] + v[2] * nb[2];
    const Lane f1 = fastAtan2(w[0] * nb[0] + w[1] * nb[1] + w[2] * nb[2], u[0] * nb[0] + u[1] * nb[1] + u[2] * nb[2]);
    ok = (d > 0.f) && (vn > 0.f);
    b1 = binOf(f1, -3.14159274f, 3.14159274f);
    b2 = binOf(f2, -1.f, 1.f) + kBins;
    b3 = binOf(f3, -1.f, 1.f) + 2 * kBins;
  }
};

}  // namespace

FastFeatures computeFastFeatures(const std::vector<Eigen::Vector3f>& points, const FastFeatureParams& params,
                                 StageObserver* observer) {
  FastFeatures out;
  const std::size_t n = points.size();
  if (n == 0) {
    out.features = FpfhMatrix(kFpfhDim, 0);
    return out;
  }
  const double spfh_r = params.spfh_radius > 0.0 ? params.spfh_radius : params.fpfh_radius;
  const float rf2 = static_cast<float>(params.fpfh_radius * params.fpfh_radius);
  const float rs2 = static_cast<float>(spfh_r * spfh_r);
  const float rn2 = static_cast<float>(params.normal_radius * params.normal_radius);
  const float rsearch = static_cast<float>(std::max({spfh_r, params.normal_radius, params.fpfh_radius}));
  // Every neighbour pair once, at the largest of the three radii.
  const NeighbourPairs pairs = findNeighbourPairs(points, rsearch);
  const std::size_t np = pairs.size();
  notifyStage(observer, "neighbours");

  // Normals: covariance moments relative to each point (small numbers: float accumulation is accurate
  // enough), accumulated per pair into both points (q and -q give the same second moments).
  std::vector<Eigen::Matrix<float, 9, 1>> mom(n, Eigen::Matrix<float, 9, 1>::Zero());  // m1 (3), xx xy xz yy yz zz, k
  for (std::size_t e = 0; e < np; ++e) {
    if (pairs.squared_distance[e] > rn2) continue;
    const std::uint32_t i = pairs.first[e], j = pairs.second[e];
    const Eigen::Vector3f q = points[j] - points[i];
    Eigen::Matrix<float, 9, 1> m;
    m << q.x(), q.y(), q.z(), q.x() * q.x(), q.x() * q.y(), q.x() * q.z(), q.y() * q.y(), q.y() * q.z(), q.z() * q.z();
    mom[i] += m;
    m.head<3>() = -m.head<3>();
    mom[j] += m;
  }
  std::vector<std::uint32_t> count(n, 1);  // the point itself
  for (std::size_t e = 0; e < np; ++e)
    if (pairs.squared_distance[e] <= rn2) ++count[pairs.first[e]], ++count[pairs.second[e]];
  std::vector<Eigen::Vector3f> normals(n, Eigen::Vector3f::Zero());
  std::vector<unsigned char> valid(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = count[i];
    if (k < std::max<std::size_t>(params.min_neighbors, 3)) continue;
    const Eigen::Matrix<float, 9, 1>& m = mom[i];
    const Eigen::Vector3d mean = m.head<3>().cast<double>() / static_cast<double>(k);
    Eigen::Matrix3d cov;
    cov << m(3), m(4), m(5), m(4), m(6), m(7), m(5), m(7), m(8);
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
  notifyStage(observer, "normals");

  // SPFH of every valid point over its valid neighbours within the SPFH radius. PCL's pair feature is
  // symmetric (swapping the two points selects the same source normal), so each pair is computed once and
  // counted in both histograms; the feature itself runs in blocks of kBlock pairs (vectorised).
  std::vector<float> spfh(n * kFpfhDim, 0.f);
  std::vector<int> spfh_count(n, 0);
  {
    std::vector<std::uint32_t> sel_i, sel_j;
    sel_i.reserve(np), sel_j.reserve(np);
    for (std::size_t e = 0; e < np; ++e) {
      const std::uint32_t i = pairs.first[e], j = pairs.second[e];
      if (pairs.squared_distance[e] <= rs2 && valid[i] && valid[j]) sel_i.push_back(i), sel_j.push_back(j);
    }
    PairBlock blk;
    for (std::size_t s = 0; s < sel_i.size(); s += kBlock) {
      const std::size_t len = std::min<std::size_t>(kBlock, sel_i.size() - s);
      for (std::size_t l = 0; l < kBlock; ++l) {
        const std::size_t e = s + std::min(l, len - 1);  // the tail repeats the last pair; not counted
        const Eigen::Vector3f &p1 = points[sel_i[e]], &p2 = points[sel_j[e]];
        const Eigen::Vector3f &n1 = normals[sel_i[e]], &n2 = normals[sel_j[e]];
        for (int k = 0; k < 3; ++k) {
          blk.p1[k](static_cast<Eigen::Index>(l)) = p1(k), blk.n1[k](static_cast<Eigen::Index>(l)) = n1(k);
          blk.p2[k](static_cast<Eigen::Index>(l)) = p2(k), blk.n2[k](static_cast<Eigen::Index>(l)) = n2(k);
        }
      }
      blk.compute();
      for (std::size_t l = 0; l < len; ++l) {
        const auto li = static_cast<Eigen::Index>(l);
        if (!blk.ok(li)) continue;
        float* hi = &spfh[sel_i[s + l] * kFpfhDim];
        float* hj = &spfh[sel_j[s + l] * kFpfhDim];
        ++hi[blk.b1(li)], ++hi[blk.b2(li)], ++hi[blk.b3(li)];
        ++hj[blk.b1(li)], ++hj[blk.b2(li)], ++hj[blk.b3(li)];
        ++spfh_count[sel_i[s + l]], ++spfh_count[sel_j[s + l]];
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (spfh_count[i] > 0) {
      const float s = 100.f / static_cast<float>(spfh_count[i]);
      for (int b = 0; b < kFpfhDim; ++b) spfh[i * kFpfhDim + b] *= s;
    }
  notifyStage(observer, "spfh");

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

  // FPFH = own SPFH + distance-weighted mean of the neighbours' SPFH (within fpfh_radius); sub-histograms
  // normalised to 100. The sums run over the pair list into the keypoints' columns.
  using Hist = Eigen::Matrix<float, kFpfhDim, 1>;
  std::vector<int> key_col(n, -1);
  for (std::size_t c = 0; c < out.keypoints.size(); ++c)
    key_col[static_cast<std::size_t>(out.kept[static_cast<std::size_t>(out.keypoints[c])])] = static_cast<int>(c);
  out.features = FpfhMatrix::Zero(kFpfhDim, static_cast<Eigen::Index>(out.keypoints.size()));
  std::vector<int> weight_count(out.keypoints.size(), 0);
  for (std::size_t e = 0; e < np; ++e) {
    const float d2 = pairs.squared_distance[e];
    if (d2 > rf2 || d2 <= 0.f) continue;
    const std::uint32_t i = pairs.first[e], j = pairs.second[e];
    if (!valid[i] || !valid[j] || (key_col[i] < 0 && key_col[j] < 0)) continue;
    const float w = 1.f / std::sqrt(d2);
    if (key_col[i] >= 0) {
      out.features.col(key_col[i]) += Eigen::Map<const Hist>(&spfh[j * kFpfhDim]) * w;
      ++weight_count[static_cast<std::size_t>(key_col[i])];
    }
    if (key_col[j] >= 0) {
      out.features.col(key_col[j]) += Eigen::Map<const Hist>(&spfh[i * kFpfhDim]) * w;
      ++weight_count[static_cast<std::size_t>(key_col[j])];
    }
  }
  for (std::size_t c = 0; c < out.keypoints.size(); ++c) {
    const auto i = static_cast<std::size_t>(out.kept[static_cast<std::size_t>(out.keypoints[c])]);
    auto acc = out.features.col(static_cast<Eigen::Index>(c));
    if (weight_count[c] > 0) acc /= static_cast<float>(weight_count[c]);
    acc += Eigen::Map<const Hist>(&spfh[i * kFpfhDim]);
    for (int s = 0; s < 3; ++s) {
      const float sum = acc.segment<kBins>(s * kBins).sum();
      if (sum > 0.f) acc.segment<kBins>(s * kBins) *= 100.f / sum;
    }
  }
  notifyStage(observer, "fpfh");
  return out;
}

}  // namespace cosmo
