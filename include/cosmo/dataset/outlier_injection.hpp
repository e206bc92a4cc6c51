#pragma once
// Injected outliers: a labelled dataset with added loop closures that are wrong by one of the rules of
// dataset/outlier_kinds.hpp, for sweeps of robust back-ends over outlier rates (`cosmo_jrl inject`).
//
// Rate. N loop closures in scope (intra-robot, inter-robot or both) of which `natural` are labelled outliers; n
// closures are added. RateOf::Injected (default): n / (N + n) = rate, i.e. n = round(rate * N / (1 - rate)): the
// share of injected closures among the loop closures in scope after injection, the natural outliers left as they
// are (riSAM's g2o-2-irl counts its percentages the same way). RateOf::All: (natural + n) / (N + n) = rate, the
// share of every labelled outlier in scope; a rate below the natural share is refused. Either way the measured
// share is within one closure of the rate.
// With scope Both each draw is intra- or inter-robot in proportion to the dataset's own intra and inter closures.
//
// Output. Each closure is appended to the end of its entry (every existing FactorId stays valid), listed in both
// potential_outlier_factors and outlier_factors, carries the covariance of a loop closure of the dataset, and its
// teammate key (inter-robot) is added to the owner's ground truth (the owner's value) and initialization (through
// the robot's first closure referring to it, jrl.md §10). Nothing else changes: the labelled inliers are the same
// factors in the same order, so their solve is unchanged. Deterministic in the seed.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cosmo/dataset/outlier_kinds.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::dataset {

enum class RateOf { Injected, All };

struct InjectionParams {
  double rate = 0.1;  ///< in [0, 1)
  OutlierKind kind = OutlierKind::Random;
  ClosureScope scope = ClosureScope::Both;
  RateOf rate_of = RateOf::Injected;
  std::uint64_t seed = 0;
  OutlierDrawParams draw;  ///< label rule, local radius and error, group size
};

struct InjectionReport {
  std::size_t closures_before = 0;  ///< loop closures in scope before
  std::size_t natural_outliers = 0; ///< of those, labelled outliers
  std::size_t injected = 0;
  std::size_t groups = 0;            ///< draws (a group counts once)
  std::size_t injected_random = 0, injected_local = 0, injected_group = 0;
  std::size_t injected_intra = 0, injected_inter = 0;
  std::vector<std::pair<char, jrl::FactorId>> ids;  ///< every injected factor

  std::size_t closuresAfter() const { return closures_before + injected; }
  double injectedShare() const;  ///< injected / closures after
  double outlierShare() const;   ///< (natural + injected) / closures after
};

/// How many closures to add for `rate` to N closures with `natural` labelled outliers. Throws
/// std::invalid_argument for a rate outside [0, 1), or (RateOf::All) below the natural share.
std::size_t injectedCount(double rate, RateOf rate_of, std::size_t closures, std::size_t natural);

/// `dataset` with the injected outliers. Throws std::invalid_argument when the dataset has no ground truth, no
/// outlier labels, no loop closure in scope, or the rate is out of range; std::runtime_error when the kind finds no
/// pose pair (OutlierDrawer::draw).
jrl::Dataset injectOutliers(const jrl::Dataset& dataset, const InjectionParams& params,
                            InjectionReport* report = nullptr);

/// One line: "injected 42 random outliers (30 intra, 12 inter) into 356 loop closures with 48 labelled outliers:
/// 10.6 % injected, 20.4 % outliers".
std::string formatInjection(const InjectionReport& report, OutlierKind kind);

}  // namespace cosmo::dataset
