#include "cosmo/dataset/dataset_recorder.hpp"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/dataset/gap_bridge.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"

namespace cosmo::dataset {
namespace {

bool finitePose(const Pose3& T) { return T.matrix().allFinite(); }

// A YAML double-quoted string.
std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') q += '\\';
    q += c == '\n' ? ' ' : c;
  }
  return q + "\"";
}

}  // namespace

struct DatasetRecorder::Placed {
  std::size_t entry = 0;  // index into the owner's keyframes, or n + k for the k-th closure after the last
  const LoopClosureMeasurement* lc = nullptr;
  std::size_t arrival = 0;

  bool operator<(const Placed& b) const {
    return std::tie(entry, lc->computed_at, lc->key1, lc->key2, arrival) <
           std::tie(b.entry, b.lc->computed_at, b.lc->key1, b.lc->key2, b.arrival);
  }
};

Matrix6 priorCovariance() {
  Matrix6 c = Matrix6::Zero();
  c.diagonal() << 1e-8, 1e-8, 1e-8, 1e-6, 1e-6, 1e-6;
  return c;
}

DatasetRecorder::DatasetRecorder(std::string name, std::vector<char> robots, NoiseModels noise, OutlierRule rule)
    : name_(std::move(name)), robots_(std::move(robots)), noise_(std::move(noise)), rule_(rule) {
  std::set<char> seen;
  for (const char r : robots_) {
    if (!seen.insert(r).second) throw std::invalid_argument("recorder: robot '" + std::string(1, r) + "' listed twice");
    if (static_cast<unsigned char>(r) >= 128 || r <= ' ')
      throw std::invalid_argument("recorder: robot ids must be printable 7-bit ASCII characters");
    counts_.keyframes[r] = 0;
  }
  checkCovariance(noise_.odometry, "recorder: odometry noise model");
  checkCovariance(noise_.loop_closure, "recorder: loop-closure noise model");
}

bool DatasetRecorder::knows(char robot) const {
  return std::find(robots_.begin(), robots_.end(), robot) != robots_.end();
}

void DatasetRecorder::addKeyframe(char robot, std::size_t index, StampNs stamp, const Pose3& odometry_from_previous,
                                  const std::optional<Pose3>& reference_pose, std::optional<std::size_t> bridge_from) {
  const std::string what = "keyframe " + std::string(1, robot) + std::to_string(index);
  auto refuse = [&](const std::string& why) {
    ++counts_.rejected;
    throw std::invalid_argument(what + ": " + why);
  };
  if (!knows(robot)) refuse("robot '" + std::string(1, robot) + "' is not in the recorder's robot list");
  if (index > jrl::kIndexMask) refuse("index too large for a JRL key");
  if (bridge_from && *bridge_from >= index) refuse("bridged from keyframe " + std::to_string(*bridge_from) + ", not before it");
  if (index > 0 && !bridge_from && !finitePose(odometry_from_previous)) refuse("odometry is not finite");
  auto& frames = keyframes_[robot];
  if (frames.count(index)) refuse("duplicate keyframe index");
  const auto next = frames.lower_bound(index);
  if (next != frames.end() && next->second.stamp <= stamp)
    refuse("stamp " + std::to_string(stamp) + " not before keyframe " + std::to_string(next->first) + "'s " +
           std::to_string(next->second.stamp));
  if (next != frames.begin() && std::prev(next)->second.stamp >= stamp)
    refuse("stamp " + std::to_string(stamp) + " not after keyframe " + std::to_string(std::prev(next)->first) + "'s " +
           std::to_string(std::prev(next)->second.stamp));
  Keyframe k;
  k.stamp = stamp;
  k.odometry = index == 0 || bridge_from ? Pose3::Identity() : odometry_from_previous;
  k.bridge_from = bridge_from;
  if (reference_pose && finitePose(*reference_pose)) k.reference = *reference_pose;
  frames.emplace(index, k);
  ++counts_.keyframes[robot];
}

void DatasetRecorder::addLoopClosure(const LoopClosureMeasurement& input) {
  LoopClosureMeasurement lc = input;
  const std::string what = "loop closure " + jrl::keyName(lc.key1) + " -> " + jrl::keyName(lc.key2) + " of robot " +
                           std::string(1, lc.owner);
  auto refuse = [&](const std::string& why) {
    ++counts_.rejected;
    throw std::invalid_argument(what + ": " + why);
  };
  if (!knows(lc.owner)) refuse("owner is not in the recorder's robot list");
  if (!knows(jrl::robotOf(lc.key1)) || !knows(jrl::robotOf(lc.key2))) refuse("key of an unknown robot");
  if (lc.key1 == lc.key2) refuse("key1 == key2");
  if (!finitePose(lc.measurement)) refuse("measurement is not finite");
  const bool own1 = jrl::robotOf(lc.key1) == lc.owner, own2 = jrl::robotOf(lc.key2) == lc.owner;
  if (!own1 && !own2) refuse("neither key belongs to the owner");
  // Normalise: key1 is the owner's pose; for an intra-robot closure the newer one.
  if (!own1 || (own2 && jrl::indexOf(lc.key2) > jrl::indexOf(lc.key1))) {
    std::swap(lc.key1, lc.key2);
    lc.measurement = lc.measurement.inverse(Eigen::Isometry);
  }
  if (!loop_closure_ids_.emplace(lc.owner, lc.key1, lc.key2, lc.computed_at).second)
    refuse("received twice (same owner, keys and computed_at)");
  loop_closures_.push_back(lc);
  ++counts_.loop_closures;
  ++(own1 && own2 ? counts_.intra : counts_.inter);
}

