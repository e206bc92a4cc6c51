#pragma once
// The label a front-end shows a loop closure with (the rviz markers' colours): rejected by the registration gate,
// or accepted and then an inlier or an outlier by the dataset's chi^2 rule (dataset/outlier_rule.hpp, the rule the
// recorder labels the JRL with) against the reference poses of its two keyframes, or unlabelled when a keyframe
// has no reference or there are no noise models (live use).
#include <cstddef>
#include <map>
#include <optional>
#include <utility>

#include "cosmo/common/pose.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::frontend {

enum class ClosureLabel { Rejected, Inlier, Outlier, Unlabelled };

class ClosureLabeller {
 public:
  /// `noise`: the noise models the loop-closure covariance comes from (none: accepted closures are unlabelled).
  explicit ClosureLabeller(std::optional<dataset::NoiseModels> noise,
                           dataset::OutlierRule rule = dataset::OutlierRule::Fidelity);

  /// The reference pose (world frame) of keyframe `index` of `robot`: own keyframes and teammates' received scans.
  void addReference(char robot, std::size_t index, const Pose3& reference);
  ClosureLabel label(const LoopClosureAttempt& attempt) const;
  bool hasNoiseModels() const { return noise_.has_value(); }
  /// Noise models known only later (a lockstep front-end learns its sequence from the player).
  void setNoiseModels(dataset::NoiseModels noise) { noise_ = std::move(noise); }

 private:
  std::optional<dataset::NoiseModels> noise_;
  dataset::OutlierRule rule_;
  std::map<std::pair<char, std::size_t>, Pose3> references_;
};

}  // namespace cosmo::frontend
