#include "cosmo/nebula/synthetic_team.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "cosmo/nebula/covariance_order.hpp"

namespace cosmo::nebula {

namespace {

/// Dense covariances (rotation first) with distinct blocks, so that a wrong block order shows.
Matrix6 denseCovariance(double sigma_rot, double sigma_trans) {
  Matrix6 L = Matrix6::Zero();
  L.diagonal() << sigma_rot, 1.3 * sigma_rot, 0.8 * sigma_rot, sigma_trans, 1.2 * sigma_trans, 0.6 * sigma_trans;
  L(3, 0) = 0.3 * sigma_trans;  // tx correlated with rx
  L(5, 2) = 0.2 * sigma_trans;
  L(1, 0) = 0.2 * sigma_rot;
  return L * L.transpose();
}

Pose3 noisy(const Pose3& truth, const Matrix6& covariance, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vector6 z;
  for (int i = 0; i < 6; ++i) z(i) = n(rng);
  const Matrix6 L = covariance.llt().matrixL();
  return truth * expSE3(L * z);
}

Pose3 wrongBy(const Pose3& truth, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), dist(1.5, 4.0), angle(0.2, 0.5);
  Eigen::Vector3d dir(u(rng), u(rng), 0.3 * u(rng)), axis(u(rng), u(rng), u(rng) + 2.0);
  Vector6 xi;
  xi << angle(rng) * axis.normalized(), dist(rng) * dir.normalized();
  return truth * expSE3(xi);
}

PoseGraphEdge edge(jrl::Key from, jrl::Key to, std::int32_t type, const Pose3& measurement, const Matrix6& cov) {
  PoseGraphEdge e;
  e.key_from = from;
  e.key_to = to;
  e.type = type;
  e.pose = PoseMsg::fromPose(measurement);
  e.covariance = toLampCovariance(cov);
  return e;
}

PoseGraphNode node(jrl::Key key, StampNs stamp, const Pose3& pose, const std::string& id = "") {
  PoseGraphNode n;
  n.header.sec = static_cast<std::uint32_t>(stamp / 1'000'000'000ull);
  n.header.nsec = static_cast<std::uint32_t>(stamp % 1'000'000'000ull);
  n.header.frame_id = "world";
  n.key = key;
  n.id = id;
  n.pose = PoseMsg::fromPose(pose);
  n.covariance = toLampCovariance(Matrix6::Identity() * 1e-4);
  return n;
}

/// What one robot publishes at its pose i (new node and the edges made then).
struct Step {
  std::vector<PoseGraphNode> nodes;
  std::vector<PoseGraphEdge> edges;
};
using Steps = std::map<char, std::vector<Step>>;

/// Reference trajectories (laps of a circle per robot, alternate robots the other way round, gently rolling) and
/// stamps.
void makeTrajectories(const SyntheticTeamParams& params, SyntheticTeam& team, std::mt19937_64& rng) {
  std::normal_distribution<double> turn(0.0, 0.12), climb(0.0, 0.01);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < params.robots.size(); ++k) {
    const auto& [name, c] = params.robots[k];
    team.names[c] = name;
    const double radius = 20.0 + 2.5 * double(k), direction = k % 2 ? -1.0 : 1.0;
    double theta = 0.7 * double(k), t = params.start_spacing_s * double(k);
    for (std::size_t i = 0; i < params.poses_per_robot; ++i) {
      const double yaw = theta + direction * M_PI / 2 + turn(rng) * 0.2;
      team.truth[jrl::symbol(c, i)] = makePose(radius * std::cos(theta), radius * std::sin(theta),
                                               0.5 * std::sin(3.0 * theta), climb(rng), climb(rng), yaw);
      team.stamps[c].push_back(params.first_stamp + toStampNs(t));
      theta += direction * params.step_m / radius;
      t += params.period_s + 0.5 * unit(rng);
    }
  }
}

/// An IMU attitude edge: a unit vector in the position, no rotation (quaternion all zero).
PoseGraphEdge imuEdge(jrl::Key key) {
  PoseGraphEdge imu;
  imu.key_from = imu.key_to = key;
  imu.type = kImu;
  imu.pose.position = {0.0, 0.0, 1.0};
  imu.pose.orientation = {0.0, 0.0, 0.0, 0.0};
  return imu;
}

/// An artifact and a UWB anchor seen from robot c's pose `key` (number `landmark`, counted up).
void addLandmarks(char c, jrl::Key key, StampNs stamp, std::size_t& landmark, SyntheticTeam& team, Step& s) {
  const Pose3& T = team.truth.at(key);
  const jrl::Key artifact = jrl::symbol(static_cast<char>(std::toupper(c)), landmark);
  const jrl::Key anchor = jrl::symbol('u', landmark++);
  const Pose3 A = T * makePose(4.0, 1.0, 0.5, 0, 0, 0), U = T * makePose(-2.0, 3.0, 1.0, 0, 0, 0);
  team.landmarks[artifact] = A;
  team.landmarks[anchor] = U;
  s.nodes.push_back(node(artifact, stamp, A, "artifact-" + std::to_string(landmark)));
  s.nodes.push_back(node(anchor, stamp, U, "uwb-" + std::to_string(landmark)));
  s.edges.push_back(edge(key, artifact, kArtifact, T.inverse() * A, Matrix6::Identity() * 0.01));
  PoseGraphEdge range = edge(key, anchor, kUwbRange, Pose3::Identity(), Matrix6::Identity());
  range.range = (U.translation() - T.translation()).norm();
  range.range_error = 0.1;
  s.edges.push_back(range);
  s.edges.push_back(edge(key, anchor, kUwbBetween, T.inverse() * U, Matrix6::Identity() * 0.01));
  team.other_edges["ARTIFACT"] += 1;
  team.other_edges["UWB_RANGE"] += 1;
  team.other_edges["UWB_BETWEEN"] += 1;
}

/// What each robot publishes at each pose: its node, the prior or odometry, IMU and landmarks now and then.
Steps makeSteps(const SyntheticTeamParams& params, SyntheticTeam& team, std::mt19937_64& rng) {
  Steps steps;
  std::size_t landmark = 0;
  for (const auto& [name, c] : params.robots) {
    auto& list = steps[c];
    list.resize(params.poses_per_robot);
    for (std::size_t i = 0; i < params.poses_per_robot; ++i) {
      const jrl::Key key = jrl::symbol(c, i);
      const Pose3& T = team.truth.at(key);
      Step& s = list[i];
      s.nodes.push_back(node(key, team.stamps[c][i], T));
      if (i == 0) {
        s.edges.push_back(edge(key, key, kPrior, T, Matrix6::Identity() * 1e-6));
        ++team.other_edges["PRIOR"];
      } else {
        const jrl::Key prev = jrl::symbol(c, i - 1);
        const Pose3 m = noisy(team.truth.at(prev).inverse() * T, team.odometry_covariance, rng);
        s.edges.push_back(edge(prev, key, kOdom, m, team.odometry_covariance));
        team.g2o_edges[name].push_back({prev, key, m, team.odometry_covariance, 0});
      }
      if (i % 10 == 5) {
        s.edges.push_back(imuEdge(key));
        ++team.other_edges["IMU"];
      }
      if (i % 25 == 12) addLandmarks(c, key, team.stamps[c][i], landmark, team, s);
    }
  }
  return steps;
}

/// Loop closures (random orientation, one per pose pair; a known share wrong) and inter-robot ranges.
class ClosureMaker {
 public:
  ClosureMaker(const SyntheticTeamParams& params, SyntheticTeam& team, Steps& steps, std::mt19937_64& rng)
      : params_(params), team_(team), steps_(steps), rng_(rng) {}

  void run() {
    for (const auto& [name, c] : params_.robots)
      for (std::size_t i = 8; i < params_.poses_per_robot; ++i) closeAt(name, c, i);
  }

 private:
  double unit() { return unit_(rng_); }

  /// A random pose of robot `c` among 0..end-1 within 25 m of `key` (where a real closure could be found).
  std::optional<jrl::Key> nearby(jrl::Key key, char c, std::size_t end) {
    std::vector<jrl::Key> candidates;
    for (std::size_t j = 0; j < end; ++j)
      if ((team_.truth.at(jrl::symbol(c, j)).translation() - team_.truth.at(key).translation()).norm() < 25.0)
        candidates.push_back(jrl::symbol(c, j));
    if (candidates.empty()) return std::nullopt;
    return candidates[static_cast<std::size_t>(unit() * double(candidates.size())) % candidates.size()];
  }

  /// A closure between `key` (robot c's pose i) and `other`, once per pair; false when the pair has one.
  bool close(const std::string& name, char c, std::size_t i, jrl::Key key, jrl::Key other, std::int32_t type) {
    if (!closed_.insert({std::min(key, other), std::max(key, other)}).second) return false;
    const bool forward = unit() < 0.5;
    const jrl::Key from = forward ? key : other, to = forward ? other : key;
    const Pose3 truth = team_.truth.at(from).inverse() * team_.truth.at(to);
    const bool wrong = unit() < params_.wrong_ratio;
    const Pose3 m = wrong ? wrongBy(truth, rng_) : noisy(truth, team_.loop_closure_covariance, rng_);
    if (wrong) team_.wrong_closures.insert({from, to});
    steps_[c][i].edges.push_back(edge(from, to, type, m, team_.loop_closure_covariance));
    team_.g2o_edges[name].push_back({from, to, m, team_.loop_closure_covariance, 0});
    return true;
  }

  void closeAt(const std::string& name, char c, std::size_t i) {
    const jrl::Key key = jrl::symbol(c, i);
    if (unit() < params_.lc_probability) {
      const auto j = nearby(key, c, i - 5);
      if (j && close(name, c, i, key, *j, kLoopClose)) ++team_.intra;
    }
    if (params_.robots.size() > 1 && unit() < params_.irlc_probability) {
      char other = c;
      while (other == c)
        other = params_.robots[static_cast<std::size_t>(unit() * params_.robots.size()) % params_.robots.size()].second;
      const auto j = nearby(key, other, params_.poses_per_robot);
      if (!j) return;
      const jrl::Key key2 = *j;
      const std::int32_t type = unit() < 0.5 ? kInterRobotBetween : kLoopClose;
      if (close(name, c, i, key, key2, type)) ++team_.inter;
      if (i % 4 == 0) {
        PoseGraphEdge range = edge(key, key2, kInterRobotRange, Pose3::Identity(), Matrix6::Identity());
        range.range = (team_.truth.at(key).translation() - team_.truth.at(key2).translation()).norm();
        range.range_error = 0.2;
        steps_[c][i].edges.push_back(range);
        ++team_.other_edges["INTERROB_RANGE"];
      }
    }
  }

  const SyntheticTeamParams& params_;
  SyntheticTeam& team_;
  Steps& steps_;
  std::mt19937_64& rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::set<std::pair<jrl::Key, jrl::Key>> closed_;
};

/// Incremental messages: every poses_per_message poses; halfway a full re-publication; the last node of a message
/// repeated in the next one.
void makeMessages(const SyntheticTeamParams& params, const Steps& steps, SyntheticTeam& team) {
  for (const auto& [name, c] : params.robots) {
    auto& out = team.messages[name];
    const std::vector<Step>& list = steps.at(c);
    std::uint32_t seq = 0;
    PoseGraph all;
    all.incremental = false;
    for (std::size_t begin = 0; begin < params.poses_per_robot; begin += params.poses_per_message) {
      const std::size_t end = std::min(begin + params.poses_per_message, params.poses_per_robot);
      PoseGraph msg;
      msg.incremental = true;
      if (begin > 0) msg.nodes.push_back(list[begin - 1].nodes.front());
      for (std::size_t i = begin; i < end; ++i) {
        const Step& s = list[i];
        msg.nodes.insert(msg.nodes.end(), s.nodes.begin(), s.nodes.end());
        msg.edges.insert(msg.edges.end(), s.edges.begin(), s.edges.end());
        all.nodes.insert(all.nodes.end(), s.nodes.begin(), s.nodes.end());
        all.edges.insert(all.edges.end(), s.edges.begin(), s.edges.end());
      }
      msg.header = list[end - 1].nodes.front().header;
      msg.header.seq = seq++;
      out.push_back(msg);
      if (begin < params.poses_per_robot / 2 && end >= params.poses_per_robot / 2) {
        all.header = msg.header;
        all.header.seq = seq++;
        out.push_back(all);
      }
    }
  }
}

}  // namespace

SyntheticTeam makeSyntheticTeam(const SyntheticTeamParams& params, std::mt19937_64& rng) {
  SyntheticTeam team;
  team.odometry_covariance = denseCovariance(0.002, 0.02);
  team.loop_closure_covariance = denseCovariance(0.005, 0.05);
  makeTrajectories(params, team, rng);
  Steps steps = makeSteps(params, team, rng);
  ClosureMaker(params, team, steps, rng).run();
  makeMessages(params, steps, team);
  return team;
}

}  // namespace cosmo::nebula