std::optional<std::size_t> DatasetRecorder::Chain::find(std::size_t i) const {
  const auto it = position.find(i);
  return it == position.end() ? std::nullopt : std::optional<std::size_t>(it->second);
}

// From keyframe 0, each step goes to a keyframe bridged from the current one, else to the next index unless that
// one is bridged from elsewhere.
DatasetRecorder::Chain DatasetRecorder::chainOf(char robot) const {
  Chain c;
  const auto it = keyframes_.find(robot);
  if (it == keyframes_.end()) return c;
  const auto& frames = it->second;
  std::map<std::size_t, std::size_t> bridged;  // from -> the first keyframe bridged from it
  for (const auto& [index, frame] : frames)
    if (frame.bridge_from) bridged.emplace(*frame.bridge_from, index);
  auto at = frames.find(0);
  while (at != frames.end()) {
    c.position[at->first] = c.frames.size();
    c.index.push_back(at->first);
    c.frames.push_back(&at->second);
    if (const auto b = bridged.find(at->first); b != bridged.end()) {
      at = frames.find(b->second);
    } else {
      at = frames.find(at->first + 1);
      if (at != frames.end() && at->second.bridge_from) break;
    }
  }
  return c;
}

std::optional<std::size_t> DatasetRecorder::chainEnd(char robot) const {
  const Chain c = chainOf(robot);
  return c.empty() ? std::nullopt : std::optional<std::size_t>(c.index.back());
}

DatasetRecorder::Chains DatasetRecorder::keyframeChains(BuildReport& report) const {
  Chains chains;
  for (const char r : robots_) {
    chains[r] = chainOf(r);
    const auto it = keyframes_.find(r);
    if (it != keyframes_.end()) report.keyframes_pending += it->second.size() - chains[r].size();
  }
  return chains;
}

std::map<char, std::vector<DatasetRecorder::Placed>> DatasetRecorder::placeLoopClosures(const Chains& chains,
                                                                                        BuildReport& report) const {
  const auto written = [&](std::uint64_t key) {
    const auto c = chains.find(jrl::robotOf(key));
    return c != chains.end() && c->second.find(jrl::indexOf(key));
  };
  std::map<char, std::vector<Placed>> placed;
  for (std::size_t i = 0; i < loop_closures_.size(); ++i) {
    const LoopClosureMeasurement& lc = loop_closures_[i];
    if (!written(lc.key1) || !written(lc.key2)) {
      ++report.loop_closures_pending;
      continue;
    }
    const Chain& own = chains.at(lc.owner);
    Placed p{0, &lc, i};
    if (lc.computed_at > own.frames.back()->stamp) {
      p.entry = own.size();  // after the last keyframe; split into one entry each (addRobot)
    } else {
      // Last keyframe with stamp <= computed_at (keyframe 0 when computed before it).
      const auto after = std::upper_bound(own.frames.begin(), own.frames.end(), lc.computed_at,
                                          [](StampNs t, const Keyframe* k) { return t < k->stamp; });
      const std::size_t at = after == own.frames.begin() ? 0 : static_cast<std::size_t>(after - own.frames.begin()) - 1;
      std::size_t earliest = *own.find(jrl::indexOf(lc.key1));
      if (jrl::robotOf(lc.key2) == lc.owner) earliest = std::max(earliest, *own.find(jrl::indexOf(lc.key2)));
      p.entry = std::max(at, earliest);
    }
    placed[lc.owner].push_back(p);
  }
  return placed;
}

