#pragma once
// The whole team's Pose3 graph of a dataset in one flat view, for solvers, figures and exports: every
// PriorFactorPose3 / BetweenFactorPose3 with its kind, its place in the file and its outlier label, and one
// value per key taken from the key's owner (jrl.md §10: a teammate's copy of a key differs in initialization).
//   kinds as in jrl/stats.hpp: odometry = <r>i -> <r>(i+1); loop closure = any other between factor within one
//   robot; inter-robot loop closure = between two robots.
#include <cstddef>
#include <map>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

enum class FactorKind { Prior, Odometry, LoopClosure, InterRobotLoopClosure };

/// "prior", "odometry", "lc", "irlc".
const char* factorKindName(FactorKind kind);

struct PoseFactor {
  FactorKind kind = FactorKind::Prior;
  char robot = 0;                                    ///< the robot whose measurement list holds the factor
  FactorId id;                                       ///< its [entry, measurement] there
  StampNs stamp = 0;                                 ///< the entry's stamp
  Key key1 = 0;                                      ///< the prior's key, or the between factor's key1
  Key key2 = 0;                                      ///< between factors only (== key1 for priors)
  cosmo::Pose3 measured = cosmo::Pose3::Identity();  ///< prior, or T_key1^-1 * T_key2
  Matrix6 covariance = Matrix6::Identity();          ///< rotation first
  bool potential_outlier = false;
  bool outlier = false;

  bool isLoopClosure() const { return kind == FactorKind::LoopClosure || kind == FactorKind::InterRobotLoopClosure; }
};

using PoseMap = std::map<Key, cosmo::Pose3>;

struct PoseGraph {
  std::string name;
  std::vector<char> robots;
  std::vector<PoseFactor> factors;  ///< robots in dataset order, then entries, then measurements
  PoseMap initialization;           ///< one value per key (the owner's); empty without initialization
  PoseMap groundtruth;              ///< likewise; empty without ground truth
  bool has_outlier_labels = false;  ///< the dataset lists outlier_factors
  /// Stamp of each own pose: the stamp of the first entry of its owner that refers to it.
  std::map<Key, StampNs> stamps;

  /// Keys owned by `robot` (top byte), in index order, that have a ground-truth or initialization value.
  std::vector<Key> ownKeys(char robot) const;
};

/// The Pose3 graph of `dataset`. Throws std::runtime_error naming the robot, entry and measurement of a factor
/// that is not a Pose3 prior or between factor (COSMO uses only those, jrl.md §5.1).
PoseGraph poseGraph(const Dataset& dataset);

/// One Pose3 per key from per-robot values: the owner robot's value when it holds the key, else the value of the
/// first robot (in `robots` order) that does. Non-Pose3 values are skipped.
PoseMap ownerPoses(const std::vector<char>& robots, const std::map<char, Values>& values);

}  // namespace cosmo::jrl
