#include "cosmo/registration/fast_features.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/StdVector>
#include <algorithm>
#include <cmath>

#include "cosmo/common/voxel_key.hpp"
#include "cosmo/common/radix_sort.hpp"
#include "cosmo/registration/float4.hpp"
#include "cosmo/registration/neighbour_pairs.hpp"
#include "cosmo/registration/stage_observer.hpp"

namespace cosmo::registration {

namespace {

constexpr int kBins = 11;
constexpr int kBlock = 4;         ///< pairs per vector step of the pair-feature loop (one Float4)
constexpr std::size_t kRow = 36;  ///< histogram row stride: 33 bins padded to a multiple of 4 floats

/// acc[0..kRow) += w row[0..kRow) (both 16-byte aligned).
inline void addScaledRow(float* acc, const float* row, float w) {
  const Float4 ww(w);
  for (std::size_t b = 0; b < kRow; b += 4) (Float4::load(acc + b) + Float4::load(row + b) * ww).store(acc + b);
}

/// atan2 within 2e-4 rad (odd minimax polynomial of atan on [0, 1] plus octant folding), branch-free: the
/// angle is only binned into 11 bins, so libm's exact atan2f is not needed. Deterministic.
inline Float4 fastAtan2(Float4 y, Float4 x) {
  const Float4 ax = abs(x), ay = abs(y);
  const Float4 mx = max(ax, ay), mn = min(ax, ay);
  const Float4 a = mn / max(mx, Float4(1e-30f));  // 0 when both are 0
  const Float4 s = a * a;
  Float4 r = ((Float4(-0.0464964749f) * s + Float4(0.15931422f)) * s - Float4(0.327622764f)) * s * a + a;
  r = select(ay > ax, Float4(1.57079637f) - r, r);
  r = select(x < Float4(0.f), Float4(3.14159274f) - r, r);
  return select(y < Float4(0.f), -r, r);
}

/// Bin of x in [lo, hi] into kBins: PCL's floor(kBins (x - lo) / (hi - lo)) clamped to [0, kBins - 1], with
/// the division as a multiplication by kBins / (hi - lo); clamped before the truncation (NaN -> bin 0).
inline void storeBin(Float4 x, float lo, float hi, int offset, std::int32_t* out) {
  const Float4 v = (x - Float4(lo)) * Float4(static_cast<float>(kBins) / (hi - lo));
  const Float4 clamped = max(min(v, Float4(static_cast<float>(kBins - 1))), Float4(0.f));
  (clamped + Float4(static_cast<float>(offset))).storeTruncated(out);
}

/// PCL's pair feature (pcl::computePairFeatures) for kBlock pairs, each pair's p1, n1, p2, n2 as rows
/// [x y z 0] of 8 floats [p n] per point (`pn`; the pairs' point indices i[0..4), j[0..4)); writes the bins of
/// f1 = theta (over [-pi, pi]), f2 = alpha and f3 = phi (over [-1, 1]), offset to the 33-bin layout, and
/// ok = 0 for degenerate pairs (coincident points, source normal along the line).
/// PCL's Darboux frame, with d = (p2 - p1) / |p2 - p1|, a1 = n1.d, a2 = n2.d: the source is the normal more
/// parallel to d (u = n1, nb = n2, a_s = a1, a_t = a2, phi = a1; or u = n2, nb = n1, d -> -d, a_s = -a2,
/// a_t = -a1, phi = -a2), v = d x u / |d x u|, w = u x v. In closed form, with c = n1.n2 and |d x u| =
/// sqrt(1 - a_s^2): alpha = v.nb = d.(n1 x n2) / |d x u| (the same for both choices), and theta =
/// atan2(w.nb, u.nb) = atan2(a_t - a_s c, c |d x u|).
__attribute__((always_inline)) inline void pairFeatureBlock(const float* pn, const std::uint32_t* i,
                                                            const std::uint32_t* j, std::int32_t* b1, std::int32_t* b2,
                                                            std::int32_t* b3, std::int32_t* ok) {
  // Four rows [x y z 0] gathered and transposed into x, y, z lanes (the fourth row is the zero column).
  auto lanes = [&](const std::uint32_t* idx, std::size_t offset, Float4& x, Float4& y, Float4& z) {
    x = Float4::load(pn + 8 * static_cast<std::size_t>(idx[0]) + offset);
    y = Float4::load(pn + 8 * static_cast<std::size_t>(idx[1]) + offset);
    z = Float4::load(pn + 8 * static_cast<std::size_t>(idx[2]) + offset);
    Float4 w = Float4::load(pn + 8 * static_cast<std::size_t>(idx[3]) + offset);
    transpose4(x, y, z, w);
  };
  Float4 p1x, p1y, p1z, n1x, n1y, n1z, p2x, p2y, p2z, n2x, n2y, n2z;
  lanes(i, 0, p1x, p1y, p1z);
  lanes(i, 4, n1x, n1y, n1z);
  lanes(j, 0, p2x, p2y, p2z);
  lanes(j, 4, n2x, n2y, n2z);
  const Float4 dx = p2x - p1x, dy = p2y - p1y, dz = p2z - p1z;
  const Float4 zero(0.f), tiny(1e-30f);
  const Float4 d = sqrt(dx * dx + dy * dy + dz * dz);
  const Float4 inv_d = select(d > zero, Float4(1.f) / max(d, tiny), zero);
  const Float4 a1 = (n1x * dx + n1y * dy + n1z * dz) * inv_d;
  const Float4 a2 = (n2x * dx + n2y * dy + n2z * dz) * inv_d;
  const Float4 c = n1x * n2x + n1y * n2y + n1z * n2z;
  const Float4 triple =
      (dx * (n1y * n2z - n1z * n2y) + dy * (n1z * n2x - n1x * n2z) + dz * (n1x * n2y - n1y * n2x)) * inv_d;
  const Float4 swap = abs(a1) < abs(a2);
  const Float4 a_s = select(swap, -a2, a1), a_t = select(swap, -a1, a2);
  const Float4 vn2 = Float4(1.f) - a_s * a_s;
  const Float4 vn = sqrt(max(vn2, zero));
  const Float4 f2 = triple / max(vn, tiny);
  const Float4 f1 = fastAtan2(a_t - a_s * c, c * vn);
  maskAnd(d > zero, vn2 > zero).storeMask(ok);
  storeBin(f1, -3.14159274f, 3.14159274f, 0, b1);
  storeBin(f2, -1.f, 1.f, kBins, b2);
  storeBin(a_s, -1.f, 1.f, 2 * kBins, b3);
}

using AlignedFloats = std::vector<float, Eigen::aligned_allocator<float>>;

/// The input's neighbour pairs at the largest radius, numbered by position in the grid's cell order: the
/// per-point work runs on the points in that order (a cell's points contiguous in memory) and only the outputs go
/// back to input order. The pairs come in the same sequence as with input numbering, so every per-point sum
/// accumulates in the same order (same bits).
struct OrderedCloud {
  NeighbourPairs pairs;
  std::vector<Eigen::Vector3f> points;  ///< by position
  std::vector<int> position;            ///< by input index: its position, -1 without one
};

OrderedCloud orderCloud(const std::vector<Eigen::Vector3f>& input, float radius) {
  OrderedCloud c;
  std::vector<std::uint32_t> order;
  c.pairs = findNeighbourPairs(input, radius, order);
  const std::size_t n = order.size();
  c.points.resize(n);
  for (std::size_t s = 0; s < n; ++s) c.points[s] = input[order[s]];
  c.position.assign(input.size(), -1);
  for (std::size_t s = 0; s < n; ++s) c.position[order[s]] = static_cast<int>(s);
  return c;
}

/// Rows of kMoments floats, three Float4: [x y z 0 | xx xy xz yy | yz zz 0 0].
constexpr std::size_t kMoments = 12;

/// Covariance moments relative to each point (small numbers: float accumulation is accurate enough),
/// accumulated per pair within `rn2` into both points (q and -q give the same second moments); `count`: the
/// points summed, the point itself included. In chunks: the pairs within the radius listed first without a
/// branch (the test is data-dependent and would mispredict), in pair order, so the moments accumulate in the same
/// order as a direct loop.
void accumulateMoments(const OrderedCloud& c, float rn2, AlignedFloats& mom, std::vector<std::uint32_t>& count) {
  const std::size_t n = c.points.size(), np = c.pairs.size();
  mom.assign(n * kMoments, 0.f);
  count.assign(n, 1);
  constexpr std::size_t kSelect = 512;
  std::uint32_t selected[kSelect];
  for (std::size_t e0 = 0; e0 < np; e0 += kSelect) {
    const std::size_t e1 = std::min(np, e0 + kSelect);
    std::size_t ns = 0;
    for (std::size_t e = e0; e < e1; ++e) {
      selected[ns] = static_cast<std::uint32_t>(e);
      ns += c.pairs[e].squared_distance > rn2 ? 0 : 1;
    }
    for (std::size_t s = 0; s < ns; ++s) {
      const std::size_t e = selected[s];
      const std::uint32_t i = c.pairs[e].first, j = c.pairs[e].second;
      ++count[i], ++count[j];
      const Eigen::Vector3f q = c.points[j] - c.points[i];
      const float x = q.x(), y = q.y(), z = q.z();
      const Float4 first(x, y, z, 0.f);
      const Float4 second = Float4(x, x, x, y) * Float4(x, y, z, y);
      const Float4 third = Float4(y, z, 0.f, 0.f) * Float4(z, z, 0.f, 0.f);
      float* mi = &mom[i * kMoments];
      float* mj = &mom[j * kMoments];
      (Float4::load(mi) + first).store(mi);
      (Float4::load(mi + 4) + second).store(mi + 4);
      (Float4::load(mi + 8) + third).store(mi + 8);
      (Float4::load(mj) + -first).store(mj);
      (Float4::load(mj + 4) + second).store(mj + 4);
      (Float4::load(mj + 8) + third).store(mj + 8);
    }
  }
}

/// Each point's normal (the float eigensolver's smallest eigenvector, oriented towards the origin), valid with
/// enough neighbours and a covariance that is not too linear.
void normalsFromMoments(const std::vector<Eigen::Vector3f>& points, const AlignedFloats& mom,
                        const std::vector<std::uint32_t>& count, const FastFeatureParams& params,
                        std::vector<Eigen::Vector3f>& normals, std::vector<unsigned char>& valid) {
  const std::size_t n = points.size();
  normals.assign(n, Eigen::Vector3f::Zero());
  valid.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = count[i];
    if (k < std::max<std::size_t>(params.min_neighbors, 3)) continue;
    const float* m = &mom[i * kMoments];
    const Eigen::Vector3f mean = Eigen::Vector3f(m[0], m[1], m[2]) / static_cast<float>(k);
    Eigen::Matrix3f cov;
    cov << m[4], m[5], m[6], m[5], m[7], m[8], m[6], m[8], m[9];
    cov = cov / static_cast<float>(k) - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> es;
    es.computeDirect(cov);
    const Eigen::Vector3f ev = es.eigenvalues();  // ascending
    if (!(ev(2) > 0.f)) continue;
    const float linearity = (ev(2) - ev(1)) / ev(2);
    if (linearity > params.max_linearity) continue;
    Eigen::Vector3f nrm = es.eigenvectors().col(0);
    if (!nrm.allFinite()) continue;
    nrm.normalize();
    if (nrm.dot(-points[i]) < 0.f) nrm = -nrm;
    normals[i] = nrm;
    valid[i] = 1;
  }
}

/// Integer SPFH bin counts (rows of kRow) of every valid point over its valid neighbours within `rs2`. PCL's pair
/// feature is symmetric (swapping the two points selects the same source normal), so each pair is computed once
/// and counted in both histograms. Chunks of up to kChunk selected pairs (selected without a branch), features
/// in blocks of kBlock gathered from packed [point normal] rows, then the histogram increments.
std::vector<std::uint16_t> countSpfhBins(const OrderedCloud& c, const std::vector<Eigen::Vector3f>& normals,
                                         const std::vector<unsigned char>& valid, float rs2) {
  const std::size_t n = c.points.size(), np = c.pairs.size();
  std::vector<std::uint16_t> bins(n * kRow, 0);
  AlignedFloats pn(n * 8, 0.f);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) pn[8 * i + k] = c.points[i][k], pn[8 * i + 4 + k] = normals[i][k];
  constexpr std::size_t kChunk = 256;
  alignas(16) std::int32_t b1[kChunk], b2[kChunk], b3[kChunk], ok[kChunk];
  std::uint32_t ci[kChunk + kBlock], cj[kChunk + kBlock];
  std::size_t e = 0;
  while (e < np) {
    std::size_t len = 0;
    for (; e < np && len < kChunk; ++e) {
      const std::uint32_t i = c.pairs[e].first, j = c.pairs[e].second;
      ci[len] = i, cj[len] = j;
      len += (c.pairs[e].squared_distance <= rs2) & (valid[i] != 0) & (valid[j] != 0) ? 1 : 0;
    }
    if (len == 0) break;
    const std::size_t padded = (len + kBlock - 1) / kBlock * kBlock;
    for (std::size_t l = len; l < padded; ++l) ci[l] = ci[len - 1], cj[l] = cj[len - 1];  // not counted
    for (std::size_t l = 0; l < padded; l += kBlock)
      pairFeatureBlock(pn.data(), ci + l, cj + l, b1 + l, b2 + l, b3 + l, ok + l);
    for (std::size_t l = 0; l < len; ++l) {
      if (!ok[l]) continue;
      std::uint16_t* hi = &bins[ci[l] * kRow];
      std::uint16_t* hj = &bins[cj[l] * kRow];
      ++hi[b1[l]], ++hi[b2[l]], ++hi[b3[l]];
      ++hj[b1[l]], ++hj[b2[l]], ++hj[b3[l]];
    }
  }
  return bins;
}