void DatasetRecorder::addRobot(char r, const Chains& chains, std::vector<Placed> closures, jrl::Dataset& ds,
                               BuildReport& report) const {
  const Chain& chain = chains.at(r);
  const std::vector<const Keyframe*>& own = chain.frames;
  if (own.empty()) {
    report.robots_without_keyframes.push_back(r);
    return;
  }
  ds.robots.push_back(r);
  std::sort(closures.begin(), closures.end());

  const auto key = [&](std::size_t position) { return jrl::symbol(r, chain.index[position]); };
  std::vector<jrl::Entry> entries(own.size());
  std::vector<Pose3> init(own.size());
  init[0] = own[0]->reference.value_or(Pose3::Identity());
  entries[0].stamp = own[0]->stamp;
  entries[0].factors.push_back(jrl::Factor::priorPose3(key(0), init[0], priorCovariance()));
  for (std::size_t i = 1; i < own.size(); ++i) {
    entries[i].stamp = own[i]->stamp;
    Pose3 odometry = own[i]->odometry;
    Matrix6 covariance = noise_.odometry;
    if (own[i]->bridge_from) {
      const dataset::GapBridge b = dataset::bridgeGap(own[i - 1]->stamp, own[i - 1]->reference, own[i]->stamp,
                                                      own[i]->reference, noise_.odometry, keyframe_distance_);
      odometry = b.measurement;
      covariance = b.covariance;
      report.bridges.push_back({r, chain.index[i - 1], chain.index[i], b.gap_seconds, b.rule});
    }
    entries[i].factors.push_back(jrl::Factor::betweenPose3(key(i - 1), key(i), odometry, covariance));
    init[i] = init[i - 1] * odometry;
    ++report.odometry;
  }

  auto& potential = (*ds.potential_outliers)[r];
  auto& outliers = (*ds.outliers)[r];
  jrl::Values& gt = (*ds.groundtruth)[r];
  jrl::Values& in = (*ds.initialization)[r];
  for (std::size_t i = 0; i < own.size(); ++i) {
    jrl::insertPose3(in, key(i), init[i]);
    if (report.labelled) jrl::insertPose3(gt, key(i), *own[i]->reference);
  }
  const auto referenceOf = [&](std::uint64_t k) -> const std::optional<Pose3>& {
    const Chain& c = chains.at(jrl::robotOf(k));
    return c.frames[*c.find(jrl::indexOf(k))]->reference;
  };
  for (const Placed& p : closures) {
    const LoopClosureMeasurement& lc = *p.lc;
    if (p.entry >= own.size()) {  // after the last keyframe: an entry of its own
      jrl::Entry e;
      e.stamp = std::max(lc.computed_at, entries.back().stamp + 1);
      entries.push_back(std::move(e));
    }
    const std::size_t entry = p.entry >= own.size() ? entries.size() - 1 : p.entry;
    const jrl::FactorId id{entry, entries[entry].factors.size()};
    entries[entry].factors.push_back(jrl::Factor::betweenPose3(lc.key1, lc.key2, lc.measurement, noise_.loop_closure));
    potential.insert(id);
    const bool intra = jrl::robotOf(lc.key2) == r;
    ++(intra ? report.intra : report.inter);
    if (!intra && !in.count(lc.key2)) {
      jrl::insertPose3(in, lc.key2, init[*chain.find(jrl::indexOf(lc.key1))] * lc.measurement);
      if (report.labelled) jrl::insertPose3(gt, lc.key2, *referenceOf(lc.key2));
    }
    if (report.labelled) {
      const Pose3 truth = referenceOf(lc.key1)->inverse(Eigen::Isometry) * *referenceOf(lc.key2);
      if (isOutlier(lc.measurement, truth, noise_.loop_closure, rule_, critical_value_)) {
        outliers.insert(id);
        ++report.outliers;
      }
    }
  }
  report.entries += entries.size();
  ds.measurements[r] = std::move(entries);
}

jrl::Dataset DatasetRecorder::build(BuildReport* report_out) const {
  BuildReport report;
  const Chains chains = keyframeChains(report);
  std::map<char, std::vector<Placed>> placed = placeLoopClosures(chains, report);

  // Labels need a reference pose for every written keyframe.
  std::size_t without_reference = 0;
  for (const auto& [r, c] : chains)
    for (const Keyframe* k : c.frames) without_reference += k->reference ? 0 : 1;
  report.labelled = without_reference == 0;
  if (!report.labelled)
    report.labels_note = std::to_string(without_reference) +
                         " keyframe(s) have no reference pose: no groundtruth and no outlier labels (all loop "
                         "closures are listed as potential outliers)";

  jrl::Dataset ds;
  ds.name = name_;
  ds.groundtruth.emplace();
  ds.initialization.emplace();
  ds.potential_outliers.emplace();
  ds.outliers.emplace();
  for (const char r : robots_) addRobot(r, chains, std::move(placed[r]), ds, report);
  if (!report.labelled) {
    ds.groundtruth.reset();
    ds.outliers.reset();
  }
  if (report_out) *report_out = report;
  return ds;
}

