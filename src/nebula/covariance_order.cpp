#include "cosmo/nebula/covariance_order.hpp"

namespace cosmo::nebula {

Matrix6 swapTranslationRotation(const Matrix6& m) {
  Matrix6 out;
  out.topLeftCorner<3, 3>() = m.bottomRightCorner<3, 3>();
  out.bottomRightCorner<3, 3>() = m.topLeftCorner<3, 3>();
  out.topRightCorner<3, 3>() = m.bottomLeftCorner<3, 3>();
  out.bottomLeftCorner<3, 3>() = m.topRightCorner<3, 3>();
  return out;
}

Matrix6 toJrlCovariance(const std::array<double, 36>& values, CovarianceOrder order) {
  Matrix6 m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = values[static_cast<std::size_t>(6 * r + c)];
  return order == CovarianceOrder::TranslationFirst ? swapTranslationRotation(m) : m;
}

std::array<double, 36> toLampCovariance(const Matrix6& jrl_covariance) {
  const Matrix6 m = swapTranslationRotation(jrl_covariance);
  std::array<double, 36> out{};
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) out[static_cast<std::size_t>(6 * r + c)] = m(r, c);
  return out;
}

Matrix6 adjoint(const Pose3& T) {
  const Eigen::Matrix3d R = T.linear();
  Matrix6 ad = Matrix6::Zero();
  ad.topLeftCorner<3, 3>() = R;
  ad.bottomRightCorner<3, 3>() = R;
  ad.bottomLeftCorner<3, 3>() = skew(T.translation()) * R;
  return ad;
}

}  // namespace cosmo::nebula
