#pragma once
// LAMP's covariances list the tangent coordinates translation first, (x, y, z, rx, ry, rz) (the message comment
// of PoseGraphNode / PoseGraphEdge, and g2o's EDGE_SE3:QUAT information matrix); JRL and GTSAM put rotation
// first, [rx, ry, rz, tx, ty, tz]. Converting swaps the two 3x3 blocks on both sides: Σ_jrl = P Σ_lamp Pᵀ with
// P the block swap, which is its own inverse.
#include <array>

#include "cosmo/common/pose.hpp"

namespace cosmo::nebula {

/// Which order a dataset's recorded covariances use (the default is what the message definition states).
enum class CovarianceOrder { TranslationFirst, RotationFirst };

/// Swap the translation and rotation blocks of a 6x6 matrix (either direction).
Matrix6 swapTranslationRotation(const Matrix6& m);

/// A message's 36 numbers (row by row, in `order`) as a JRL covariance (rotation first).
Matrix6 toJrlCovariance(const std::array<double, 36>& values,
                        CovarianceOrder order = CovarianceOrder::TranslationFirst);
/// A JRL covariance as 36 numbers in LAMP's translation-first order (what a LAMP message would carry).
std::array<double, 36> toLampCovariance(const Matrix6& jrl_covariance);

/// Adjoint of a pose in GTSAM's order [[R, 0], [t^ R, R]]: the covariance of T^-1 is Ad_T Σ Ad_Tᵀ when Σ is
/// T's (right-perturbation) covariance.
Matrix6 adjoint(const Pose3& T);

}  // namespace cosmo::nebula
