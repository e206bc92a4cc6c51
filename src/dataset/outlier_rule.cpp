#include "cosmo/dataset/outlier_rule.hpp"

#include <cctype>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

namespace cosmo::dataset {

const char* outlierRuleName(OutlierRule rule) { return rule == OutlierRule::Squared ? "squared" : "fidelity"; }

std::optional<OutlierRule> parseOutlierRule(const std::string& name) {
  std::string s;
  for (const char c : name) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "fidelity") return OutlierRule::Fidelity;
  if (s == "squared") return OutlierRule::Squared;
  return std::nullopt;
}

Vector6 measurementResidual(const Pose3& measurement, const Pose3& truth) {
  return logSE3(measurement.inverse(Eigen::Isometry) * truth);
}

double chi2Distance(const Pose3& measurement, const Pose3& truth, const Matrix6& cov) {
  const Vector6 r = measurementResidual(measurement, truth);
  const Eigen::LLT<Matrix6> llt(cov);
  if (llt.info() != Eigen::Success || !r.allFinite()) return std::numeric_limits<double>::infinity();
  return r.dot(llt.solve(r));
}

bool exceedsRule(double d2, OutlierRule rule, double critical_value) {
  if (!(d2 == d2)) return true;  // NaN: never call it an inlier
  return rule == OutlierRule::Squared ? d2 > critical_value : std::sqrt(d2) > critical_value;
}

bool isOutlier(const Pose3& measurement, const Pose3& truth, const Matrix6& cov, OutlierRule rule,
               double critical_value) {
  return exceedsRule(chi2Distance(measurement, truth, cov), rule, critical_value);
}

}  // namespace cosmo::dataset