/// The SPFH rows (kRow floats, 16-byte aligned so that the FPFH sums run on Float4): the bin counts scaled so
/// that each sub-histogram sums to 100.
AlignedFloats scaleSpfh(const std::vector<std::uint16_t>& bins, std::size_t n) {
  AlignedFloats spfh(n * kRow, 0.f);
  for (std::size_t i = 0; i < n; ++i) {
    // Pairs counted in the point's SPFH = the sum of any one sub-histogram (each pair adds one to each).
    int pairs_counted = 0;
    for (int b = 0; b < kBins; ++b) pairs_counted += bins[i * kRow + b];
    const float s = pairs_counted > 0 ? 100.f / static_cast<float>(pairs_counted) : 1.f;
    for (int b = 0; b < kFpfhDim; ++b) spfh[i * kRow + b] = static_cast<float>(bins[i * kRow + b]) * s;
  }
  return spfh;
}

/// out.kept / out.normals: the valid points in input order; out.keypoints: the first valid point (in input order)
/// of each keypoint voxel, or every valid point.
void selectKeypoints(const std::vector<Eigen::Vector3f>& input, const std::vector<int>& position,
                     const std::vector<Eigen::Vector3f>& normals, const std::vector<unsigned char>& valid,
                     double keypoint_voxel, FastFeatures& out) {
  std::vector<int> kept_index(normals.size(), -1);  // by position
  for (std::size_t i = 0; i < input.size(); ++i) {
    const int s = position[i];
    if (s >= 0 && valid[static_cast<std::size_t>(s)]) {
      kept_index[static_cast<std::size_t>(s)] = static_cast<int>(out.kept.size());
      out.kept.push_back(static_cast<int>(i));
      out.normals.push_back(normals[static_cast<std::size_t>(s)]);
    }
  }
  if (keypoint_voxel > 0.0) {
    std::vector<std::pair<std::uint64_t, int>> keyed;
    const double inv = 1.0 / keypoint_voxel;
    for (const int i : out.kept) {
      const Eigen::Vector3f& p = input[static_cast<std::size_t>(i)];
      keyed.emplace_back(packVoxelKey(voxelCoord(p.x(), inv), voxelCoord(p.y(), inv), voxelCoord(p.z(), inv)),
                         kept_index[static_cast<std::size_t>(position[static_cast<std::size_t>(i)])]);
    }
    radixSortByKey(keyed);  // = std::sort: the input is in kept order
    for (std::size_t b = 0; b < keyed.size(); ++b)
      if (b == 0 || keyed[b].first != keyed[b - 1].first) out.keypoints.push_back(keyed[b].second);
    std::sort(out.keypoints.begin(), out.keypoints.end());
  } else {
    out.keypoints.resize(out.kept.size());
    for (std::size_t c = 0; c < out.kept.size(); ++c) out.keypoints[c] = static_cast<int>(c);
  }
}

