// Routes over the path network: waypoint routes pass their junctions in order along shortest paths, respect
// streets_only, reject bad junctions, and a sequence config's waypoints give a trajectory through those places.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cosmo/sim/route_planner.hpp"
#include "cosmo/sim/sequence_planner.hpp"

using namespace cosmo;
using namespace cosmo::sim;

namespace {
// 3 x 2 grid of junctions 100 m apart (0 1 2 / 3 4 5); 0-4 a footpath diagonal (141 m).
PathNetwork grid() {
  PathNetwork net;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) net.addNode({100.0 * i, 100.0 * j});
  net.addEdge(0, 1, true);
  net.addEdge(1, 2, true);
  net.addEdge(3, 4, true);
  net.addEdge(4, 5, true);
  net.addEdge(0, 3, true);
  net.addEdge(1, 4, true);
  net.addEdge(2, 5, true);
  net.addEdge(0, 4, false);
  return net;
}

bool adjacent(const PathNetwork& net, int a, int b, bool streets_only) {
  for (const auto& [v, e] : net.adjacency[a])
    if (v == b && (!streets_only || net.edges[e].street)) return true;
  return false;
}

double routeLength(const PathNetwork& net, const std::vector<int>& route) {
  double len = 0.0;
  for (std::size_t k = 1; k < route.size(); ++k) len += (net.nodes[route[k]] - net.nodes[route[k - 1]]).norm();
  return len;
}
}  // namespace

TEST(RoutePlanner, WaypointsInOrderAlongShortestPaths) {
  const auto net = grid();
  RouteParams p;
  p.start_node = 2;
  p.waypoints = {3, 5, 2};
  p.length = 10.0;  // not used with waypoints
  std::mt19937_64 rng(1);
  const auto route = planRoute(net, p, rng);
  // 2 -> 3: 2 1 0 3 or 2 5 4 3 or 2 1 4 3 (300 m); 3 -> 5: 3 4 5; 5 -> 2.
  ASSERT_GE(route.size(), 7u);
  EXPECT_EQ(route.front(), 2);
  EXPECT_EQ(route.back(), 2);
  for (std::size_t k = 1; k < route.size(); ++k) EXPECT_TRUE(adjacent(net, route[k - 1], route[k], false));
  EXPECT_NEAR(routeLength(net, route), 300.0 + 200.0 + 100.0, 1e-9);
  std::size_t next = 0;  // waypoints appear in order
  for (int n : route)
    if (next < p.waypoints.size() && n == p.waypoints[next]) ++next;
  EXPECT_EQ(next, p.waypoints.size());
  // Deterministic and draws no randomness.
  std::mt19937_64 rng2(99);
  EXPECT_EQ(planRoute(net, p, rng2), route);
  EXPECT_EQ(rng(), std::mt19937_64(1)());
}

TEST(RoutePlanner, WaypointsUseFootpathsUnlessStreetsOnly) {
  const auto net = grid();
  RouteParams p;
  p.waypoints = {0, 4};  // starts at the first waypoint
  std::mt19937_64 rng(1);
  EXPECT_EQ(planRoute(net, p, rng), (std::vector<int>{0, 4}));  // the 141 m diagonal
  p.streets_only = true;
  const auto route = planRoute(net, p, rng);
  ASSERT_EQ(route.size(), 3u);
  EXPECT_NEAR(routeLength(net, route), 200.0, 1e-9);
  for (std::size_t k = 1; k < route.size(); ++k) EXPECT_TRUE(adjacent(net, route[k - 1], route[k], true));
}

TEST(RoutePlanner, BadWaypointsThrow) {
  auto net = grid();
  std::mt19937_64 rng(1);
  RouteParams p;
  p.waypoints = {0, 6};
  EXPECT_THROW(planRoute(net, p, rng), std::invalid_argument);
  net.addNode({500.0, 500.0});  // junction 6, unconnected
  EXPECT_THROW(planRoute(net, p, rng), std::invalid_argument);
  EXPECT_TRUE(shortestPath(net, 0, 6, false).empty());
  EXPECT_EQ(shortestPath(net, 5, 5, false), (std::vector<int>{5}));
}

