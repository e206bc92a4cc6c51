#include "cosmo/jrl/dataset.hpp"

#include <array>
#include <stdexcept>

namespace cosmo::jrl {

namespace {

struct FactorTypeInfo {
  FactorType type;
  const char* tag;
  int dim;
  std::size_t measured;  // index into Measured
};

// Measured alternatives: 0 Pose3Value, 1 Pose2, 2 Point2, 3 Point3, 4 Scalar, 5 BearingRange2, 6 BearingRange3.
constexpr std::array<FactorTypeInfo, kFactorTypeCount> kFactorTypes{{
    {FactorType::PriorFactorPose3, "PriorFactorPose3", 6, 0},
    {FactorType::BetweenFactorPose3, "BetweenFactorPose3", 6, 0},
    {FactorType::PriorFactorPose2, "PriorFactorPose2", 3, 1},
    {FactorType::BetweenFactorPose2, "BetweenFactorPose2", 3, 1},
    {FactorType::PriorFactorPoint2, "PriorFactorPoint2", 2, 2},
    {FactorType::BetweenFactorPoint2, "BetweenFactorPoint2", 2, 2},
    {FactorType::PriorFactorPoint3, "PriorFactorPoint3", 3, 3},
    {FactorType::BetweenFactorPoint3, "BetweenFactorPoint3", 3, 3},
    {FactorType::RangeFactorPose2, "RangeFactorPose2", 1, 4},
    {FactorType::RangeFactorPose3, "RangeFactorPose3", 1, 4},
    {FactorType::RangeFactor2D, "RangeFactor2D", 1, 4},
    {FactorType::RangeFactor3D, "RangeFactor3D", 1, 4},
    {FactorType::BearingRangeFactorPose2, "BearingRangeFactorPose2", 2, 5},
    {FactorType::BearingRangeFactor2D, "BearingRangeFactor2D", 2, 5},
    {FactorType::BearingRangeFactorPose3, "BearingRangeFactorPose3", 3, 6},
    {FactorType::BearingRangeFactor3D, "BearingRangeFactor3D", 3, 6},
}};

const FactorTypeInfo& info(FactorType type) {
  const auto i = static_cast<std::size_t>(type);
  if (i >= kFactorTypes.size()) throw std::logic_error("jrl: invalid FactorType value");
  return kFactorTypes[i];
}

std::vector<double> flatten(const Matrix6& m) {
  std::vector<double> v(36);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) v[static_cast<std::size_t>(r * 6 + c)] = m(r, c);
  return v;
}

}  // namespace

std::string keyName(Key key) {
  const char r = robotOf(key);
  std::string s;
  if (r >= 0x21 && r <= 0x7e)
    s.push_back(r);
  else
    s = "#" + std::to_string(static_cast<unsigned>(static_cast<unsigned char>(r))) + ":";
  return s + std::to_string(indexOf(key));
}

cosmo::Pose3 Pose3Value::toPose() const { return cosmo::makePose(translation, rotation); }

Pose3Value Pose3Value::fromPose(const cosmo::Pose3& T) {
  Pose3Value v;
  v.translation = T.translation();
  v.rotation = Eigen::Quaterniond(T.linear()).normalized();
  return v;
}

const char* factorTag(FactorType type) { return info(type).tag; }

std::optional<FactorType> factorTypeFromTag(std::string_view tag) {
  for (const auto& i : kFactorTypes)
    if (tag == i.tag) return i.type;
  return std::nullopt;
}

int factorDim(FactorType type) { return info(type).dim; }

bool isPrior(FactorType type) {
  switch (type) {
    case FactorType::PriorFactorPose3:
    case FactorType::PriorFactorPose2:
    case FactorType::PriorFactorPoint2:
    case FactorType::PriorFactorPoint3: return true;
    default: return false;
  }
}

std::size_t measuredKind(FactorType type) { return info(type).measured; }

Factor Factor::priorPose3(Key key, const cosmo::Pose3& prior, const Matrix6& covariance) {
  Factor f;
  f.type = FactorType::PriorFactorPose3;
  f.keys = {key};
  f.measured = Pose3Value::fromPose(prior);
  f.covariance = flatten(covariance);
  return f;
}

Factor Factor::betweenPose3(Key key1, Key key2, const cosmo::Pose3& measured, const Matrix6& covariance) {
  Factor f;
  f.type = FactorType::BetweenFactorPose3;
  f.keys = {key1, key2};
  f.measured = Pose3Value::fromPose(measured);
  f.covariance = flatten(covariance);
  return f;
}

cosmo::Pose3 Factor::pose3() const {
  const auto* p = std::get_if<Pose3Value>(&measured);
  if (!p) throw std::logic_error(std::string("jrl: factor ") + factorTag(type) + " does not measure a Pose3");
  return p->toPose();
}

Eigen::MatrixXd Factor::covarianceMatrix() const {
  const int d = factorDim(type);
  if (covariance.size() != static_cast<std::size_t>(d * d))
    throw std::logic_error("jrl: covariance of " + std::string(factorTag(type)) + " has " +
                           std::to_string(covariance.size()) + " numbers, expected " + std::to_string(d * d));
  Eigen::MatrixXd m(d, d);
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) m(r, c) = covariance[static_cast<std::size_t>(r * d + c)];
  return m;
}

const Factor& Dataset::factor(char robot, const FactorId& id) const {
  const auto& entries = measurements.at(robot);
  if (id.entry >= entries.size() || id.measurement >= entries[id.entry].factors.size())
    throw std::out_of_range("jrl: no factor [" + std::to_string(id.entry) + "," + std::to_string(id.measurement) +
                            "] in robot " + std::string(1, robot));
  return entries[id.entry].factors[id.measurement];
}

cosmo::Pose3 pose3At(const Values& values, Key key) {
  const auto it = values.find(key);
  if (it == values.end()) throw std::out_of_range("jrl: no value for key " + keyName(key));
  const auto* p = std::get_if<Pose3Value>(&it->second);
  if (!p) throw std::logic_error("jrl: value of key " + keyName(key) + " is not a Pose3");
  return p->toPose();
}

void insertPose3(Values& values, Key key, const cosmo::Pose3& pose) { values[key] = Pose3Value::fromPose(pose); }

const char* valueTag(const Value& value) {
  static constexpr const char* kTags[] = {"Pose3", "Pose2", "Point2", "Point3", "Vector", "Scalar"};
  return kTags[value.index()];
}

}  // namespace cosmo::jrl