/// Position of keypoint c.
std::size_t keypointPosition(const FastFeatures& out, const std::vector<int>& position, std::size_t c) {
  return static_cast<std::size_t>(
      position[static_cast<std::size_t>(out.kept[static_cast<std::size_t>(out.keypoints[c])])]);
}

/// The neighbours' SPFH summed with weight 1 / |p - q| (within `rf2`) into the keypoints' rows (`sums`), and
/// their number (`weight_count`). The (keypoint column, neighbour row, squared distance) terms are listed in pair
/// order (for a pair: the first point's term, then the second's) without data-dependent branches, then summed
/// (the weight computed only for the listed terms): each column receives the same terms in the same order as a
/// direct loop over the pairs.
void sumNeighbourSpfh(const NeighbourPairs& pairs, const std::vector<int>& key_col,
                      const std::vector<unsigned char>& valid, const AlignedFloats& spfh, float rf2,
                      AlignedFloats& sums, std::vector<int>& weight_count) {
  const std::size_t np = pairs.size();
  constexpr std::size_t kChunk = 256;
  std::uint32_t term_col[2 * kChunk], term_row[2 * kChunk];
  float term_d2[2 * kChunk];
  for (std::size_t e0 = 0; e0 < np; e0 += kChunk) {
    const std::size_t e1 = std::min(np, e0 + kChunk);
    std::size_t nt = 0;
    for (std::size_t e = e0; e < e1; ++e) {
      const float d2 = pairs[e].squared_distance;
      const std::uint32_t i = pairs[e].first, j = pairs[e].second;
      const bool ok = (d2 <= rf2) & (d2 > 0.f) & (valid[i] != 0) & (valid[j] != 0);
      const int ki = key_col[i], kj = key_col[j];
      term_col[nt] = static_cast<std::uint32_t>(ki), term_row[nt] = j, term_d2[nt] = d2;
      nt += ok & (ki >= 0) ? 1 : 0;
      term_col[nt] = static_cast<std::uint32_t>(kj), term_row[nt] = i, term_d2[nt] = d2;
      nt += ok & (kj >= 0) ? 1 : 0;
    }
    for (std::size_t t = 0; t < nt; ++t) {
      const float w = 1.f / std::sqrt(term_d2[t]);
      addScaledRow(&sums[static_cast<std::size_t>(term_col[t]) * kRow], &spfh[term_row[t] * kRow], w);
      ++weight_count[term_col[t]];
    }
  }
}

