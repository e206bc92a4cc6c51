#pragma once
// One robot's place recognition (spec section 4 items 4-5): a ScanContext database of its own keyframes and
// one database per teammate, filled with the scans received from that teammate.
//  - addOwnKeyframe: the new keyframe is searched against the own database (its most recent keyframes
//    excluded) and against every teammate database, then stored in the own database.
//  - addTeammateScan: a received scan is searched against the own database (nothing excluded), then stored in
//    that teammate's database.
// Every search is the two-phase search of ScanContextDatabase; from each database searched, the best
// `max_matches_per_database` candidates (default 1, the paper's top candidate) with a distance below
// `threshold` are returned, own database first, then teammates in robot-id order.
#include <cstddef>
#include <map>
#include <set>
#include <vector>

#include "cosmo/common/config.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/place_recognition/scan_context.hpp"
#include "cosmo/place_recognition/scan_context_database.hpp"

namespace cosmo::place_recognition {

struct PlaceRecognitionParams {
  ScanContextParams sc;
  /// Ring-key nearest neighbours scored with the full distance (Kim's code: 10).
  int num_candidates = 10;
  /// Accept a candidate when its descriptor distance is below this (see config/place_recognition.yaml).
  double threshold = 0.30;
  /// Own keyframes excluded from the own-database search: the most recent `exclude_recent` ones (30 keyframes
  /// = 60 m of travel at the 2 m keyframe spacing, within the 80 m descriptor range)...
  int exclude_recent = 30;
  /// ...and those stamped less than this many seconds before the query (0 = off).
  double exclude_recent_seconds = 0.0;
  /// Candidates returned per database searched (1 = the best only).
  int max_matches_per_database = 1;
  /// k-d tree rebuild period of each database: after max(rebuild_every, rebuild_fraction * tree size)
  /// insertions (newer entries are searched linearly).
  int rebuild_every = 50;
  double rebuild_fraction = 0.1;

  /// Reads config/place_recognition.yaml (its root or the `place_recognition` section).
  static PlaceRecognitionParams fromConfig(const ConfigNode& node);
  void validate() const;
  ScanContextDatabaseParams databaseParams() const;

  /// The YAML keys, one per member (common/param_list.hpp).
  template <class Visitor>
  void visit(Visitor&& v) {
    v("num_candidates", num_candidates);
    v("threshold", threshold);
    v("exclude_recent", exclude_recent);
    v("exclude_recent_seconds", exclude_recent_seconds);
    v("max_matches_per_database", max_matches_per_database);
    v("rebuild_every", rebuild_every);
    v("rebuild_fraction", rebuild_fraction);
  }
};

struct LoopCandidate {
  char query_robot = 'a';
  std::size_t query_index = 0;  ///< keyframe index of the query scan (on query_robot)
  char match_robot = 'a';
  std::size_t match_index = 0;  ///< keyframe index of the matched scan (on match_robot)
  double distance = 1.0;        ///< ScanContext distance
  double yaw = 0.0;             ///< yaw of T_match_query, radians (see DescriptorMatch::yaw)
};

class PlaceRecognizer {
 public:
  PlaceRecognizer(char own_robot, const PlaceRecognitionParams& p);

  /// Own keyframe `index` (a dewarped scan in the sensor frame; its stamp drives the time-based exclusion).
  std::vector<LoopCandidate> addOwnKeyframe(std::size_t index, const Scan& scan);
  /// Keyframe `index` of teammate `robot`, received over the radio. A scan of that teammate already stored
  /// under the same index is searched again but not stored twice. Throws std::invalid_argument for own_robot.
  std::vector<LoopCandidate> addTeammateScan(char robot, std::size_t index, const Scan& scan);

  /// The same with a descriptor computed elsewhere (e.g. benchmarks).
  std::vector<LoopCandidate> addOwnDescriptor(std::size_t index, StampNs stamp, ScanContext descriptor);
  std::vector<LoopCandidate> addTeammateDescriptor(char robot, std::size_t index, StampNs stamp,
                                                   ScanContext descriptor);

  char ownRobot() const { return own_robot_; }
  const PlaceRecognitionParams& params() const { return params_; }
  const ScanContextDatabase& ownDatabase() const { return own_; }
  /// nullptr when nothing was received from `robot` yet.
  const ScanContextDatabase* teammateDatabase(char robot) const;

 private:
  void collect(const std::vector<DatabaseMatch>& matches, char query_robot, std::size_t query_index, char match_robot,
               std::vector<LoopCandidate>& out) const;
  std::size_t ownSearchable(StampNs stamp) const;

  char own_robot_;
  PlaceRecognitionParams params_;
  ScanContextDatabase own_;
  std::map<char, ScanContextDatabase> teammates_;
  std::map<char, std::set<std::size_t>> teammate_ids_;
};

}  // namespace cosmo::place_recognition
