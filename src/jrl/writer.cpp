// JRL writer: builds an nlohmann::json (std::map objects = sorted keys) and dumps it compactly, which is
// exactly how the reference library's Writer spells its files (jrl.md §8).
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cosmo/jrl/io.hpp"
#include "json_path.hpp"

namespace cosmo::jrl {

using detail::JsonPath;
using nlohmann::json;

namespace {

const std::string kDumpSource = "<dump>";

[[noreturn]] void fail(const JsonPath& p, const std::string& problem) { throw JrlError(kDumpSource, p.str(), problem); }

json number(double v, const JsonPath& p) {
  if (!std::isfinite(v)) fail(p, "number is not finite (JRL cannot hold NaN or Inf)");
  return json(v);
}

json numbers(const double* v, std::size_t n, const JsonPath& p) {
  json a = json::array();
  a.get_ref<json::array_t&>().reserve(n);
  for (std::size_t i = 0; i < n; ++i) a.push_back(number(v[i], p.index(i)));
  return a;
}

json pose3(const Pose3Value& v, const JsonPath& p) {
  json j;
  const Eigen::Quaterniond& q = v.rotation;
  const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  j["rotation"] = numbers(wxyz, 4, p.field("rotation"));
  j["translation"] = numbers(v.translation.data(), 3, p.field("translation"));
  j["type"] = "Pose3";
  return j;
}

json scalar(const Scalar& s, const JsonPath& p) {
  json j;
  j["type"] = "Scalar";
  j["value"] = number(s.value, p.field("value"));
  return j;
}

json pose2(const Pose2& v, const JsonPath& p) {
  json j;
  j["theta"] = number(v.theta, p.field("theta"));
  j["type"] = "Pose2";
  j["x"] = number(v.x, p.field("x"));
  j["y"] = number(v.y, p.field("y"));
  return j;
}

json point2(const Point2& v, const JsonPath& p) {
  json j;
  j["type"] = "Point2";
  j["x"] = number(v.x, p.field("x"));
  j["y"] = number(v.y, p.field("y"));
  return j;
}

json point3(const Point3& v, const JsonPath& p) {
  json j;
  j["type"] = "Point3";
  j["x"] = number(v.x, p.field("x"));
  j["y"] = number(v.y, p.field("y"));
  j["z"] = number(v.z, p.field("z"));
  return j;
}

json measured(const Measured& m, const JsonPath& p) {
  switch (m.index()) {
    case 0: return pose3(std::get<Pose3Value>(m), p);
    case 1: return pose2(std::get<Pose2>(m), p);
    case 2: return point2(std::get<Point2>(m), p);
    case 3: return point3(std::get<Point3>(m), p);
    case 4: return scalar(std::get<Scalar>(m), p);
    case 5: {
      const auto& br = std::get<BearingRange2>(m);
      json j;
      const JsonPath pb = p.field("bearing");
      j["bearing"] = {{"theta", number(br.bearing.theta, pb.field("theta"))}, {"type", "Rot2"}};
      j["range"] = scalar(br.range, p.field("range"));
      j["type"] = "BearingRange";
      return j;
    }
    default: {
      const auto& br = std::get<BearingRange3>(m);
      json j;
      const JsonPath pb = p.field("bearing");
      j["bearing"] = {{"i", number(br.bearing.i, pb.field("i"))},
                      {"j", number(br.bearing.j, pb.field("j"))},
                      {"k", number(br.bearing.k, pb.field("k"))},
                      {"type", "Unit3"}};
      j["range"] = scalar(br.range, p.field("range"));
      j["type"] = "BearingRange";
      return j;
    }
  }
}

json factor(const Factor& f, const JsonPath& p) {
  const bool prior = isPrior(f.type);
  const std::size_t nkeys = prior ? 1 : 2;
  if (f.keys.size() != nkeys)
    fail(p, std::string(factorTag(f.type)) + " needs " + std::to_string(nkeys) + " key(s), has " +
                std::to_string(f.keys.size()));
  if (f.measured.index() != measuredKind(f.type))
    fail(p, std::string(factorTag(f.type)) + ": measured value has the wrong type");
  const std::size_t d = static_cast<std::size_t>(factorDim(f.type));
  if (f.covariance.size() != d * d)
    fail(p.field("covariance"),
         "expected " + std::to_string(d * d) + " numbers, got " + std::to_string(f.covariance.size()));
  json j;
  j["covariance"] = numbers(f.covariance.data(), f.covariance.size(), p.field("covariance"));
  if (prior) {
    j["key"] = f.keys[0];
    j["prior"] = measured(f.measured, p.field("prior"));
  } else {
    j["key1"] = f.keys[0];
    j["key2"] = f.keys[1];
    j["measurement"] = measured(f.measured, p.field("measurement"));
  }
  j["type"] = factorTag(f.type);
  return j;
}

json value(Key key, const Value& v, const JsonPath& p) {
  json j;
  switch (v.index()) {
    case 0: j = pose3(std::get<Pose3Value>(v), p); break;
    case 1: j = pose2(std::get<Pose2>(v), p); break;
    case 2: j = point2(std::get<Point2>(v), p); break;
    case 3: j = point3(std::get<Point3>(v), p); break;
    case 4: {
      const auto& data = std::get<VectorValue>(v).data;
      j["data"] = numbers(data.data(), data.size(), p.field("data"));
      j["type"] = "Vector";
      break;
    }
    default: j = scalar(std::get<Scalar>(v), p); break;
  }
  j["key"] = key;
  return j;
}

template <typename Map>
void checkRobots(const Map& map, const std::vector<char>& robots, const JsonPath& p) {
  for (const auto& kv : map) {
    bool known = false;
    for (char r : robots) known = known || r == kv.first;
    if (!known) fail(p, std::string("robot '") + kv.first + "' is not listed in robots");
  }
}

json perRobotValues(const std::map<char, Values>& map, const std::vector<char>& robots, const JsonPath& p) {
  checkRobots(map, robots, p);
  json out = json::object();
  for (char r : robots) {
    const std::string rk(1, r);
    const JsonPath pr = p.field(rk);
    json& arr = out[rk];  // null when the robot has no values, as the reference Writer emits
    const auto it = map.find(r);
    if (it == map.end()) continue;
    std::size_t i = 0;
    for (const auto& [key, v] : it->second) {
      arr.push_back(value(key, v, pr.index(i)));
      ++i;
    }
  }
  return out;
}

json perRobotIds(const std::map<char, std::set<FactorId>>& map, const std::vector<char>& robots, const JsonPath& p) {
  checkRobots(map, robots, p);
  json out = json::object();
  for (char r : robots) {
    json arr = json::array();
    const auto it = map.find(r);
    if (it != map.end())
      for (const auto& id : it->second) arr.push_back(json::array({id.entry, id.measurement}));
    out[std::string(1, r)] = std::move(arr);
  }
  return out;
}

}  // namespace

std::string dumpJrl(const Dataset& d) {
  const JsonPath root;
  json doc;
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    const char r = d.robots[i];
    if (r < 0x21 || r > 0x7e) fail(root.field("robots").index(i), "robot id is not a printable ASCII character");
    for (std::size_t k = 0; k < i; ++k)
      if (d.robots[k] == r) fail(root.field("robots").index(i), std::string("duplicate robot '") + r + "'");
  }
  checkRobots(d.measurements, d.robots, root.field("measurements"));
  json& meas = doc["measurements"] = json::object();
  const JsonPath pm = root.field("measurements");
  for (char r : d.robots) {
    const std::string rk(1, r);
    const JsonPath pr = pm.field(rk);
    json& arr = meas[rk];
    const auto it = d.measurements.find(r);
    if (it == d.measurements.end()) continue;
    const auto& entries = it->second;
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const JsonPath pe = pr.index(e);
      json je;
      if (!entries[e].factors.empty()) {
        json& jf = je["measurements"] = json::array();
        const JsonPath pf = pe.field("measurements");
        for (std::size_t m = 0; m < entries[e].factors.size(); ++m)
          jf.push_back(factor(entries[e].factors[m], pf.index(m)));
      }
      je["stamp"] = entries[e].stamp;
      arr.push_back(std::move(je));
    }
  }
  doc["name"] = d.name;
  json robots = json::array();
  for (char r : d.robots) robots.push_back(static_cast<int>(r));
  doc["robots"] = std::move(robots);
  if (d.groundtruth) doc["groundtruth"] = perRobotValues(*d.groundtruth, d.robots, root.field("groundtruth"));
  if (d.initialization)
    doc["initialization"] = perRobotValues(*d.initialization, d.robots, root.field("initialization"));
  if (d.potential_outliers)
    doc["potential_outlier_factors"] =
        perRobotIds(*d.potential_outliers, d.robots, root.field("potential_outlier_factors"));
  if (d.outliers) doc["outlier_factors"] = perRobotIds(*d.outliers, d.robots, root.field("outlier_factors"));
  return doc.dump();
}

void writeJrl(const std::string& path, const Dataset& dataset) {
  const std::string text = dumpJrl(dataset);
  std::string tmp = path + ".tmpXXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw std::runtime_error(path + ": cannot create temporary file: " + std::strerror(errno));
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string err = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error(path + ": write failed: " + err);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  ::fchmod(fd, 0644);  // mkstemp creates 0600
  const bool synced = ::fsync(fd) == 0;
  const int sync_errno = errno;
  if (::close(fd) != 0 || !synced) {
    const std::string err = std::strerror(synced ? errno : sync_errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": write failed: " + err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": cannot rename temporary file into place: " + err);
  }
}

}  // namespace cosmo::jrl