/// FPFH = own SPFH + distance-weighted mean of the neighbours' SPFH (within `rf2`), each sub-histogram
/// normalised to 100, for the keypoints.
void computeFpfh(const OrderedCloud& c, const std::vector<unsigned char>& valid, const AlignedFloats& spfh, float rf2,
                 FastFeatures& out) {
  std::vector<int> key_col(c.points.size(), -1);  // by position
  for (std::size_t k = 0; k < out.keypoints.size(); ++k)
    key_col[keypointPosition(out, c.position, k)] = static_cast<int>(k);
  const std::size_t nk = out.keypoints.size();
  AlignedFloats sums(nk * kRow, 0.f);
  std::vector<int> weight_count(nk, 0);
  sumNeighbourSpfh(c.pairs, key_col, valid, spfh, rf2, sums, weight_count);
  out.features.resize(kFpfhDim, static_cast<Eigen::Index>(nk));
  for (std::size_t k = 0; k < nk; ++k) {
    const std::size_t i = keypointPosition(out, c.position, k);
    auto acc = out.features.col(static_cast<Eigen::Index>(k));
    acc = Eigen::Map<const Eigen::Matrix<float, kFpfhDim, 1>>(&sums[k * kRow]);
    if (weight_count[k] > 0) acc /= static_cast<float>(weight_count[k]);
    acc += Eigen::Map<const Eigen::Matrix<float, kFpfhDim, 1>>(&spfh[i * kRow]);
    for (int s = 0; s < 3; ++s) {
      const float sum = acc.segment<kBins>(s * kBins).sum();
      if (sum > 0.f) acc.segment<kBins>(s * kBins) *= 100.f / sum;
    }
  }
}

}  // namespace

