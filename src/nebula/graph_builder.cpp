#include "cosmo/nebula/graph_builder.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace cosmo::nebula {

namespace {

bool isLoopClosureType(std::int32_t type) { return type == kLoopClose || type == kInterRobotBetween; }

std::string keyText(jrl::Key key) {
  const char c = jrl::robotOf(key);
  if (std::isprint(static_cast<unsigned char>(c))) return jrl::keyName(key);
  return "key " + std::to_string(key);
}

std::string edgeText(jrl::Key from, jrl::Key to, std::int32_t type, const std::string& source) {
  return edgeTypeName(type) + " " + keyText(from) + " -> " + keyText(to) + " (" + source + ")";
}

bool sameEdge(const PoseGraphEdge& a, const Between& b, CovarianceOrder order) {
  try {
    return a.pose.toPose().isApprox(b.measurement, 1e-12) && toJrlCovariance(a.covariance, order) == b.covariance;
  } catch (const std::invalid_argument&) { return false; }
}

std::string robotLabel(const RobotGraph& r) {
  return std::string("robot '") + r.character + "'" + (r.name.empty() ? "" : " (" + r.name + ")");
}

}  // namespace

void Warnings::add(const std::string& kind, const std::string& example) {
  ++counts[kind];
  auto& list = examples[kind];
  if (list.size() < 3) list.push_back(example);
}

std::size_t Warnings::total() const {
  std::size_t n = 0;
  for (const auto& [kind, count] : counts) n += count;
  return n;
}

std::string Warnings::str() const {
  std::ostringstream out;
  for (const auto& [kind, count] : counts) {
    out << "  " << count << ' ' << kind;
    const auto& list = examples.at(kind);
    for (std::size_t i = 0; i < list.size(); ++i) out << (i ? "; " : ", e.g. ") << list[i];
    out << '\n';
  }
  return out.str();
}

void GraphBuilder::addNode(jrl::Key key, StampNs stamp, const std::string& source) {
  ++nodes_read_;
  const auto [it, inserted] = nodes_.emplace(key, Node{stamp, source});
  if (inserted) return;
  ++repeated_nodes_;
  if (it->second.stamp != stamp)
    warnings_.add("nodes published again with another stamp (the first stamp is kept)",
                  keyText(key) + " in " + source + ", first in " + it->second.source);
}

void GraphBuilder::addBetween(Between between) {
  const auto id = std::make_tuple(between.key1, between.key2, between.type);
  const auto [it, inserted] = edges_.emplace(id, Edge{std::nullopt, between.source});
  if (!inserted) {
    ++repeated_edges_;
    return;
  }
  it->second.between = std::move(between);
}

void GraphBuilder::addEdge(const PoseGraphEdge& e, const std::string& source, CovarianceOrder order) {
  ++edges_read_;
  const auto id = std::make_tuple(e.key_from, e.key_to, e.type);
  if (const auto it = edges_.find(id); it != edges_.end()) {
    ++repeated_edges_;
    if (it->second.between && !sameEdge(e, *it->second.between, order))
      warnings_.add("edges published again with another measurement (the first is kept)",
                    edgeText(e.key_from, e.key_to, e.type, source) + ", first in " + it->second.source);
    return;
  }
  if (e.type != kOdom && !isLoopClosureType(e.type)) {
    edges_.emplace(id, Edge{std::nullopt, source});  // counted by type in build()
    return;
  }
  Between b;
  b.key1 = e.key_from;
  b.key2 = e.key_to;
  b.type = e.type;
  b.source = source;
  try {
    b.measurement = e.pose.toPose();
  } catch (const std::invalid_argument& err) {
    warnings_.add("odometry / loop-closure edges with an invalid pose (dropped)",
                  edgeText(e.key_from, e.key_to, e.type, source) + ": " + err.what());
    edges_.emplace(id, Edge{std::nullopt, source});
    return;
  }
  b.covariance = toJrlCovariance(e.covariance, order);
  edges_.emplace(id, Edge{std::move(b), source});
}

