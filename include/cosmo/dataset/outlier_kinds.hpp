#pragma once
// The rules by which injected loop closures are wrong (docs/design.md, "Injected outliers"). Each draw takes a
// template: a loop closure of the dataset, of the scope asked for when there is one, whose covariance the new
// closure carries (the dataset's loop-closure noise model) and, for `random` and `group`, whose measured relative
// pose it claims between other poses (a wrong place match claims what a right one would: a relative pose of the
// size real closures have). Every closure drawn fails the dataset's label rule against the ground truth.
//   random  two poses of the team drawn uniformly (intra: of one robot, at least 2 indices apart; inter: of two
//           robots), the template's measurement between them.
//   local   two poses at most `local_radius_m` apart in the ground truth, measured at their true relative pose
//           moved by `local_min`..`local_max` times the label bound (whitened distance) in a uniformly random
//           direction of the covariance's whitened space: close to right, and still an outlier.
//   group   `group_size` closures (a_k, b_k) = (a_0 + k, b_0 + k) claiming one wrong alignment: the first as
//           `random`, the others A_k^-1 M_0 B_k with A_k, B_k the true motion from a_0 to a_k and from b_0 to b_k,
//           so that they agree with each other through the odometry as a group of inliers does.
//   mixed   each draw is random, local or group with equal chance.
// A closure is stored by the robot whose pose is the newer (later stamp; intra: higher index), in the entry that
// made that pose, with that pose as key1: where the front-end would have computed it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/dataset/team_poses.hpp"

namespace cosmo::dataset {

enum class OutlierKind { Random, Local, Group, Mixed };
/// Which pose pairs: within one robot, between robots, or both.
enum class ClosureScope { Intra, Inter, Both };

const char* outlierKindName(OutlierKind kind);  ///< "random", "local", "group", "mixed"
std::optional<OutlierKind> parseOutlierKind(const std::string& name);
const char* closureScopeName(ClosureScope scope);  ///< "intra", "inter", "both"
std::optional<ClosureScope> parseClosureScope(const std::string& name);

struct OutlierDrawParams {
  OutlierRule rule = OutlierRule::Fidelity;  ///< the dataset's label rule: every injected closure fails it
  double local_radius_m = 10.0;              ///< local: pose pairs at most this far apart (riSAM's close radius)
  double local_min = 1.5, local_max = 3.0;   ///< local: error in multiples of the label bound (whitened)
  std::size_t group_size = 5;                ///< group: closures per group
};

/// One wrong loop closure, placed.
struct WrongClosure {
  char owner = 0;          ///< the robot whose list holds it
  std::size_t entry = 0;   ///< the entry that made key1
  jrl::Key key1 = 0, key2 = 0;
  Pose3 measured = Pose3::Identity();  ///< claimed T_key1^-1 * T_key2
  Matrix6 covariance = Matrix6::Identity();
  OutlierKind kind = OutlierKind::Random;  ///< random, local or group (never mixed)
  double d2 = 0.0;                         ///< its squared whitened distance to the truth
};

class OutlierDrawer {
 public:
  /// Throws std::invalid_argument when `team` has no loop closure (no noise model to take) or a parameter is out
  /// of range.
  OutlierDrawer(const TeamPoses& team, const OutlierDrawParams& params, std::uint64_t seed);

  /// One draw of `kind` between poses of one robot (`inter` false) or of two: one closure, or for a group up to
  /// `max_size` of them. Throws std::runtime_error when the team has no such pose pair (e.g. inter with one
  /// robot, local with no poses that close).
  std::vector<WrongClosure> draw(OutlierKind kind, bool inter, std::size_t max_size);

  /// Uniform in [0, 1) (the drawer's stream; for the caller's own choices).
  double uniform();

 private:
  struct PoseRef {
    char robot;
    std::size_t index;  ///< into TeamPoses::robots[robot]
  };
  const TeamPose& pose(const PoseRef& p) const;
  /// Whether `b` is the newer pose of the pair (later stamp; one robot: higher index): the one that stores it.
  bool newer(const PoseRef& b, const PoseRef& a) const;
  const jrl::PoseFactor& pickTemplate(bool inter);
  std::optional<std::pair<PoseRef, PoseRef>> pickPair(bool inter, bool local, std::size_t shift);
  WrongClosure place(const PoseRef& a, const PoseRef& b, const Pose3& claim, const Matrix6& cov,
                     OutlierKind kind) const;
  std::vector<WrongClosure> tryDraw(OutlierKind kind, bool inter, std::size_t size);
  std::size_t index(std::size_t n);
  double normal();

  const TeamPoses& team_;
  OutlierDrawParams params_;
  double bound_d_;  ///< whitened distance at which the rule calls a closure an outlier
  std::vector<PoseRef> all_;
  std::mt19937_64 rng_;
};

}  // namespace cosmo::dataset