namespace {
/// `jrl_path` without its ".jrl" extension (unchanged when it has another one) followed by `suffix`.
std::string besideJrl(const std::string& jrl_path, const std::string& suffix) {
  const std::string ext = ".jrl";
  if (jrl_path.size() >= ext.size() && jrl_path.compare(jrl_path.size() - ext.size(), ext.size(), ext) == 0)
    return jrl_path.substr(0, jrl_path.size() - ext.size()) + suffix;
  return jrl_path + suffix;
}
}  // namespace

std::string DatasetRecorder::metadataPath(const std::string& jrl_path) { return besideJrl(jrl_path, ".recorder.yaml"); }

std::string DatasetRecorder::statsPath(const std::string& jrl_path) { return besideJrl(jrl_path, ".stats.txt"); }

std::string DatasetRecorder::metadataYaml(const BuildReport& report) const {
  std::ostringstream out;
  out << "# Written by the cosmo recorder next to " << name_
      << ".jrl (see include/cosmo/dataset/dataset_recorder.hpp)\n";
  out << "name: " << quoted(name_) << "\n";
  out << "robots: [";
  for (std::size_t i = 0; i < robots_.size(); ++i) out << (i ? ", " : "") << robots_[i];
  out << "]\n";
  out << "robots_without_keyframes: [";
  for (std::size_t i = 0; i < report.robots_without_keyframes.size(); ++i)
    out << (i ? ", " : "") << report.robots_without_keyframes[i];
  out << "]\n";
  out << "outlier_labels: " << (report.labelled ? "true" : "false") << "\n";
  if (!report.labelled) out << "outlier_labels_note: " << quoted(report.labels_note) << "\n";
  out << "outlier_rule: " << outlierRuleName(rule_)
      << "  # fidelity: sqrt(r^T Q^-1 r) > critical; squared: r^T Q^-1 r > critical\n";
  out << "critical_value: " << critical_value_ << "  # 95 % chi^2, 6 dof\n";
  out << "noise_models:  # the covariances of every odometry factor / loop closure and of the outlier labels\n";
  out << "  environment: " << quoted(noise_.environment) << "\n";
  out << "  file: " << quoted(noise_.source.empty() ? "(built in code)" : noise_.source) << "\n";
  out << "  provenance: " << quoted(noise_.provenance) << "\n";
  if (noise_.estimated_from) {
    const NoiseModelRecord& r = *noise_.estimated_from;
    out << "  estimated_from: {trial: " << quoted(r.trial) << ", odometry_factors: " << r.odometry_factors
        << ", loop_closures: " << r.loop_closures << ", loop_closures_left_out: " << r.loop_closures_left_out
        << ", max_translation_error: " << r.max_translation_error << ", max_rotation_error: " << r.max_rotation_error
        << "}\n";
  }
  out << "entries: " << report.entries << "\n";
  out << "odometry_factors: " << report.odometry << "\n";
  out << "intra_robot_loop_closures: " << report.intra << "\n";
  out << "inter_robot_loop_closures: " << report.inter << "\n";
  out << "outliers: " << report.outliers << "\n";
  out << "keyframes_pending: " << report.keyframes_pending << "  # after a gap in a robot's indices, not written\n";
  out << "loop_closures_pending: " << report.loop_closures_pending << "  # touching keys not written\n";
  out << "inputs_rejected: " << counts_.rejected << "\n";
  out << "bridges:";  // odometry factors across front-end restarts (include/cosmo/dataset/gap_bridge.hpp)
  if (report.bridges.empty()) out << " []";
  for (const BuildReport::Bridge& b : report.bridges)
    out << "\n  - {robot: " << b.robot << ", from: " << jrl::keyName(jrl::symbol(b.robot, b.from))
        << ", to: " << jrl::keyName(jrl::symbol(b.robot, b.to)) << ", gap_seconds: " << b.gap_seconds
        << ", rule: " << b.rule << "}";
  out << "\n";
  for (const auto& [key, value] : extra_metadata_) out << key << ": " << value << "\n";
  return out.str();
}

BuildReport DatasetRecorder::write(const std::string& path, jrl::Dataset* built) const {
  BuildReport report;
  jrl::Dataset ds = build(&report);
  jrl::writeJrl(path, ds);
  writeFileAtomically(metadataPath(path), metadataYaml(report));
  writeFileAtomically(statsPath(path),
                      jrl::formatStats(jrl::computeStats(ds)) + "\nnoise models: " + noise_.describe() + "\n");
  if (built) *built = std::move(ds);
  return report;
}

std::string DatasetRecorder::progressLine() const {
  std::ostringstream out;
  out << "keyframes";
  for (const char r : robots_) out << ' ' << r << ' ' << counts_.keyframes.at(r);
  out << " | loop closures " << counts_.loop_closures << " (intra " << counts_.intra << ", inter " << counts_.inter
      << ")";
  if (counts_.rejected) out << " | rejected " << counts_.rejected;
  return out.str();
}

}  // namespace cosmo::dataset
