#include "cosmo/dataset/outlier_kinds.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace cosmo::dataset {

namespace {
constexpr int kPickAttempts = 1000;  // rejection sampling of one pose pair
constexpr int kDrawAttempts = 200;   // pairs tried until one gives closures that fail the rule
}  // namespace

const char* outlierKindName(OutlierKind kind) {
  switch (kind) {
    case OutlierKind::Random: return "random";
    case OutlierKind::Local: return "local";
    case OutlierKind::Group: return "group";
    case OutlierKind::Mixed: return "mixed";
  }
  return "?";
}

std::optional<OutlierKind> parseOutlierKind(const std::string& name) {
  for (OutlierKind k : {OutlierKind::Random, OutlierKind::Local, OutlierKind::Group, OutlierKind::Mixed})
    if (name == outlierKindName(k)) return k;
  return std::nullopt;
}

const char* closureScopeName(ClosureScope scope) {
  switch (scope) {
    case ClosureScope::Intra: return "intra";
    case ClosureScope::Inter: return "inter";
    case ClosureScope::Both: return "both";
  }
  return "?";
}

std::optional<ClosureScope> parseClosureScope(const std::string& name) {
  for (ClosureScope s : {ClosureScope::Intra, ClosureScope::Inter, ClosureScope::Both})
    if (name == closureScopeName(s)) return s;
  return std::nullopt;
}

OutlierDrawer::OutlierDrawer(const TeamPoses& team, const OutlierDrawParams& params, std::uint64_t seed)
    : team_(team), params_(params), rng_(seed) {
  if (team.loop_closures.empty())
    throw std::invalid_argument("the dataset has no loop closure to take the loop-closure noise model from");
  if (!(params.local_radius_m > 0.0) || !(params.local_min > 1.0) || !(params.local_max >= params.local_min))
    throw std::invalid_argument("outlier draw: local radius must be > 0 and 1 < local_min <= local_max");
  if (params.group_size < 1) throw std::invalid_argument("outlier draw: group size must be >= 1");
  bound_d_ = params.rule == OutlierRule::Fidelity ? kChi2Critical95Dof6 : std::sqrt(kChi2Critical95Dof6);
  for (const auto& [robot, poses] : team.robots)
    for (std::size_t i = 0; i < poses.size(); ++i) all_.push_back({robot, i});
}

double OutlierDrawer::uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

std::size_t OutlierDrawer::index(std::size_t n) {
  return static_cast<std::size_t>(uniform() * static_cast<double>(n)) % n;
}

double OutlierDrawer::normal() {  // Box-Muller: the same numbers with any standard library
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * uniform());
}

const TeamPose& OutlierDrawer::pose(const PoseRef& p) const { return team_.robots.at(p.robot)[p.index]; }

const jrl::PoseFactor& OutlierDrawer::pickTemplate(bool inter) {
  std::vector<const jrl::PoseFactor*> pool = team_.closures(inter);
  if (pool.empty()) pool = team_.closures(!inter);
  return *pool[index(pool.size())];
}

std::optional<std::pair<OutlierDrawer::PoseRef, OutlierDrawer::PoseRef>> OutlierDrawer::pickPair(bool inter, bool local,
                                                                                                  std::size_t shift) {
  const auto fits = [&](const PoseRef& p) { return p.index + shift < team_.robots.at(p.robot).size(); };
  const auto pairs = [&](const PoseRef& a, const PoseRef& b) {
    if (!fits(b)) return false;
    if (inter) return a.robot != b.robot;
    return a.robot == b.robot && (a.index > b.index ? a.index - b.index : b.index - a.index) >= 2;
  };
  for (int attempt = 0; attempt < kPickAttempts; ++attempt) {
    const PoseRef a = all_[index(all_.size())];
    if (!fits(a)) continue;
    if (!local) {
      const PoseRef b = all_[index(all_.size())];
      if (pairs(a, b)) return std::make_pair(a, b);
      continue;
    }
    std::vector<PoseRef> near;
    const Eigen::Vector3d& ta = pose(a).truth.translation();
    for (const PoseRef& b : all_)
      if (pairs(a, b) && (pose(b).truth.translation() - ta).norm() <= params_.local_radius_m) near.push_back(b);
    if (!near.empty()) return std::make_pair(a, near[index(near.size())]);
  }
  return std::nullopt;
}