TEST(RoutePlanner, SequenceConfigWaypointsDriveThroughThoseJunctions) {
  const auto node = YAML::Load(R"(
name: wp
world: {blocks_x: 2, blocks_y: 2, block_min: 50.0, block_max: 60.0, outer_ring: 30.0, terrain_margin: 60.0}
trials:
  - {robot: a, platform: atv, start_node: 0, waypoints: [2, 8, 6, 0, 2]}
  - {robot: b, platform: handheld, length: 80.0, start_node: 4}
)");
  const auto params = SimulationParams::fromConfig(ConfigNode{node, "test.yaml: "});
  ASSERT_EQ(params.trials[0].route.waypoints, (std::vector<int>{2, 8, 6, 0, 2}));
  EXPECT_TRUE(params.trials[1].route.waypoints.empty());
  // Waypoints are part of the cache key; configs without them keep their old key text.
  EXPECT_NE(params.trials[0].describe().find("waypoints=2,8,6,0,2,"), std::string::npos);
  EXPECT_EQ(params.trials[1].describe().find("waypoints"), std::string::npos);
  const auto seq = planSequence(params);
  const auto& t = seq.trials[0];
  const auto& net = seq.world->network();
  // Passes 0, 2, 8, 6, 0, 2 in that order: the trajectory comes within a few metres of each junction in turn.
  std::size_t next = 0;
  const std::vector<int> stops{0, 2, 8, 6, 0, 2};
  for (StampNs s = t.body.startStamp(); s <= t.body.endStamp() && next < stops.size(); s += 100000000) {
    const Eigen::Vector3d p = t.body.atClamped(s).translation();
    if ((p.head<2>() - net.nodes[stops[next]]).norm() < 8.0) ++next;
  }
  EXPECT_EQ(next, stops.size());
  // A lap around the 2 x 2 blocks and once more along the first side (corners rounded), ending near junction 2.
  EXPECT_EQ(t.route.front(), 0);
  EXPECT_EQ(t.route.back(), 2);
  EXPECT_GT(t.body.length(), 0.9 * routeLength(net, t.route));
  EXPECT_LT(t.body.length(), 1.1 * routeLength(net, t.route));
  EXPECT_LT((t.body.atClamped(t.body.endStamp()).translation().head<2>() - net.nodes[2]).norm(), 8.0);
}

TEST(RoutePlanner, DefaultDemoTrialsShareMuchOfTheirPaths) {
  // The demo (config/sim/default.yaml) relies on the robots driving the same streets (Wi-Fi meetings and
  // inter-robot loop closures): each pair of trials covers >= 100 m of common path (within 5 m); every ATV
  // revisits some of its own path later (intra-robot closures), and one (b, the noise-model trial) >= 40 m.
  const auto params = SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/default.yaml");
  const auto seq = planSequence(params);
  ASSERT_GE(seq.trials.size(), 3u);
  auto samples = [](const Trajectory& t) {  // a point every ~2 m of travel
    std::vector<Eigen::Vector2d> pts;
    for (const auto& p : t.poses()) {
      const Eigen::Vector2d q = p.pose.translation().head<2>();
      if (pts.empty() || (q - pts.back()).norm() >= 2.0) pts.push_back(q);
    }
    return pts;
  };
  auto near = [](const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& pts, std::size_t end) {
    for (std::size_t k = 0; k < end; ++k)
      if ((pts[k] - q).norm() < 5.0) return true;
    return false;
  };
  std::vector<std::vector<Eigen::Vector2d>> pts;
  for (const auto& t : seq.trials) pts.push_back(samples(t.body));
  double most_revisited = 0.0;  // m
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (std::size_t j = i + 1; j < pts.size(); ++j) {
      std::size_t shared = 0;
      for (const auto& q : pts[i]) shared += near(q, pts[j], pts[j].size());
      EXPECT_GE(2.0 * shared, 100.0) << seq.trials[i].params.name << " / " << seq.trials[j].params.name;
    }
    std::size_t revisits = 0;  // points within 5 m of where the trial was >= 60 m of travel earlier
    for (std::size_t k = 30; k < pts[i].size(); ++k) revisits += near(pts[i][k], pts[i], k - 30);
    if (seq.trials[i].params.platform != "handheld") EXPECT_GE(2.0 * revisits, 10.0) << seq.trials[i].params.name;
    most_revisited = std::max(most_revisited, 2.0 * revisits);
  }
  EXPECT_GE(most_revisited, 40.0);
}
