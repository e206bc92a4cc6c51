#include "cosmo/sim/route_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>
#include <stdexcept>
#include <string>

namespace cosmo::sim {

namespace {
bool usable(const PathNetwork& net, int e, bool streets_only) { return !streets_only || net.edges[e].street; }

/// Dijkstra from `target`; `next` (when given) receives each node's neighbour on its shortest way to target.
std::vector<double> distancesTo(const PathNetwork& net, int target, bool streets_only,
                                std::vector<int>* next = nullptr) {
  std::vector<double> dist(net.nodes.size(), std::numeric_limits<double>::infinity());
  if (next) next->assign(net.nodes.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  dist[target] = 0.0;
  q.push({0.0, target});
  while (!q.empty()) {
    const auto [d, u] = q.top();
    q.pop();
    if (d > dist[u]) continue;
    for (const auto& [v, e] : net.adjacency[u]) {
      if (!usable(net, e, streets_only)) continue;
      const double nd = d + net.edgeLength(e);
      if (nd < dist[v]) {
        dist[v] = nd;
        if (next) (*next)[v] = u;
        q.push({nd, v});
      }
    }
  }
  return dist;
}

std::vector<int> waypointRoute(const PathNetwork& net, const RouteParams& p) {
  const int n = static_cast<int>(net.nodes.size());
  std::vector<int> stops;
  if (p.start_node >= 0) stops.push_back(p.start_node);
  stops.insert(stops.end(), p.waypoints.begin(), p.waypoints.end());
  for (int s : stops)
    if (s < 0 || s >= n)
      throw std::invalid_argument("planRoute: waypoint " + std::to_string(s) + " is not a junction (0.." +
                                  std::to_string(n - 1) + ")");
  std::vector<int> route{stops.front()};
  for (std::size_t k = 1; k < stops.size(); ++k) {
    if (stops[k] == route.back()) continue;
    const auto leg = shortestPath(net, route.back(), stops[k], p.streets_only);
    if (leg.empty())
      throw std::invalid_argument("planRoute: no path from junction " + std::to_string(route.back()) + " to " +
                                  std::to_string(stops[k]));
    route.insert(route.end(), leg.begin() + 1, leg.end());
  }
  return route;
}
}  // namespace

std::vector<int> shortestPath(const PathNetwork& net, int from, int to, bool streets_only) {
  const int n = static_cast<int>(net.nodes.size());
  if (from < 0 || from >= n || to < 0 || to >= n) return {};
  std::vector<int> next;
  const auto dist = distancesTo(net, to, streets_only, &next);
  if (!std::isfinite(dist[from])) return {};
  std::vector<int> path{from};
  while (path.back() != to) path.push_back(next[path.back()]);
  return path;
}

std::vector<int> planRoute(const PathNetwork& net, const RouteParams& p, std::mt19937_64& rng) {
  if (net.nodes.empty() || net.edges.empty()) throw std::invalid_argument("planRoute: empty path network");
  if (!p.waypoints.empty()) return waypointRoute(net, p);
  const int n = static_cast<int>(net.nodes.size());
  int start = p.start_node;
  if (start < 0 || start >= n) {
    std::vector<int> ok;
    for (int u = 0; u < n; ++u)
      for (const auto& [v, e] : net.adjacency[u])
        if (usable(net, e, p.streets_only)) {
          ok.push_back(u);
          break;
        }
    if (ok.empty()) throw std::invalid_argument("planRoute: no usable edge");
    start = ok[std::uniform_int_distribution<std::size_t>(0, ok.size() - 1)(rng)];
  }
  std::vector<int> route{start};
  std::vector<int> visits(net.edges.size(), 0);
  double length = 0.0;
  int prev = -1;
  auto step = [&](int v, int e) {
    prev = route.back();
    route.push_back(v);
    ++visits[e];
    length += net.edgeLength(e);
  };
  auto randomStep = [&]() {
    const int u = route.back();
    std::vector<std::pair<int, int>> cand;
    std::vector<double> w;
    for (const auto& [v, e] : net.adjacency[u]) {
      if (!usable(net, e, p.streets_only) || v == prev) continue;
      cand.emplace_back(v, e);
      w.push_back(visits[e] == 0 ? 4.0 : 1.0);
    }
    if (cand.empty()) {  // dead end: turn back
      for (const auto& [v, e] : net.adjacency[u])
        if (usable(net, e, p.streets_only)) {
          step(v, e);
          return true;
        }
      return false;
    }
    const auto k = std::discrete_distribution<std::size_t>(w.begin(), w.end())(rng);
    step(cand[k].first, cand[k].second);
    return true;
  };
  const double target = std::max(0.0, p.length);
  while (length < p.return_fraction * target)
    if (!randomStep()) return route;
  // Head back to the start (greedy on shortest-path distances, never straight back the way we came).
  const auto dist = distancesTo(net, start, p.streets_only);
  for (int guard = 0; p.return_fraction < 1.0 && route.back() != start && guard < 4 * n; ++guard) {
    const int u = route.back();
    int best_v = -1, best_e = -1;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [v, e] : net.adjacency[u]) {
      if (!usable(net, e, p.streets_only) || v == prev) continue;
      const double c = net.edgeLength(e) + dist[v];
      if (c < best) {
        best = c;
        best_v = v;
        best_e = e;
      }
    }
    if (best_v < 0) break;
    step(best_v, best_e);
  }
  while (length < target)
    if (!randomStep()) break;
  return route;
}

}  // namespace cosmo::sim