FastFeatures computeFastFeatures(const std::vector<Eigen::Vector3f>& input, const FastFeatureParams& params,
                                 StageObserver* observer) {
  FastFeatures out;
  if (input.empty()) {
    out.features = FpfhMatrix(kFpfhDim, 0);
    return out;
  }
  const double spfh_r = params.spfh_radius > 0.0 ? params.spfh_radius : params.fpfh_radius;
  const float rf2 = static_cast<float>(params.fpfh_radius * params.fpfh_radius);
  const float rs2 = static_cast<float>(spfh_r * spfh_r);
  const float rn2 = static_cast<float>(params.normal_radius * params.normal_radius);
  const float rsearch = static_cast<float>(std::max({spfh_r, params.normal_radius, params.fpfh_radius}));

  const OrderedCloud cloud = orderCloud(input, rsearch);
  notifyStage(observer, "neighbours");

  AlignedFloats moments;
  std::vector<std::uint32_t> count;
  accumulateMoments(cloud, rn2, moments, count);
  std::vector<Eigen::Vector3f> normals;
  std::vector<unsigned char> valid;
  normalsFromMoments(cloud.points, moments, count, params, normals, valid);
  notifyStage(observer, "normals");

  const AlignedFloats spfh = scaleSpfh(countSpfhBins(cloud, normals, valid, rs2), cloud.points.size());
  notifyStage(observer, "spfh");

  selectKeypoints(input, cloud.position, normals, valid, params.keypoint_voxel, out);
  computeFpfh(cloud, valid, spfh, rf2, out);
  notifyStage(observer, "fpfh");
  return out;
}

}  // namespace cosmo::registration
