#include "cosmo/jrl/synthetic.hpp"

#include <cmath>

namespace cosmo::jrl {

namespace {

Vector6 gaussian6(std::mt19937_64& rng, double sigma_rot, double sigma_trans) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vector6 v;
  for (int i = 0; i < 3; ++i) v(i) = sigma_rot * n(rng);
  for (int i = 3; i < 6; ++i) v(i) = sigma_trans * n(rng);
  return v;
}

/// A dense SPD covariance: diag(rot², trans²) with small correlations, like COSMO's constant covariances.
Matrix6 denseCovariance(std::mt19937_64& rng, double sigma_rot, double sigma_trans) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Matrix6 A = Matrix6::Identity();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < r; ++c) A(r, c) = u(rng);
  Vector6 s;
  s << sigma_rot, sigma_rot, sigma_rot, sigma_trans, sigma_trans, sigma_trans;
  const Matrix6 L = s.asDiagonal() * A;
  const Matrix6 S = L * L.transpose();
  return 0.5 * (S + S.transpose());
}

}  // namespace

Dataset makeSyntheticDataset(const SyntheticParams& p, std::mt19937_64& rng) {
  Dataset d;
  d.name = "synthetic_cosmo";
  d.robots = p.robots;
  const std::size_t n = std::max<std::size_t>(1, p.poses_per_robot);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);

  // Ground truth: random walks with smooth heading changes, starting near each other.
  std::map<char, std::vector<cosmo::Pose3>> gt;
  for (std::size_t ri = 0; ri < p.robots.size(); ++ri) {
    auto& traj = gt[p.robots[ri]];
    cosmo::Pose3 T =
        cosmo::makePose(5.0 * double(ri), -3.0 * double(ri), 0.1 * gauss(rng), 0.0, 0.0, 2.0 * M_PI * uni(rng));
    traj.push_back(T);
    for (std::size_t i = 1; i < n; ++i) {
      const cosmo::Pose3 step = cosmo::makePose(p.step_m * (0.7 + 0.6 * uni(rng)), 0.05 * gauss(rng), 0.01 * gauss(rng),
                                                0.005 * gauss(rng), 0.005 * gauss(rng), 0.15 * gauss(rng));
      T = cosmo::orthonormalized(T * step);
      traj.push_back(T);
    }
  }

  Matrix6 prior_cov = Matrix6::Zero();
  prior_cov.diagonal() << 1e-8, 1e-8, 1e-8, 1e-6, 1e-6, 1e-6;
  const Matrix6 odom_cov = denseCovariance(rng, 2e-3, 0.02);
  const Matrix6 lc_cov = denseCovariance(rng, 1e-2, 0.1);

  d.groundtruth.emplace();
  d.initialization.emplace();
  d.potential_outliers.emplace();
  d.outliers.emplace();
  for (std::size_t ri = 0; ri < p.robots.size(); ++ri) {
    const char r = p.robots[ri];
    const auto& traj = gt.at(r);
    auto& entries = d.measurements[r];
    Values& gtv = (*d.groundtruth)[r];
    Values& init = (*d.initialization)[r];
    auto& potential = (*d.potential_outliers)[r];
    auto& outliers = (*d.outliers)[r];
    std::map<Key, cosmo::Pose3> init_pose;  // own dead reckoning + teammates through first closure

    for (std::size_t i = 0; i < n; ++i) {
      Entry e;
      e.stamp = p.first_stamp + ri * 777'000'000ull + i * p.period_ns;
      const Key ki = symbol(r, i);
      insertPose3(gtv, ki, traj[i]);
      if (i == 0) {
        e.factors.push_back(Factor::priorPose3(ki, traj[0], prior_cov));
        init_pose[ki] = traj[0];
      } else {
        const cosmo::Pose3 rel = traj[i - 1].inverse() * traj[i];
        const cosmo::Pose3 meas = rel * cosmo::expSE3(gaussian6(rng, 2e-3, 0.02));
        e.factors.push_back(Factor::betweenPose3(symbol(r, i - 1), ki, meas, odom_cov));
        init_pose[ki] = cosmo::orthonormalized(init_pose.at(symbol(r, i - 1)) * meas);
      }
      auto closure = [&](Key k1, const cosmo::Pose3& T1, Key k2, const cosmo::Pose3& T2) {
        cosmo::Pose3 meas = T1.inverse() * T2 * cosmo::expSE3(gaussian6(rng, 5e-3, 0.05));
        const bool outlier = uni(rng) < p.outlier_ratio;
        if (outlier) meas = meas * cosmo::expSE3(gaussian6(rng, 0.5, 5.0));
        const FactorId id{entries.size(), e.factors.size()};
        e.factors.push_back(Factor::betweenPose3(k1, k2, meas, lc_cov));
        potential.insert(id);
        if (outlier) outliers.insert(id);
        insertPose3(gtv, k2, T2);
        if (!init_pose.count(k2)) init_pose[k2] = cosmo::orthonormalized(init_pose.at(k1) * meas);
      };
      if (i > 10 && uni(rng) < p.lc_probability) {
        const std::size_t j = static_cast<std::size_t>(uni(rng) * double(i - 5));
        closure(ki, traj[i], symbol(r, j), traj[j]);
      }
      if (p.robots.size() > 1 && i > 0 && uni(rng) < p.irlc_probability) {
        char o = r;
        while (o == r) o = p.robots[static_cast<std::size_t>(uni(rng) * double(p.robots.size())) % p.robots.size()];
        const std::size_t j = static_cast<std::size_t>(uni(rng) * double(i));
        closure(ki, traj[i], symbol(o, j), gt.at(o)[j]);
      }
      entries.push_back(std::move(e));
    }
    for (const auto& [k, T] : init_pose) insertPose3(init, k, T);
  }
  return d;
}

}  // namespace cosmo::jrl
