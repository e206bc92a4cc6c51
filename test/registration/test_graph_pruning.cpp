// k-core decomposition and maximum clique on small graphs with known answers, and against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <Eigen/Geometry>
#include <random>

#include "cosmo/registration/graph_pruning.hpp"

using namespace cosmo;

namespace {
bool isClique(const registration::ConsistencyGraph& g, const std::vector<int>& c) {
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = a + 1; b < c.size(); ++b)
      if (!g.adjacent(c[a], c[b])) return false;
  return true;
}
std::size_t bruteForceCliqueSize(const registration::ConsistencyGraph& g) {
  const int n = g.size();
  std::size_t best = 0;
  for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> c;
    for (int v = 0; v < n; ++v)
      if (mask & (1u << v)) c.push_back(v);
    if (c.size() > best && isClique(g, c)) best = c.size();
  }
  return best;
}
}  // namespace

TEST(GraphPruning, CoreNumbersOfKnownGraph) {
  // K4 on {0,1,2,3}, a path 3-4-5, an isolated vertex 6, and a triangle 7-8-9 hanging on 4.
  const auto g = registration::ConsistencyGraph::fromEdges(
      10, {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}, {3, 4}, {4, 5}, {7, 8}, {8, 9}, {7, 9}, {4, 7}});
  EXPECT_EQ(g.edgeCount(), 12u);
  const auto core = coreNumbers(g);
  const std::vector<int> expected{3, 3, 3, 3, 2, 1, 0, 2, 2, 2};
  EXPECT_EQ(core, expected);
  EXPECT_EQ(maxKCore(g), (std::vector<int>{0, 1, 2, 3}));
  const auto clique = maxClique(g);
  EXPECT_EQ(clique.vertices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(clique.proven_maximum);
  EXPECT_EQ(clique.max_core_size, 4u);  // the max k-core found on the way
}

TEST(GraphPruning, EmptyAndEdgelessGraphs) {
  EXPECT_TRUE(maxClique(registration::ConsistencyGraph(0)).vertices.empty());
  EXPECT_TRUE(maxKCore(registration::ConsistencyGraph(5)).empty());
  EXPECT_EQ(maxClique(registration::ConsistencyGraph(5)).vertices.size(), 1u);
  EXPECT_EQ(maxClique(registration::ConsistencyGraph(5)).max_core_size, 0u);
}

TEST(GraphPruning, MaxCliqueMatchesBruteForceOnRandomGraphs) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 8 + trial % 7;  // up to 14 vertices: 16k subsets
    const double p = 0.3 + 0.5 * (trial % 5) / 4.0;
    std::bernoulli_distribution edge(p);
    std::vector<std::pair<int, int>> edges;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        if (edge(rng)) edges.emplace_back(a, b);
    const auto g = registration::ConsistencyGraph::fromEdges(n, edges);
    const auto c = maxClique(g);
    EXPECT_TRUE(isClique(g, c.vertices)) << "trial " << trial;
    EXPECT_EQ(c.vertices.size(), bruteForceCliqueSize(g)) << "trial " << trial;
    EXPECT_TRUE(std::is_sorted(c.vertices.begin(), c.vertices.end()));
    EXPECT_EQ(c.max_core_size, maxKCore(g).size()) << "trial " << trial;
  }
}

TEST(GraphPruning, PlantedCliqueInNoiseIsFoundAndDeterministic) {
  // 600 vertices, a planted clique on every third vertex up to 120 (40 vertices), 5 % random edges.
  std::mt19937_64 rng(3);
  std::bernoulli_distribution edge(0.05);
  std::vector<std::pair<int, int>> edges;
  for (int a = 0; a < 600; ++a)
    for (int b = a + 1; b < 600; ++b)
      if ((a % 3 == 0 && b % 3 == 0 && b < 120) || edge(rng)) edges.emplace_back(a, b);
  const auto g = registration::ConsistencyGraph::fromEdges(600, edges);
  const auto c1 = maxClique(g, 100000);
  const auto c2 = maxClique(g, 100000);
  EXPECT_TRUE(c1.proven_maximum);
  EXPECT_EQ(c1.vertices, c2.vertices);
  ASSERT_GE(c1.vertices.size(), 40u);
  EXPECT_TRUE(isClique(g, c1.vertices));
  int planted = 0;
  for (const int v : c1.vertices) planted += (v % 3 == 0 && v < 120);
  EXPECT_EQ(planted, 40);
  // The max k-core contains the planted clique.
  const auto core = maxKCore(g);
  for (int v = 0; v < 120; v += 3) EXPECT_TRUE(std::binary_search(core.begin(), core.end(), v)) << v;
}

TEST(GraphPruning, ConsistencyGraphFromCorrespondences) {
  // Three points moved rigidly and one that is not: the odd one is adjacent to nobody.
  const std::vector<Eigen::Vector3f> s{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {5, 5, 0}};
  std::vector<Eigen::Vector3f> t;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(0.7f, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (int i = 0; i < 3; ++i) t.push_back(R * s[i] + Eigen::Vector3f(3, -1, 2));
  t.push_back({40, 0, 0});
  const auto g = registration::ConsistencyGraph::fromCorrespondences(s, t, 0.05);
  EXPECT_TRUE(g.adjacent(0, 1) && g.adjacent(0, 2) && g.adjacent(1, 2));
  EXPECT_EQ(g.degree(3), 0);
  EXPECT_EQ(maxClique(g).vertices, (std::vector<int>{0, 1, 2}));
}
