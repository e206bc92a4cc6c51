#pragma once
// Outlier labels of loop closures (spec section 6): a measurement m of a relative pose whose reference value
// is m* has the residual r = Log(m^-1 * m*) (GTSAM tangent order, rotation first) and the squared Mahalanobis
// distance d^2 = r^T Q^-1 r under the loop-closure covariance Q. With the 95 % chi^2 critical value for 6
// degrees of freedom (12.592):
//   Fidelity (default): outlier iff sqrt(d^2) > 12.592  -- what every released COSMO-Bench file follows
//   Squared:            outlier iff d^2 > 12.592        -- the textbook chi^2 test
#include <optional>
#include <string>

#include "cosmo/common/pose.hpp"

namespace cosmo::dataset {

enum class OutlierRule { Fidelity, Squared };

/// 95 % quantile of chi^2 with 6 degrees of freedom.
constexpr double kChi2Critical95Dof6 = 12.592;

/// "fidelity" / "squared".
const char* outlierRuleName(OutlierRule rule);
/// Parse "fidelity" / "squared" (case-insensitive); nullopt otherwise.
std::optional<OutlierRule> parseOutlierRule(const std::string& name);

/// r = Log(measurement^-1 * truth), [rx, ry, rz, tx, ty, tz].
Vector6 measurementResidual(const Pose3& measurement, const Pose3& truth);
/// d^2 = r^T cov^-1 r with r = measurementResidual(measurement, truth) (chi^2 distributed with 6 dof for an
/// inlier whose error follows cov). +Inf when cov is not positive definite.
double chi2Distance(const Pose3& measurement, const Pose3& truth, const Matrix6& cov);
/// True when the squared distance d2 fails `rule` at `critical_value`.
bool exceedsRule(double d2, OutlierRule rule, double critical_value = kChi2Critical95Dof6);
/// exceedsRule(chi2Distance(measurement, truth, cov), rule, critical_value).
bool isOutlier(const Pose3& measurement, const Pose3& truth, const Matrix6& cov,
               OutlierRule rule = OutlierRule::Fidelity, double critical_value = kChi2Critical95Dof6);

}  // namespace cosmo::dataset
