#pragma once
// Assembling a COSMO-Bench style JRL dataset from every robot's keyframes, odometry and loop closures
// (spec sections 6-7, ../shared/docs/jrl.md §10). ROS-free; the `recorder` node and the offline driver both
// feed it. build() is a pure function of what was added (the order of addKeyframe/addLoopClosure calls across
// robots does not matter), so the same measurements give the same bytes.
//
// What build() produces, per robot r with keyframes 0..n-1 (the contiguous run starting at 0):
// - entry 0 (stamp of keyframe 0): PriorFactorPose3 on <r>0 at its reference pose (identity without one),
//   covariance diag(1e-8 x3, 1e-6 x3) (sigma_rot 1e-4 rad, sigma_trans 1e-3 m);
// - entry i >= 1 (stamp of keyframe i): BetweenFactorPose3 <r>(i-1) -> <r>i (odometry) as measurement 0;
// - each loop closure in the entry at which it was computed: the last keyframe of its owner with
//   stamp <= computed_at, but never before key1's (or an own key2's) entry; key1 is the owner's pose (an
//   intra-robot closure has key1 = the newer pose); within an entry sorted by (computed_at, key1, key2);
// - after the owner's last keyframe: one entry per loop closure, stamped computed_at (made strictly
//   increasing by +1 ns where needed);
// - potential outliers: every loop closure; outliers: loop closures failing the chi^2 rule (outlier_rule.hpp)
//   against the reference poses with the loop-closure covariance;
// - groundtruth: reference poses of every key r's factors refer to (teammates' keys included);
//   initialization: own poses by dead reckoning from the prior, a teammate key as init_r(key1) * measurement
//   of the first closure in r's list that refers to it.
// Groundtruth and outlier labels need a reference pose for every written keyframe; without them the dataset
// has potential outliers only (no groundtruth, no outlier_factors) and report().labels_note says why.
// Keyframes after a gap in a robot's indices and loop closures touching keys not (yet) written are left out
// of this build (they are kept and enter a later build once the gap is filled).
// A bridged keyframe (the first of a restarted front-end, addKeyframe's bridge_from) continues the robot's chain
// after keyframe bridge_from, whatever the indices between (they may never come): its odometry factor joins the two
// by the bridge rule (gap_bridge.hpp) and is listed in the build report and the metadata.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::dataset {

/// A loop-closure measurement: measurement = T_key1^-1 * T_key2 (JRL BetweenFactor semantics), key1 owned by
/// `owner` (when only key2 is, the recorder swaps the keys and inverts the measurement).
struct LoopClosureMeasurement {
  char owner = 'a';
  StampNs computed_at = 0;  ///< sequence time at which the owner computed it
  std::uint64_t key1 = 0;   ///< jrl::symbol(robot, index)
  std::uint64_t key2 = 0;
  Pose3 measurement = Pose3::Identity();
};

/// Prior covariance on every robot's keyframe 0: diag(1e-8 x3, 1e-6 x3).
Matrix6 priorCovariance();

/// Received-measurement counters (for progress output).
struct RecorderCounts {
  std::map<char, std::size_t> keyframes;  ///< per robot
  std::size_t loop_closures = 0;          ///< accepted by addLoopClosure
  std::size_t intra = 0;
  std::size_t inter = 0;
  std::size_t rejected = 0;  ///< inputs refused (unknown robot, NaN, duplicate, ...)
};

/// What the last build() did.
struct BuildReport {
  bool labelled = false;    ///< groundtruth and outlier_factors written
  std::string labels_note;  ///< why not, when !labelled
  std::size_t entries = 0;
  std::size_t odometry = 0;
  std::size_t intra = 0;                       ///< intra-robot loop closures written
  std::size_t inter = 0;                       ///< inter-robot loop closures written
  std::size_t outliers = 0;                    ///< labelled outliers (0 when !labelled)
  std::size_t keyframes_pending = 0;           ///< keyframes after a gap in their robot's indices
  std::size_t loop_closures_pending = 0;       ///< loop closures touching keys not written
  std::vector<char> robots_without_keyframes;  ///< left out of `robots`
  struct Bridge {
    char robot = 'a';
    std::size_t from = 0, to = 0;  ///< keyframe indices
    double gap_seconds = 0.0;
    std::string rule;
  };
  std::vector<Bridge> bridges;  ///< odometry factors across front-end restarts (gap_bridge.hpp)
};

class DatasetRecorder {
 public:
  DatasetRecorder(std::string name, std::vector<char> robots, NoiseModels noise,
                  OutlierRule rule = OutlierRule::Fidelity);

