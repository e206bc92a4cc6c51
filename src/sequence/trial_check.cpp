#include "cosmo/sequence/trial_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cosmo/sequence/trial_coverage.hpp"

namespace cosmo::sequence {

namespace {

std::string fmt(const char* format, double a, double b = 0.0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

/// Median spacing of the scans' stamps, as a rate (Hz); 0 with fewer than two scans.
double scanRate(const std::vector<Scan>& scans) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < scans.size(); ++i)
    if (scans[i].stamp > scans[i - 1].stamp) dt.push_back(toSeconds(scans[i].stamp - scans[i - 1].stamp));
  if (dt.empty()) return 0.0;
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return 1.0 / dt[dt.size() / 2];
}

bool isReturn(const Eigen::Vector3f& p) { return p.allFinite() && !(p.x() == 0.0f && p.y() == 0.0f && p.z() == 0.0f); }

double referenceRate(const Trajectory& ref) {
  if (ref.size() < 2) return 0.0;
  return static_cast<double>(ref.size() - 1) / toSeconds(ref.endStamp() - ref.startStamp());
}

}  // namespace

TrialCheck checkTrial(const TrialConfig& trial, const TrialProbe& probe, const Trajectory& reference,
                      const std::string& reference_error, const std::string& noise_models) {
  TrialCheck c;
  c.robot = trial.robot;
  std::ostringstream line;
  line << "robot " << trial.robot << "  " << trial.name << ": ";
  if (probe.bag != BagState::Ok) {
    switch (probe.bag) {
      case BagState::Missing: line << "bag NOT FOUND " << trial.bag; break;
      case BagState::Unreadable: line << "bag UNREADABLE " << trial.bag; break;
      case BagState::NotABag: line << "NOT A BAG " << trial.bag; break;
      case BagState::Damaged: line << "bag DAMAGED " << trial.bag; break;
      case BagState::Empty: line << "bag EMPTY " << trial.bag << " (a recording of no messages)"; break;
      case BagState::Ok: break;
    }
    c.errors.push_back(trial.name + ": " + (probe.error.empty() ? "bag not found: " + trial.bag : probe.error));
    c.line = line.str();
    return c;
  }
  line << "bag ok";
  if (!probe.topic_found) {
    line << ", topic " << trial.topic << " MISSING (the bag has:";
    for (const auto& t : probe.topics) line << " " << t;
    line << ")";
    c.errors.push_back(trial.name + ": " +
                       (probe.error.empty() ? "no topic " + trial.topic + " in " + trial.bag : probe.error));
    c.line = line.str();
    return c;
  }
  line << ", topic " << trial.topic << " (" << probe.messages << " scans)";
  if (!probe.error.empty()) {
    line << ", UNREADABLE: " << probe.error;
    c.errors.push_back(trial.name + ": " + probe.error);
    c.line = line.str();
    return c;
  }
  if (probe.messages == 0) {
    line << ": EMPTY";
    c.errors.push_back(trial.name + ": topic " + trial.topic + " of " + trial.bag +
                       " holds no messages (record the trial again or name the topic that holds its scans)");
    c.line = line.str();
    return c;
  }
  line << ", fields " << probe.fields;
  const double rate = scanRate(probe.first_scans);
  line << ", " << fmt("%.1f Hz", rate) << ", stamp " << (trial.stamp_at_end ? "end" : "start");
  std::size_t returns = 0;
  for (const Scan& s : probe.first_scans)
    for (const auto& p : s.points) returns += isReturn(p);
  if (probe.points_in_messages > 0)
    line << ", invalid returns "
         << fmt("%.1f %%",
                100.0 * (1.0 - static_cast<double>(returns) / static_cast<double>(probe.points_in_messages)));
  if (returns == 0) c.errors.push_back(trial.name + ": the first scans hold no valid point");

  if (reference.empty()) {
    line << ", reference NONE";
    c.errors.push_back(trial.name + ": " +
                       (reference_error.empty() ? "no reference: the dataset would have no "
                                                  "groundtruth and no outlier labels"
                                                : reference_error));
  } else {
    const double before = std::max(0.0, toSeconds(reference.startStamp()) - toSeconds(probe.first_stamp));
    const double after = std::max(0.0, toSeconds(probe.last_stamp) - toSeconds(reference.endStamp()));
    line << ", reference " << fmt("%.1f Hz", referenceRate(reference)) << " over "
         << fmt("%.1f s", toSeconds(reference.endStamp() - reference.startStamp())) << " of the scans' "
         << fmt("%.1f s", toSeconds(probe.last_stamp - probe.first_stamp)) << " (uncovered "
         << fmt("%.1f s at the start, %.1f s at the end)", before, after);
    try {
      TrialCoverage(trial.name, reference).clip({trial.robot, probe.first_stamp, probe.last_stamp});
    } catch (const std::exception& e) { c.errors.push_back(e.what()); }
  }
  line << ", extrinsic rotation " << fmt("%.2f deg", rotationAngle(trial.extrinsic) * 180.0 / M_PI);
  line << ", noise models "
       << (noise_models.empty() ? std::string("none: the run stops (see cosmo_generate --estimate-noise-models)")
                                : noise_models);
  c.line = line.str();
  return c;
}

bool formatChecks(const std::vector<TrialCheck>& checks, std::string& text) {
  std::ostringstream out;
  std::vector<std::string> errors;
  for (const auto& c : checks) {
    out << c.line << "\n";
    errors.insert(errors.end(), c.errors.begin(), c.errors.end());
  }
  if (errors.empty()) {
    out << "ok: every trial has scans and a reference over them: the dataset will be labelled\n";
  } else {
    out << "cannot produce a labelled dataset:\n";
    for (const auto& e : errors) out << "  " << e << "\n";
  }
  text = out.str();
  return errors.empty();
}

}  // namespace cosmo::sequence