bool OutlierDrawer::newer(const PoseRef& b, const PoseRef& a) const {
  return a.robot == b.robot ? b.index > a.index : pose(b).stamp > pose(a).stamp;
}

WrongClosure OutlierDrawer::place(const PoseRef& a, const PoseRef& b, const Pose3& claim, const Matrix6& cov,
                                  OutlierKind kind) const {
  const TeamPose& pa = pose(a);
  const TeamPose& pb = pose(b);
  const bool b_newer = newer(b, a);
  WrongClosure c;
  c.owner = b_newer ? b.robot : a.robot;
  c.entry = b_newer ? pb.entry : pa.entry;
  c.key1 = b_newer ? pb.key : pa.key;
  c.key2 = b_newer ? pa.key : pb.key;
  c.measured = b_newer ? Pose3(claim.inverse()) : claim;
  c.covariance = cov;
  c.kind = kind;
  const Pose3 truth = b_newer ? Pose3(pb.truth.inverse() * pa.truth) : Pose3(pa.truth.inverse() * pb.truth);
  c.d2 = chi2Distance(c.measured, truth, cov);
  return c;
}

std::vector<WrongClosure> OutlierDrawer::tryDraw(OutlierKind kind, bool inter, std::size_t size) {
  const jrl::PoseFactor& tpl = pickTemplate(inter);
  const auto pair = pickPair(inter, kind == OutlierKind::Local, size - 1);
  if (!pair) return {};
  const auto& [a, b] = *pair;
  std::vector<WrongClosure> out;
  if (kind == OutlierKind::Local) {  // the truth moved by m bounds along a random whitened direction
    Vector6 u;
    for (int i = 0; i < 6; ++i) u(i) = normal();
    const double m = bound_d_ * (params_.local_min + (params_.local_max - params_.local_min) * uniform());
    const Matrix6 L = Eigen::LLT<Matrix6>(tpl.covariance).matrixL();
    const PoseRef& k1 = newer(b, a) ? b : a;  // measured as stored (key1 the newer pose), so that d = m
    const PoseRef& k2 = newer(b, a) ? a : b;
    const Pose3 truth = pose(k1).truth.inverse() * pose(k2).truth;
    out.push_back(place(k1, k2, truth * expSE3(m * (L * u.normalized())), tpl.covariance, kind));
  } else {  // the template's claim between a_0 and b_0, carried along both trajectories for a group
    for (std::size_t k = 0; k < size; ++k) {
      const PoseRef ak{a.robot, a.index + k}, bk{b.robot, b.index + k};
      const Pose3 A = pose(a).truth.inverse() * pose(ak).truth;
      const Pose3 B = pose(b).truth.inverse() * pose(bk).truth;
      out.push_back(place(ak, bk, A.inverse() * tpl.measured * B, tpl.covariance, kind));
    }
  }
  for (const WrongClosure& c : out)
    if (!exceedsRule(c.d2, params_.rule)) return {};
  return out;
}

std::vector<WrongClosure> OutlierDrawer::draw(OutlierKind kind, bool inter, std::size_t max_size) {
  if (kind == OutlierKind::Mixed) {
    const OutlierKind kinds[] = {OutlierKind::Random, OutlierKind::Local, OutlierKind::Group};
    kind = kinds[index(3)];
  }
  const std::size_t size = kind == OutlierKind::Group ? std::max<std::size_t>(1, std::min(params_.group_size, max_size)) : 1;
  for (int attempt = 0; attempt < kDrawAttempts; ++attempt) {
    std::vector<WrongClosure> out = tryDraw(kind, inter, size);
    if (!out.empty()) return out;
  }
  throw std::runtime_error(std::string("cannot draw ") + outlierKindName(kind) + (inter ? " inter" : " intra") +
                           "-robot outliers" + (size > 1 ? " in groups of " + std::to_string(size) : "") +
                           ": no pose pair of the team fits (" +
                           (kind == OutlierKind::Local ? "poses within " + std::to_string(params_.local_radius_m) + " m, " : "") +
                           (inter ? "two robots" : "one robot, 2 indices apart") + ")");
}

}  // namespace cosmo::dataset