  /// Keyframe `index` of `robot` at `stamp` with the odometry T_{index-1}^-1 * T_index (ignored for index 0)
  /// and its reference (world) pose when known. Throws std::invalid_argument naming the problem (unknown
  /// robot, duplicate index, non-finite odometry, stamp not between its neighbours'); a non-finite reference
  /// pose is kept as "no reference". `bridge_from`: the first keyframe of a restarted front-end, following keyframe
  /// *bridge_from (< index) by the bridge rule; its odometry is ignored.
  void addKeyframe(char robot, std::size_t index, StampNs stamp, const Pose3& odometry_from_previous,
                   const std::optional<Pose3>& reference_pose,
                   std::optional<std::size_t> bridge_from = std::nullopt);
  /// The last keyframe index of `robot`'s chain (what build() writes), if it has keyframe 0.
  std::optional<std::size_t> chainEnd(char robot) const;
  /// The nominal keyframe distance the bridge rule divides a gap's length by (gap_bridge.hpp; default 2 m).
  void setKeyframeDistance(double metres) { keyframe_distance_ = metres; }
  /// Throws std::invalid_argument naming the problem (unknown robot, no key owned by `owner`, key1 == key2,
  /// non-finite measurement, the same owner/keys/computed_at twice).
  void addLoopClosure(const LoopClosureMeasurement& lc);

  /// The dataset (deterministic). See the file comment for the conventions.
  jrl::Dataset build() const { return build(nullptr); }
  jrl::Dataset build(BuildReport* report) const;
  /// build() and write the JRL to `path` atomically (temp + rename), then the metadata (metadataPath(path)) and
  /// the `cosmo_jrl stats` table (statsPath(path)) next to it. Returns the build report; the dataset written goes to
  /// `*built` when given. Throws std::runtime_error naming the path on I/O failure (an existing file is left
  /// untouched).
  BuildReport write(const std::string& path, jrl::Dataset* built = nullptr) const;
  /// "<path without .jrl>.recorder.yaml".
  static std::string metadataPath(const std::string& jrl_path);
  /// "<path without .jrl>.stats.txt": the dataset's Fig. 1 statistics as `cosmo_jrl stats` prints them.
  static std::string statsPath(const std::string& jrl_path);
  /// The metadata text written next to the JRL: rule, whether labels exist, noise models, counts, and the
  /// caller's own lines (setMetadata).
  std::string metadataYaml(const BuildReport& report) const;
  /// Extra `key: value` lines of the metadata (value as YAML text, e.g. the sequence's reference offset).
  void setMetadata(std::vector<std::pair<std::string, std::string>> lines) { extra_metadata_ = std::move(lines); }

  const RecorderCounts& counts() const { return counts_; }
  /// One line for progress output, e.g. "keyframes a 12 b 10 | loop closures 5 (intra 3, inter 2)".
  std::string progressLine() const;
  const std::string& name() const { return name_; }
  const std::vector<char>& robots() const { return robots_; }
  const NoiseModels& noiseModels() const { return noise_; }
  OutlierRule outlierRule() const { return rule_; }
  /// Critical value of the chi^2 rule (default kChi2Critical95Dof6).
  void setCriticalValue(double value) { critical_value_ = value; }
  double criticalValue() const { return critical_value_; }

 private:
  struct Keyframe {
    StampNs stamp = 0;
    Pose3 odometry = Pose3::Identity();
    std::optional<Pose3> reference;
    std::optional<std::size_t> bridge_from;
  };
  bool knows(char robot) const;

  // build()'s steps.
  struct Placed;  ///< a loop closure placed in an entry of its owner
  /// A robot's written keyframes in order: 0, 1, 2, ..., each the next index or a bridge from the one before.
  struct Chain {
    std::vector<std::size_t> index;
    std::vector<const Keyframe*> frames;
    std::map<std::size_t, std::size_t> position;  ///< keyframe index -> position in the chain
    std::size_t size() const { return frames.size(); }
    bool empty() const { return frames.empty(); }
    /// The position of keyframe `index`, when written.
    std::optional<std::size_t> find(std::size_t index) const;
  };
  using Chains = std::map<char, Chain>;
  /// `robot`'s chain.
  Chain chainOf(char robot) const;
  /// Per robot, its chain (the keyframes written).
  Chains keyframeChains(BuildReport& report) const;
  /// Per owner, the loop closures between written keyframes, each placed in one of the owner's entries.
  std::map<char, std::vector<Placed>> placeLoopClosures(const Chains& chains, BuildReport& report) const;
  /// Robot r's measurements (prior, odometry, its loop closures), initial values, ground truth and labels.
  void addRobot(char r, const Chains& chains, std::vector<Placed> closures, jrl::Dataset& ds,
                BuildReport& report) const;

  std::string name_;
  std::vector<char> robots_;
  NoiseModels noise_;
  OutlierRule rule_;
  double critical_value_ = kChi2Critical95Dof6;
  double keyframe_distance_ = 2.0;
  std::vector<std::pair<std::string, std::string>> extra_metadata_;
  std::map<char, std::map<std::size_t, Keyframe>> keyframes_;
  std::vector<LoopClosureMeasurement> loop_closures_;  ///< normalised (key1 owned), in arrival order
  std::set<std::tuple<char, std::uint64_t, std::uint64_t, StampNs>> loop_closure_ids_;
  RecorderCounts counts_;
};

}  // namespace cosmo::dataset
