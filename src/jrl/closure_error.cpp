#include "cosmo/jrl/closure_error.hpp"

#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace cosmo::jrl {

namespace {

const cosmo::Pose3& truthOf(const PoseMap& gt, Key key) {
  const auto it = gt.find(key);
  if (it == gt.end()) throw std::runtime_error("no ground truth of pose " + keyName(key));
  return it->second;
}

}  // namespace

ClosureError closureError(const PoseFactor& f, const PoseMap& gt) {
  const cosmo::Pose3 truth =
      f.kind == FactorKind::Prior ? truthOf(gt, f.key1) : truthOf(gt, f.key1).inverse() * truthOf(gt, f.key2);
  const cosmo::Pose3 E = f.measured.inverse() * truth;
  ClosureError out;
  out.trans_m = E.translation().norm();
  out.rot_rad = cosmo::rotationAngle(E);
  const Vector6 r = cosmo::logSE3(E);
  const Eigen::LLT<Matrix6> llt(f.covariance);
  out.d2 = llt.info() == Eigen::Success ? r.dot(llt.solve(r)) : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace cosmo::jrl
