// Intra- and inter-robot place recognition over one own and one-per-teammate ScanContext databases.
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/common/param_list.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace cosmo::place_recognition {

PlaceRecognitionParams PlaceRecognitionParams::fromConfig(const ConfigNode& root) {
  ConfigNode node = root;
  if (node.has("place_recognition")) node = node["place_recognition"];
  PlaceRecognitionParams p;
  p.sc = ScanContextParams::fromConfig(node);
  // The ScanContext keys sit in a `scan_context` sub-section, or beside these.
  std::vector<std::string> other_keys = paramKeys<ScanContextParams>();
  other_keys.insert(other_keys.end(), {"scan_context", "empty_columns"});
  readParams(node, p, other_keys);
  try {
    p.validate();
  } catch (const std::invalid_argument& e) { throw std::runtime_error(node.where + ": " + e.what()); }
  return p;
}

void PlaceRecognitionParams::validate() const {
  sc.validate();
  if (num_candidates < 1) throw std::invalid_argument("num_candidates must be >= 1");
  if (!std::isfinite(threshold) || threshold < 0.0) throw std::invalid_argument("threshold must be >= 0");
  if (exclude_recent < 0) throw std::invalid_argument("exclude_recent must be >= 0");
  if (!(exclude_recent_seconds >= 0.0)) throw std::invalid_argument("exclude_recent_seconds must be >= 0");
  if (max_matches_per_database < 1) throw std::invalid_argument("max_matches_per_database must be >= 1");
  if (rebuild_every < 1) throw std::invalid_argument("rebuild_every must be >= 1");
  if (!(rebuild_fraction >= 0.0)) throw std::invalid_argument("rebuild_fraction must be >= 0");
}

ScanContextDatabaseParams PlaceRecognitionParams::databaseParams() const {
  ScanContextDatabaseParams d;
  d.num_candidates = num_candidates;
  d.rebuild_every = rebuild_every;
  d.rebuild_fraction = rebuild_fraction;
  d.empty_columns = sc.empty_columns;
  d.coarse_search_radius = sc.coarse_search_radius;
  return d;
}

PlaceRecognizer::PlaceRecognizer(char own_robot, const PlaceRecognitionParams& p)
    : own_robot_(own_robot), params_(p), own_((p.validate(), p.databaseParams())) {}

const ScanContextDatabase* PlaceRecognizer::teammateDatabase(char robot) const {
  const auto it = teammates_.find(robot);
  return it == teammates_.end() ? nullptr : &it->second;
}

std::size_t PlaceRecognizer::ownSearchable(StampNs stamp) const {
  std::size_t n = own_.size();
  n = n > static_cast<std::size_t>(params_.exclude_recent) ? n - static_cast<std::size_t>(params_.exclude_recent) : 0;
  if (params_.exclude_recent_seconds > 0.0) {
    const auto window = static_cast<StampNs>(std::llround(params_.exclude_recent_seconds * 1e9));
    // Own entries are in keyframe order; drop the trailing ones within the window before the query stamp.
    while (n > 0 && own_.entry(n - 1).stamp + window > stamp) --n;
  }
  return n;
}

void PlaceRecognizer::collect(const std::vector<DatabaseMatch>& matches, char query_robot, std::size_t query_index,
                              char match_robot, std::vector<LoopCandidate>& out) const {
  int taken = 0;
  for (const DatabaseMatch& m : matches) {
    if (taken >= params_.max_matches_per_database || !(m.match.distance < params_.threshold)) break;
    out.push_back(LoopCandidate{query_robot, query_index, match_robot, m.id, m.match.distance, m.match.yaw});
    ++taken;
  }
}

std::vector<LoopCandidate> PlaceRecognizer::addOwnDescriptor(std::size_t index, StampNs stamp, ScanContext descriptor) {
  std::vector<LoopCandidate> out;
  collect(own_.query(descriptor, ownSearchable(stamp)), own_robot_, index, own_robot_, out);
  for (const auto& [robot, db] : teammates_) collect(db.query(descriptor), own_robot_, index, robot, out);
  own_.insert(index, std::move(descriptor), stamp);
  return out;
}

std::vector<LoopCandidate> PlaceRecognizer::addTeammateDescriptor(char robot, std::size_t index, StampNs stamp,
                                                                  ScanContext descriptor) {
  if (robot == own_robot_) {
    throw std::invalid_argument(std::string("PlaceRecognizer: addTeammateScan called with the own robot id '") + robot +
                                "'");
  }
  std::vector<LoopCandidate> out;
  collect(own_.query(descriptor), robot, index, own_robot_, out);
  auto it = teammates_.find(robot);
  if (it == teammates_.end()) it = teammates_.emplace(robot, ScanContextDatabase(params_.databaseParams())).first;
  if (teammate_ids_[robot].insert(index).second) it->second.insert(index, std::move(descriptor), stamp);
  return out;
}

std::vector<LoopCandidate> PlaceRecognizer::addOwnKeyframe(std::size_t index, const Scan& scan) {
  return addOwnDescriptor(index, scan.stamp, makeScanContext(scan, params_.sc));
}

std::vector<LoopCandidate> PlaceRecognizer::addTeammateScan(char robot, std::size_t index, const Scan& scan) {
  return addTeammateDescriptor(robot, index, scan.stamp, makeScanContext(scan, params_.sc));
}

}  // namespace cosmo::place_recognition
