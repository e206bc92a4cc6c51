#include "cosmo/dataset/outlier_injection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

namespace cosmo::dataset {

namespace {

bool inScope(const jrl::PoseFactor& f, ClosureScope scope) {
  const bool inter = f.kind == jrl::FactorKind::InterRobotLoopClosure;
  return scope == ClosureScope::Both || inter == (scope == ClosureScope::Inter);
}

/// The draws, n closures in all: intra or inter per draw as the scope says (Both: in the dataset's proportion,
/// the other scope when the drawn one has no fitting pose pair).
std::vector<WrongClosure> drawClosures(const TeamPoses& team, const InjectionParams& p, std::size_t n,
                                       InjectionReport& report) {
  const std::size_t intra = team.closures(false).size(), inter = team.closures(true).size();
  OutlierDrawer drawer(team, p.draw, p.seed);
  std::vector<WrongClosure> added;
  while (added.size() < n) {
    bool want_inter = p.scope == ClosureScope::Inter;
    if (p.scope == ClosureScope::Both) want_inter = drawer.uniform() * static_cast<double>(intra + inter) >= double(intra);
    std::vector<WrongClosure> group;
    try {
      group = drawer.draw(p.kind, want_inter, n - added.size());
    } catch (const std::runtime_error&) {
      if (p.scope != ClosureScope::Both) throw;
      group = drawer.draw(p.kind, !want_inter, n - added.size());
    }
    ++report.groups;
    added.insert(added.end(), group.begin(), group.end());
  }
  return added;
}

const jrl::Value* findValue(const std::map<char, jrl::Values>& values, jrl::Key key) {
  const auto owner = values.find(jrl::robotOf(key));
  if (owner != values.end() && owner->second.count(key)) return &owner->second.at(key);
  for (const auto& [robot, vals] : values)
    if (vals.count(key)) return &vals.at(key);
  return nullptr;
}

/// A teammate key of an injected closure: in the robot's ground truth (the owner's value) and initialization
/// (through the robot's first closure referring to it, when that closure is an injected one).
void addTeammateValues(jrl::Dataset& d, const jrl::Dataset& in, char robot, jrl::Key key,
                       const std::set<jrl::FactorId>& injected) {
  if (const jrl::Value* gt = findValue(*in.groundtruth, key)) (*d.groundtruth)[robot].emplace(key, *gt);
  if (!d.initialization) return;
  const auto& entries = d.measurements.at(robot);
  for (std::size_t e = 0; e < entries.size(); ++e)
    for (std::size_t m = 0; m < entries[e].factors.size(); ++m) {
      const jrl::Factor& f = entries[e].factors[m];
      if (!f.isBetweenPose3() || (f.keys.front() != key && f.keys.back() != key)) continue;
      if (!injected.count(jrl::FactorId{e, m})) return;  // a closure of the dataset comes first: keep its value
      jrl::Values& init = (*d.initialization)[robot];
      const bool second = f.keys.back() == key;
      const jrl::Key other = second ? f.keys.front() : f.keys.back();
      const Pose3 from = jrl::pose3At(init, other);
      jrl::insertPose3(init, key, second ? Pose3(from * f.pose3()) : Pose3(from * f.pose3().inverse()));
      return;
    }
}

}  // namespace

double InjectionReport::injectedShare() const {
  return closuresAfter() ? static_cast<double>(injected) / static_cast<double>(closuresAfter()) : 0.0;
}

double InjectionReport::outlierShare() const {
  return closuresAfter() ? static_cast<double>(natural_outliers + injected) / static_cast<double>(closuresAfter())
                         : 0.0;
}

std::size_t injectedCount(double rate, RateOf rate_of, std::size_t closures, std::size_t natural) {
  if (!(rate >= 0.0 && rate < 1.0)) throw std::invalid_argument("the outlier rate must be in [0, 1)");
  const double n = static_cast<double>(closures);
  const double target = rate_of == RateOf::Injected ? rate * n / (1.0 - rate)
                                                    : (rate * n - static_cast<double>(natural)) / (1.0 - rate);
  if (target < -0.5) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the loop closures in scope already hold %.1f %% labelled outliers, more than %.1f %%",
                  100.0 * static_cast<double>(natural) / n, 100.0 * rate);
    throw std::invalid_argument(buf);
  }
  return static_cast<std::size_t>(std::llround(std::max(0.0, target)));
}

jrl::Dataset injectOutliers(const jrl::Dataset& in, const InjectionParams& p, InjectionReport* report_out) {
  if (!in.groundtruth) throw std::invalid_argument(in.name + ": no ground truth, so no closure can be made wrong");
  if (!in.outliers || !in.potential_outliers)
    throw std::invalid_argument(in.name + ": no outlier labels (outlier_factors, potential_outlier_factors)");
  const TeamPoses team = teamPoses(jrl::poseGraph(in));
  InjectionReport report;
  for (const jrl::PoseFactor& f : team.loop_closures)
    if (inScope(f, p.scope)) {
      ++report.closures_before;
      report.natural_outliers += f.outlier ? 1 : 0;
    }
  if (report.closures_before == 0)
    throw std::invalid_argument(in.name + ": no " + (p.scope == ClosureScope::Both ? "" : closureScopeName(p.scope)) +
                                (p.scope == ClosureScope::Both ? "" : "-robot ") + "loop closures to add outliers to");
  const std::size_t n = injectedCount(p.rate, p.rate_of, report.closures_before, report.natural_outliers);

  jrl::Dataset out = in;
  std::map<char, std::set<jrl::FactorId>> injected;
  for (const WrongClosure& c : drawClosures(team, p, n, report)) {
    jrl::Entry& entry = out.measurements.at(c.owner).at(c.entry);
    const jrl::FactorId id{c.entry, entry.factors.size()};
    entry.factors.push_back(jrl::Factor::betweenPose3(c.key1, c.key2, c.measured, c.covariance));
    (*out.potential_outliers)[c.owner].insert(id);
    (*out.outliers)[c.owner].insert(id);
    injected[c.owner].insert(id);
    report.ids.emplace_back(c.owner, id);
    ++report.injected;
    ++(c.kind == OutlierKind::Local ? report.injected_local
                                    : c.kind == OutlierKind::Group ? report.injected_group : report.injected_random);
    ++(jrl::robotOf(c.key2) == c.owner ? report.injected_intra : report.injected_inter);
  }
  for (const auto& [robot, ids] : injected)
    for (const jrl::FactorId& id : ids) {
      const jrl::Key key2 = out.measurements.at(robot)[id.entry].factors[id.measurement].keys.back();
      if (jrl::robotOf(key2) != robot) addTeammateValues(out, in, robot, key2, ids);
    }
  if (report_out) *report_out = std::move(report);
  return out;
}

std::string formatInjection(const InjectionReport& r, OutlierKind kind) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "injected %zu %s outliers (%zu intra, %zu inter; %zu random, %zu local, %zu in groups; %zu draws) into "
                "%zu loop closures with %zu labelled outliers: %.1f %% injected, %.1f %% outliers",
                r.injected, outlierKindName(kind), r.injected_intra, r.injected_inter, r.injected_random,
                r.injected_local, r.injected_group, r.groups, r.closures_before, r.natural_outliers,
                100.0 * r.injectedShare(), 100.0 * r.outlierShare());
  return buf;
}

}  // namespace cosmo::dataset
