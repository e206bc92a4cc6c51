#pragma once
// Test fixtures: measurements of a small synthetic team with known noise, fed to DatasetRecorder.
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <Eigen/Cholesky>

#include "cosmo/common/pose.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::test {

/// Zero-mean Gaussian tangent vectors with a given covariance (seeded).
class TangentSampler {
 public:
  explicit TangentSampler(std::uint64_t seed) : rng_(seed) {}
  Vector6 sample(const Matrix6& cov) {
    Vector6 z;
    for (int i = 0; i < 6; ++i) z(i) = normal_(rng_);
    return Eigen::LLT<Matrix6>(cov).matrixL() * z;
  }
  /// m* * Exp(e), e ~ N(0, cov): then Log(m^-1 * m*) = -e.
  Pose3 perturb(const Pose3& truth, const Matrix6& cov) { return truth * expSE3(sample(cov)); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
};

struct SyntheticKeyframe {
  char robot = 'a';
  std::size_t index = 0;
  StampNs stamp = 0;
  Pose3 odometry = Pose3::Identity();  // noisy T_{i-1}^-1 T_i
  Pose3 truth = Pose3::Identity();
};

struct SyntheticLoopClosure {
  dataset::LoopClosureMeasurement lc;
  bool injected_outlier = false;
  std::size_t expected_entry = 0;  // in the owner's measurements
};

struct SyntheticTeam {
  std::vector<SyntheticKeyframe> keyframes;
  std::vector<SyntheticLoopClosure> closures;
  std::map<char, std::vector<Pose3>> truth;
  std::map<char, std::vector<StampNs>> stamps;
};

inline Matrix6 diagonalCovariance(double sigma_rot, double sigma_trans) {
  Matrix6 c = Matrix6::Zero();
  c.diagonal() << Eigen::Vector3d::Constant(sigma_rot * sigma_rot),
      Eigen::Vector3d::Constant(sigma_trans * sigma_trans);
  return c;
}

/// Ground truth of robot r: a circle (radius 12 m) with a gentle vertical wave, one keyframe per second.
inline Pose3 circlePose(double phase, double offset_x) {
  const double R = 12.0;
  return makePose(offset_x + R * std::cos(phase), R * std::sin(phase), 0.3 * std::sin(3 * phase),
                  0.01 * std::sin(phase), 0.02 * std::cos(2 * phase), phase + M_PI / 2);
}

/// A "big" error: what a wrong registration gives.
inline Pose3 grossError() { return makePose(2.5, -1.5, 0.2, 0.05, -0.02, 0.4); }

/// Robot a: 40 keyframes, robot b: 30 keyframes (starting 0.3 s later), overlapping circles. Loop closures
/// (see the comments) of every kind the recorder must place.
inline SyntheticTeam makeTeam(const Matrix6& odo_cov, const Matrix6& lc_cov, std::uint64_t seed) {
  SyntheticTeam team;
  TangentSampler sampler(seed);
  const StampNs t0 = 1700000000000000000ULL;
  const std::map<char, std::size_t> count{{'a', 40}, {'b', 30}};
  for (const auto& [r, n] : count) {
    const StampNs start = t0 + (r == 'b' ? 300000000ULL : 0ULL);
    for (std::size_t i = 0; i < n; ++i) {
      const double phase = 2 * M_PI * static_cast<double>(i) / 25.0 + (r == 'b' ? 0.05 : 0.0);
      team.truth[r].push_back(circlePose(phase, r == 'b' ? 1.0 : 0.0));
      team.stamps[r].push_back(start + i * 1000000000ULL);
    }
    for (std::size_t i = 0; i < n; ++i) {
      SyntheticKeyframe k;
      k.robot = r;
      k.index = i;
      k.stamp = team.stamps[r][i];
      k.truth = team.truth[r][i];
      if (i > 0) {
        const Pose3 rel = team.truth[r][i - 1].inverse(Eigen::Isometry) * team.truth[r][i];
        k.odometry = sampler.perturb(rel, odo_cov);
      }
      team.keyframes.push_back(k);
    }
  }
  auto rel = [&](jrl::Key k1, jrl::Key k2) {
    return team.truth[jrl::robotOf(k1)][jrl::indexOf(k1)].inverse(Eigen::Isometry) *
           team.truth[jrl::robotOf(k2)][jrl::indexOf(k2)];
  };
  auto add = [&](char owner, StampNs at, jrl::Key k1, jrl::Key k2, bool outlier, std::size_t entry) {
    SyntheticLoopClosure c;
    c.lc.owner = owner;
    c.lc.computed_at = at;
    c.lc.key1 = k1;
    c.lc.key2 = k2;
    c.lc.measurement = sampler.perturb(rel(k1, k2), lc_cov);
    if (outlier) c.lc.measurement = c.lc.measurement * grossError();
    c.injected_outlier = outlier;
    c.expected_entry = entry;
    team.closures.push_back(c);
  };
  using jrl::symbol;
  // Intra-robot closures of a after one lap: key1 = the new pose, computed at its keyframe; every third is
  // an outlier.
  for (std::size_t i = 26; i < 40; i += 2)
    add('a', team.stamps['a'][i], symbol('a', i), symbol('a', i - 25), i % 3 == 0, i);
  // Intra-robot closure given with the older pose first: normalised to key1 = a30.
  add('a', team.stamps['a'][30] + 10, symbol('a', 5), symbol('a', 30), false, 30);
  // Inter-robot closures of a computed half a second after keyframe i, about an older own pose.
  for (std::size_t i = 6; i < 36; i += 5)
    add('a', team.stamps['a'][i] + 500000000ULL, symbol('a', i - 2), symbol('b', i - 3), i == 21, i);
  // Inter-robot closures of b, two about the same teammate key a7 (the first one initialises it).
  add('b', team.stamps['b'][8], symbol('b', 8), symbol('a', 7), false, 8);
  add('b', team.stamps['b'][9], symbol('b', 9), symbol('a', 7), false, 9);
  add('b', team.stamps['b'][12], symbol('b', 12), symbol('a', 12), true, 12);
  // Given with the teammate key first: normalised to key1 = b15.
  add('b', team.stamps['b'][15], symbol('a', 16), symbol('b', 15), false, 15);
  // Computed before the key1's keyframe stamp (clock skew): stays in key1's entry.
  add('b', team.stamps['b'][17] - 5, symbol('b', 18), symbol('a', 19), false, 18);
  // After b's last keyframe (29): one entry each, in computed_at order; two at the same time.
  const StampNs last_b = team.stamps['b'][29];
  add('b', last_b + 5000000000ULL, symbol('b', 29), symbol('a', 35), false, 32);
  add('b', last_b + 2000000000ULL, symbol('b', 28), symbol('a', 33), false, 30);
  add('b', last_b + 2000000000ULL, symbol('b', 29), symbol('a', 34), true, 31);
  return team;
}

/// Feed a team to a recorder (keyframes, then loop closures, in the given order).
inline void feed(dataset::DatasetRecorder& rec, const SyntheticTeam& team, bool with_reference = true) {
  for (const auto& k : team.keyframes)
    rec.addKeyframe(k.robot, k.index, k.stamp, k.odometry,
                    with_reference ? std::optional<Pose3>(k.truth) : std::nullopt);
  for (const auto& c : team.closures) rec.addLoopClosure(c.lc);
}

}  // namespace cosmo::test
