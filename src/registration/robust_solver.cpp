#include "cosmo/registration/robust_solver.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cosmo::registration {

Eigen::Matrix3d weightedProcrustes(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                   const std::vector<double>& w) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) H += w[i] * b[i] * a[i].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

RotationEstimate gncTlsRotation(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                const GncParams& params) {
  RotationEstimate out;
  const std::size_t n = a.size();
  out.inliers.assign(n, false);
  if (n == 0) return out;
  const double c2 = params.noise_bound * params.noise_bound;
  std::vector<double> w(n, 1.0), r2(n);
  auto residuals = [&](const Eigen::Matrix3d& R) {
    double max_r2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      r2[i] = (b[i] - R * a[i]).squaredNorm();
      max_r2 = std::max(max_r2, r2[i]);
    }
    return max_r2;
  };
  Eigen::Matrix3d R = weightedProcrustes(a, b, w);
  const double max_r2 = residuals(R);
  double mu = 1.0 / (2.0 * max_r2 / c2 - 1.0);
  if (mu > 0.0) {  // else every residual is already within the bound: least squares is the TLS optimum
    double prev_cost = std::numeric_limits<double>::infinity();
    for (int it = 0; it < params.max_iterations; ++it) {
      out.iterations = it + 1;
      const double th_out = (mu + 1.0) / mu * c2;  // above: weight 0
      const double th_in = mu / (mu + 1.0) * c2;   // below: weight 1
      for (std::size_t i = 0; i < n; ++i) {
        if (r2[i] >= th_out)
          w[i] = 0.0;
        else if (r2[i] <= th_in)
          w[i] = 1.0;
        else
          w[i] = std::sqrt(c2 * mu * (mu + 1.0) / r2[i]) - mu;
      }
      double wsum = 0.0;
      for (const double wi : w) wsum += wi;
      if (wsum <= 0.0) break;
      R = weightedProcrustes(a, b, w);
      residuals(R);
      double cost = 0.0;
      for (std::size_t i = 0; i < n; ++i) cost += w[i] * r2[i];
      if (std::fabs(cost - prev_cost) < params.cost_tolerance) break;
      prev_cost = cost;
      mu *= params.factor;
    }
  }
  out.R = R;
  for (std::size_t i = 0; i < n; ++i) out.inliers[i] = r2[i] <= c2;
  return out;
}

namespace {
/// argmin_x sum_i min((x - v_i)^2, c^2): sweep the interval endpoints; within each segment the active set is
/// fixed and the optimum is its mean (clamped to the segment).
double tlsScalar(const std::vector<double>& v, double c) {
  const std::size_t n = v.size();
  struct Event {
    double position;
    int sign;  // +1 enter, -1 leave
    std::size_t index;
  };
  std::vector<Event> events;
  events.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    events.push_back({v[i] - c, +1, i});
    events.push_back({v[i] + c, -1, i});
  }
  std::sort(events.begin(), events.end(), [](const Event& p, const Event& q) {
    if (p.position != q.position) return p.position < q.position;
    if (p.sign != q.sign) return p.sign > q.sign;  // enter before leave at the same position
    return p.index < q.index;
  });
  double sum = 0.0, sum2 = 0.0;
  int active = 0;
  double best_x = v.empty() ? 0.0 : v[0], best_cost = std::numeric_limits<double>::infinity();
  const double c2 = c * c;
  for (std::size_t e = 0; e + 1 < events.size(); ++e) {
    const double x = v[events[e].index];
    if (events[e].sign > 0) {
      sum += x, sum2 += x * x, ++active;
    } else {
      sum -= x, sum2 -= x * x, --active;
    }
    if (active <= 0) continue;
    const double lo = events[e].position, hi = events[e + 1].position;
    double xm = sum / active;
    xm = std::clamp(xm, lo, hi);
    const double cost = sum2 - 2.0 * xm * sum + active * xm * xm + static_cast<double>(n - active) * c2;
    if (cost < best_cost - 1e-12) {
      best_cost = cost;
      best_x = xm;
    }
  }
  return best_x;
}
}  // namespace

TranslationEstimate tlsTranslation(const std::vector<Eigen::Vector3d>& v, double noise_bound) {
  TranslationEstimate out;
  out.inliers.assign(v.size(), false);
  if (v.empty()) return out;
  std::vector<double> axis(v.size());
  for (int d = 0; d < 3; ++d) {
    for (std::size_t i = 0; i < v.size(); ++i) axis[i] = v[i][d];
    out.t[d] = tlsScalar(axis, noise_bound);
  }
  for (std::size_t i = 0; i < v.size(); ++i) out.inliers[i] = ((v[i] - out.t).array().abs() <= noise_bound).all();
  return out;
}

RigidEstimate solveRobustRigid(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                               const GncParams& params, std::size_t max_pairs) {
  RigidEstimate out;
  const std::size_t n = source.size();
  if (n < 3 || target.size() != n) return out;
  // Translation-invariant measurements: pairs (i, i+k) for k = 1, 2, ... (all pairs when they fit).
  std::vector<Eigen::Vector3d> a, b;
  const std::size_t all_pairs = n * (n - 1) / 2;
  const std::size_t want = std::min(all_pairs, std::max<std::size_t>(max_pairs, n - 1));
  a.reserve(want), b.reserve(want);
  for (std::size_t k = 1; k < n && a.size() < want; ++k)
    for (std::size_t i = 0; i + k < n && a.size() < want; ++i) {
      a.push_back(source[i + k] - source[i]);
      b.push_back(target[i + k] - target[i]);
    }
  GncParams rot_params = params;
  rot_params.noise_bound = 2.0 * params.noise_bound;  // a difference of two points carries two noises
  const RotationEstimate rot = gncTlsRotation(a, b, rot_params);
  std::vector<Eigen::Vector3d> tv(n);
  for (std::size_t i = 0; i < n; ++i) tv[i] = target[i] - rot.R * source[i];
  const TranslationEstimate tr = tlsTranslation(tv, params.noise_bound);
  out.T.linear() = rot.R;
  out.T.translation() = tr.t;
  for (std::size_t i = 0; i < n; ++i)
    if ((target[i] - out.T * source[i]).norm() <= params.noise_bound) out.inliers.push_back(static_cast<int>(i));
  out.ok = true;
  return out;
}

}  // namespace cosmo::registration