void GraphBuilder::addMessage(const PoseGraph& msg, const std::string& robot_name, const std::string& source,
                              CovarianceOrder order) {
  ++messages_;
  for (const PoseGraphNode& n : msg.nodes) addNode(n.key, n.header.stampNs(), source);
  for (const PoseGraphEdge& e : msg.edges) {
    addEdge(e, source, order);
    if (e.type == kOdom && jrl::robotOf(e.key_from) == jrl::robotOf(e.key_to) && !robot_name.empty())
      odometry_characters_[robot_name].insert(jrl::robotOf(e.key_from));
  }
  if (!robot_name.empty()) name_sources_.emplace(robot_name, source);
}

void GraphBuilder::addG2o(const G2oGraph& graph, const std::string& source) {
  ++messages_;
  for (const auto& [key, pose] : graph.vertices) addNode(key, jrl::indexOf(key) * 1'000'000'000ull, source);
  for (const G2oEdge& e : graph.edges) {
    ++edges_read_;
    const bool odometry = jrl::robotOf(e.key1) == jrl::robotOf(e.key2) && e.key2 == e.key1 + 1;
    Between b;
    b.key1 = e.key1;
    b.key2 = e.key2;
    b.type = odometry ? kOdom : kLoopClose;
    b.measurement = e.measurement;
    b.covariance = e.covariance;
    b.source = source + ":" + std::to_string(e.line);
    b.typed = false;
    addBetween(std::move(b));
  }
}

NebulaGraph GraphBuilder::build() const {
  NebulaGraph g;
  g.warnings = warnings_;
  g.messages = messages_;
  g.nodes_read = nodes_read_;
  g.edges_read = edges_read_;
  g.repeated_nodes = repeated_nodes_;
  g.repeated_edges = repeated_edges_;
  const std::map<char, OdometryLinks> links = odometryLinks(g.warnings);
  const std::map<char, std::string> names = robotNames(g.warnings);
  for (const auto& [c, robot_links] : links) g.robots.emplace(c, chainRobot(c, robot_links, names, g.warnings));
  collectLoopClosures(g);
  return g;
}

std::map<char, GraphBuilder::OdometryLinks> GraphBuilder::odometryLinks(Warnings& warnings) const {
  std::map<char, OdometryLinks> links;
  for (const auto& [id, edge] : edges_) {
    const auto& [from, to, type] = id;
    if (type != kOdom || !edge.between) continue;
    if (jrl::robotOf(from) != jrl::robotOf(to) || to != from + 1) {
      warnings.add("ODOM edges not between consecutive poses of one robot (ignored)",
                   edgeText(from, to, type, edge.source));
      continue;
    }
    links[jrl::robotOf(to)][jrl::indexOf(to)] = &*edge.between;
  }
  return links;
}

std::map<char, std::string> GraphBuilder::robotNames(Warnings& warnings) const {
  std::map<char, std::string> names;
  for (const auto& [name, characters] : odometry_characters_) {
    if (characters.size() != 1) {
      std::string list;
      for (char c : characters) list += std::string(list.empty() ? "" : ", ") + c;
      warnings.add("topics carrying odometry of several robots (no robot named after them)",
                   name + " (" + list + ") in " + name_sources_.at(name));
      continue;
    }
    const char c = *characters.begin();
    const auto [it, inserted] = names.emplace(c, name);
    if (!inserted)
      throw GraphError(std::string("robot character '") + c + "' is used by two robots: " + it->second + " (" +
                       name_sources_.at(it->second) + ") and " + name + " (" + name_sources_.at(name) + ")");
  }
  return names;
}

RobotGraph GraphBuilder::chainRobot(char c, const OdometryLinks& robot_links, const std::map<char, std::string>& names,
                                    Warnings& warnings) const {
  RobotGraph r;
  r.character = c;
  if (const auto it = names.find(c); it != names.end()) r.name = it->second;
  if (!std::isprint(static_cast<unsigned char>(c)) || c == ' ' || c == '"' || c == '\\')
    throw GraphError(robotLabel(r) + ": character " + std::to_string(int(static_cast<unsigned char>(c))) +
                     " cannot name a JRL robot");
  const auto node0 = nodes_.find(jrl::symbol(c, 0));
  if (node0 == nodes_.end())
    throw GraphError(robotLabel(r) + ": no node for its first pose " + jrl::keyName(jrl::symbol(c, 0)) + " (odometry " +
                     robot_links.begin()->second->source + ")");
  r.stamps.push_back(node0->second.stamp);
  for (std::uint64_t i = 1;; ++i) {
    const auto link = robot_links.find(i);
    const auto node = nodes_.find(jrl::symbol(c, i));
    if (link == robot_links.end()) break;
    if (node == nodes_.end())
      throw GraphError(robotLabel(r) + ": odometry edge " +
                       edgeText(link->second->key1, link->second->key2, kOdom, link->second->source) + " leads to " +
                       jrl::keyName(jrl::symbol(c, i)) + ", which has no node (no stamp)");
    if (node->second.stamp < r.stamps.back())
      throw GraphError(robotLabel(r) + ": the stamp of " + jrl::keyName(jrl::symbol(c, i)) + " (" +
                       node->second.source + ") is earlier than that of " + jrl::keyName(jrl::symbol(c, i - 1)));
    r.stamps.push_back(node->second.stamp);
    r.odometry.push_back(*link->second);
  }
  const std::uint64_t n = r.stamps.size();
  const auto later_link = robot_links.upper_bound(n);
  if (later_link != robot_links.end())
    throw GraphError(robotLabel(r) + ": odometry chain broken: no ODOM edge " + jrl::keyName(jrl::symbol(c, n - 1)) +
                     " -> " + jrl::keyName(jrl::symbol(c, n)) + " (poses 0.." + std::to_string(n - 1) +
                     " are chained; a later one is: " + later_link->second->source + ")");
  for (auto it = nodes_.lower_bound(jrl::symbol(c, n)); it != nodes_.end() && jrl::robotOf(it->first) == c; ++it)
    warnings.add("poses after the last odometry edge of their robot (left out)",
                 keyText(it->first) + " (" + it->second.source + ")");
  return r;
}

void GraphBuilder::collectLoopClosures(NebulaGraph& g) const {
  const auto chained = [&](jrl::Key key) {
    const auto it = g.robots.find(jrl::robotOf(key));
    return it != g.robots.end() && jrl::indexOf(key) < it->second.stamps.size();
  };
  for (const auto& [id, edge] : edges_) {
    const auto& [from, to, type] = id;
    if (type == kOdom) continue;
    if (!isLoopClosureType(type)) {
      if (type >= 0 && type <= kInterRobotBetween)
        ++g.ignored_edges[edgeTypeName(type)];
      else
        g.warnings.add("edges of an unknown type (ignored)", edgeText(from, to, type, edge.source));
      continue;
    }
    if (!edge.between) continue;  // invalid pose, already warned about
    if (from == to) {
      g.warnings.add("loop closures from a pose to itself (dropped)", edgeText(from, to, type, edge.source));
    } else if (!edge.between->typed && (!g.robots.count(jrl::robotOf(from)) || !g.robots.count(jrl::robotOf(to)))) {
      ++g.ignored_edges["g2o edge to another key"];
    } else if (!g.robots.count(jrl::robotOf(from)) || !g.robots.count(jrl::robotOf(to))) {
      g.warnings.add("loop closures touching a key that is no robot's pose (dropped)",
                     edgeText(from, to, type, edge.source));
    } else if (!chained(from) || !chained(to)) {
      g.warnings.add("loop closures touching a pose without a node or after its robot's last odometry (dropped)",
                     edgeText(from, to, type, edge.source));
    } else {
      g.loop_closures.push_back(*edge.between);
    }
  }
  for (const auto& [key, node] : nodes_)
    if (!g.robots.count(jrl::robotOf(key))) ++g.other_nodes[jrl::robotOf(key)];
}

}  // namespace cosmo::nebula
