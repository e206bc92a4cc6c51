#include "cosmo/nebula/jrl_assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "cosmo/dataset/dataset_recorder.hpp"

namespace cosmo::nebula {

namespace {

/// A loop closure oriented and placed: key1 is the later pose, stored in its robot's entry.
struct PlacedClosure {
  Between between;
  char owner = 'a';
  std::size_t entry = 0;
};

StampNs stampOf(const NebulaGraph& graph, jrl::Key key) {
  return graph.robots.at(jrl::robotOf(key)).stamps.at(jrl::indexOf(key));
}

void checkReference(const NebulaGraph& graph, const std::map<jrl::Key, Pose3>& reference) {
  std::size_t missing = 0;
  std::string first;
  for (const auto& [c, robot] : graph.robots)
    for (std::size_t i = 0; i < robot.stamps.size(); ++i)
      if (!reference.count(jrl::symbol(c, i)) && missing++ < 5) first += " " + jrl::keyName(jrl::symbol(c, i));
  if (missing)
    throw std::runtime_error("reference solution: no pose for " + std::to_string(missing) + " robot poses (" +
                             first.substr(1) + (missing > 5 ? ", ..." : "") + ")");
}

std::vector<PlacedClosure> placeClosures(const NebulaGraph& graph, ConversionReport& report) {
  std::vector<PlacedClosure> placed;
  placed.reserve(graph.loop_closures.size());
  for (const Between& lc : graph.loop_closures) {
    PlacedClosure p{lc, 'a', 0};
    const auto s1 = stampOf(graph, lc.key1), s2 = stampOf(graph, lc.key2);
    if (std::make_pair(s2, lc.key2) > std::make_pair(s1, lc.key1)) {
      const Matrix6 ad = adjoint(lc.measurement);
      p.between.key1 = lc.key2;
      p.between.key2 = lc.key1;
      p.between.measurement = lc.measurement.inverse();
      p.between.covariance = ad * lc.covariance * ad.transpose();
      ++report.inverted;
    }
    p.owner = jrl::robotOf(p.between.key1);
    p.entry = jrl::indexOf(p.between.key1);
    placed.push_back(std::move(p));
  }
  std::stable_sort(placed.begin(), placed.end(), [](const PlacedClosure& a, const PlacedClosure& b) {
    return std::make_tuple(a.between.key1, a.between.key2, a.between.type) <
           std::make_tuple(b.between.key1, b.between.key2, b.between.type);
  });
  return placed;
}

Pose3 truthBetween(const std::map<jrl::Key, Pose3>& reference, jrl::Key a, jrl::Key b) {
  return reference.at(a).inverse() * reference.at(b);
}

std::optional<dataset::NoiseModels> constantModels(const NebulaGraph& graph, const std::vector<PlacedClosure>& closures,
                                                   const std::map<jrl::Key, Pose3>& reference,
                                                   const ConversionParams& params, ConversionReport& report) {
  if (params.noise == NoiseSource::Recorded) return std::nullopt;
  if (params.noise == NoiseSource::Given) return params.models;
  std::vector<dataset::MeasurementWithTruth> odometry, loop_closures;
  for (const auto& [c, robot] : graph.robots)
    for (const Between& o : robot.odometry)
      odometry.push_back({o.measurement, truthBetween(reference, o.key1, o.key2)});
  for (const PlacedClosure& p : closures)
    loop_closures.push_back({p.between.measurement, truthBetween(reference, p.between.key1, p.between.key2)});
  report.estimate = estimateNoiseModels(odometry, loop_closures, params.estimation);
  report.estimate->models.environment = params.name;
  return report.estimate->models;
}

Matrix6 recordedCovariance(const Between& b) {
  dataset::checkCovariance(b.covariance, "recorded covariance of " + edgeTypeName(b.type) + " " + jrl::keyName(b.key1) +
                                             " -> " + jrl::keyName(b.key2) + " (" + b.source +
                                             "; give --noise-models or --estimate-noise-models to replace it)");
  return b.covariance;
}

/// Entries, labels, groundtruth and initialization of one robot.
void addRobot(const RobotGraph& robot, const std::vector<const PlacedClosure*>& closures,
              const std::map<jrl::Key, Pose3>& reference, const std::optional<dataset::NoiseModels>& models,
              const ConversionParams& params, jrl::Dataset& ds, ConversionReport& report) {
  const char c = robot.character;
  auto& entries = ds.measurements[c];
  auto& potential = (*ds.potential_outliers)[c];
  auto& outliers = (*ds.outliers)[c];
  auto& truth = (*ds.groundtruth)[c];
  auto& init = (*ds.initialization)[c];

  entries.resize(robot.stamps.size());
  for (std::size_t i = 0; i < robot.stamps.size(); ++i) entries[i].stamp = robot.stamps[i];
  const jrl::Key first = jrl::symbol(c, 0);
  entries[0].factors.push_back(jrl::Factor::priorPose3(first, reference.at(first), dataset::priorCovariance()));
  jrl::insertPose3(truth, first, reference.at(first));
  jrl::insertPose3(init, first, reference.at(first));

  for (std::size_t i = 1; i < robot.stamps.size(); ++i) {
    const Between& o = robot.odometry[i - 1];
    const Matrix6 cov = models ? models->odometry : recordedCovariance(o);
    entries[i].factors.push_back(jrl::Factor::betweenPose3(o.key1, o.key2, o.measurement, cov));
    jrl::insertPose3(truth, o.key2, reference.at(o.key2));
    jrl::insertPose3(init, o.key2, jrl::pose3At(init, o.key1) * o.measurement);
    ++report.odometry;
  }

  for (const PlacedClosure* p : closures) {
    const Between& b = p->between;
    const Matrix6 cov = models ? models->loop_closure : recordedCovariance(b);
    auto& factors = entries[p->entry].factors;
    const jrl::FactorId id{p->entry, factors.size()};
    factors.push_back(jrl::Factor::betweenPose3(b.key1, b.key2, b.measurement, cov));
    potential.insert(id);
    const bool inter = jrl::robotOf(b.key2) != c;
    (inter ? report.inter : report.intra)++;
    if (isOutlier(b.measurement, truthBetween(reference, b.key1, b.key2), cov, params.rule, params.critical_value)) {
      outliers.insert(id);
      (inter ? report.inter_outliers : report.intra_outliers)++;
    }
    if (!truth.count(b.key2)) {
      jrl::insertPose3(truth, b.key2, reference.at(b.key2));
      jrl::insertPose3(init, b.key2, jrl::pose3At(init, b.key1) * b.measurement);
    }
  }
}

}  // namespace

jrl::Dataset assembleJrl(const NebulaGraph& graph, const std::map<jrl::Key, Pose3>& reference,
                         const ConversionParams& params, ConversionReport* report_out) {
  ConversionReport report;
  checkReference(graph, reference);
  const std::vector<PlacedClosure> closures = placeClosures(graph, report);
  const std::optional<dataset::NoiseModels> models = constantModels(graph, closures, reference, params, report);
  report.models = models;

  jrl::Dataset ds;
  ds.name = params.name;
  ds.groundtruth.emplace();
  ds.initialization.emplace();
  ds.potential_outliers.emplace();
  ds.outliers.emplace();
  std::map<char, std::vector<const PlacedClosure*>> by_owner;
  for (const PlacedClosure& p : closures) by_owner[p.owner].push_back(&p);
  for (const auto& [c, robot] : graph.robots) {
    ds.robots.push_back(c);
    addRobot(robot, by_owner[c], reference, models, params, ds, report);
  }
  if (report_out) *report_out = std::move(report);
  return ds;
}

}  // namespace cosmo::nebula
