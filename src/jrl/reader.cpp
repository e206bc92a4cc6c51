// JRL reader: nlohmann-json DOM, then a checked walk that names the JSON path of every problem.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosmo/jrl/io.hpp"
#include "json_path.hpp"

namespace cosmo::jrl {

using detail::JsonPath;
using nlohmann::json;

JrlError::JrlError(const std::string& source, const std::string& path, const std::string& problem)
    : std::runtime_error(source + ": " + (path.empty() ? std::string() : path + ": ") + problem),
      source_(source),
      path_(path),
      problem_(problem) {}

namespace {

std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "boolean";
    case json::value_t::string: return "string";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "integer " + j.dump();
    case json::value_t::number_float: return "floating-point number " + j.dump();
    case json::value_t::object: return "object";
    case json::value_t::array: return "array";
    default: return j.type_name();
  }
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

class Reader {
 public:
  explicit Reader(const std::string& source) : source_(source) {}

  Dataset read(const json& doc) {
    const JsonPath root;
    if (!doc.is_object()) fail(root, "expected a JSON object at the top level, got " + describe(doc));
    Dataset d;
    {
      const JsonPath p = root.field("name");
      const json& name = field(doc, "name", root);
      if (!name.is_string()) fail(p, "expected a string, got " + describe(name));
      d.name = name.get<std::string>();
    }
    d.robots = robots(field(doc, "robots", root), root.field("robots"));

    const JsonPath pm = root.field("measurements");
    const json& meas = field(doc, "measurements", root);
    if (!meas.is_object()) fail(pm, "expected an object keyed by robot id, got " + describe(meas));
    for (char r : d.robots) {
      const std::string rk(1, r);
      const JsonPath pr = pm.field(rk);
      auto& entries = d.measurements[r];
      const auto it = meas.find(rk);
      if (it == meas.end() || it->is_null()) continue;
      if (!it->is_array()) fail(pr, "expected an array of entries, got " + describe(*it));
      entries.reserve(it->size());
      for (std::size_t i = 0; i < it->size(); ++i) entries.push_back(entry((*it)[i], pr.index(i)));
    }
    for (const char* name : {"groundtruth", "initialization"}) {
      const auto it = doc.find(name);
      if (it == doc.end()) continue;
      auto& target = std::string(name) == "groundtruth" ? d.groundtruth : d.initialization;
      target = perRobotValues(*it, root.field(name), d.robots);
    }
    for (const char* name : {"potential_outlier_factors", "outlier_factors"}) {
      const auto it = doc.find(name);
      if (it == doc.end()) continue;
      auto& target = std::string(name) == "outlier_factors" ? d.outliers : d.potential_outliers;
      target = perRobotFactorIds(*it, root.field(name), d.robots);
    }
    return d;
  }

 private:
  [[noreturn]] void fail(const JsonPath& p, const std::string& problem) const {
    throw JrlError(source_, p.str(), problem);
  }

  const json& field(const json& obj, const char* name, const JsonPath& p) const {
    const auto it = obj.find(name);
    if (it == obj.end()) fail(p, std::string("missing field \"") + name + "\"");
    return *it;
  }

  const json& object(const json& j, const JsonPath& p, const char* what) const {
    if (!j.is_object()) fail(p, std::string("expected ") + what + ", got " + describe(j));
    return j;
  }

  double number(const json& j, const JsonPath& p) const {
    if (j.is_number_float()) {
      const double v = j.get<double>();
      if (!std::isfinite(v)) fail(p, "number out of range (not finite)");
      return v;
    }
    if (j.is_number_unsigned()) return static_cast<double>(j.get<std::uint64_t>());
    if (j.is_number_integer()) return static_cast<double>(j.get<std::int64_t>());
    if (j.is_null()) fail(p, "expected a number, got null (NaN or Inf when written)");
    fail(p, "expected a number, got " + describe(j));
  }

  double numberField(const json& obj, const char* name, const JsonPath& p) const {
    return number(field(obj, name, p), p.field(name));
  }

  std::uint64_t unsignedInt(const json& j, const JsonPath& p, const char* what) const {
    if (j.is_number_unsigned()) return j.get<std::uint64_t>();
    if (j.is_number_integer()) fail(p, std::string("expected a non-negative integer ") + what + ", got " + describe(j));
    fail(p, std::string("expected an integer ") + what + ", got " + describe(j));
  }

  std::vector<double> numbers(const json& j, const JsonPath& p, std::size_t expected) const {
    if (!j.is_array()) fail(p, "expected an array of " + std::to_string(expected) + " numbers, got " + describe(j));
    if (j.size() != expected)
      fail(p, "expected " + std::to_string(expected) + " numbers, got " + std::to_string(j.size()));
    std::vector<double> v(expected);
    for (std::size_t i = 0; i < expected; ++i) v[i] = number(j[i], p.index(i));
    return v;
  }

  std::vector<char> robots(const json& j, const JsonPath& p) const {
    if (!j.is_array()) fail(p, "expected an array of robot char codes (e.g. [97,98]), got " + describe(j));
    std::vector<char> out;
    for (std::size_t i = 0; i < j.size(); ++i) {
      const JsonPath pi = p.index(i);
      const json& r = j[i];
      if (r.is_string()) fail(pi, "robot ids are integer char codes (97 for 'a'), got string " + r.dump());
      if (!r.is_number_integer()) fail(pi, "expected an integer char code, got " + describe(r));
      const bool in_range = r.is_number_unsigned() && r.get<std::uint64_t>() >= 0x21 && r.get<std::uint64_t>() <= 0x7e;
      if (!in_range) fail(pi, "robot code " + r.dump() + " is not a printable ASCII character (33..126)");
      const char c = static_cast<char>(r.get<std::uint64_t>());
      for (char o : out)
        if (o == c) fail(pi, std::string("duplicate robot '") + c + "'");
      out.push_back(c);
    }
    return out;
  }

  Entry entry(const json& j, const JsonPath& p) const {
    object(j, p, "an entry object {\"measurements\":[...],\"stamp\":...}");
    Entry e;
    e.stamp = unsignedInt(field(j, "stamp", p), p.field("stamp"), "stamp");
    const auto it = j.find("measurements");
    if (it == j.end() || it->is_null()) return e;
    const JsonPath pm = p.field("measurements");
    if (!it->is_array()) fail(pm, "expected an array of measurements, got " + describe(*it));
    e.factors.reserve(it->size());
    for (std::size_t i = 0; i < it->size(); ++i) e.factors.push_back(factor((*it)[i], pm.index(i)));
    return e;
  }

  Factor factor(const json& j, const JsonPath& p) const {
    object(j, p, "a measurement object");
    Factor f;
    const json& tag = field(j, "type", p);
    if (!tag.is_string()) fail(p.field("type"), "expected a factor tag string, got " + describe(tag));
    const auto type = factorTypeFromTag(tag.get_ref<const std::string&>());
    if (!type) fail(p.field("type"), "unknown factor type " + tag.dump());
    f.type = *type;
    const bool prior = isPrior(f.type);
    if (prior) {
      f.keys = {unsignedInt(field(j, "key", p), p.field("key"), "key")};
    } else {
      f.keys = {unsignedInt(field(j, "key1", p), p.field("key1"), "key"),
                unsignedInt(field(j, "key2", p), p.field("key2"), "key")};
    }
    const char* mname = prior ? "prior" : "measurement";
    f.measured = measured(field(j, mname, p), p.field(mname), measuredKind(f.type));
    const int d = factorDim(f.type);
    f.covariance = numbers(field(j, "covariance", p), p.field("covariance"), static_cast<std::size_t>(d * d));
    return f;
  }

  Pose3Value pose3(const json& j, const JsonPath& p) const {
    object(j, p, "a Pose3 object");
    Pose3Value v;
    const JsonPath pt = p.field("translation"), pr = p.field("rotation");
    const auto t = numbers(field(j, "translation", p), pt, 3);
    const auto q = numbers(field(j, "rotation", p), pr, 4);
    v.translation = Eigen::Vector3d(t[0], t[1], t[2]);
    v.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);  // file order w, x, y, z
    const double n = v.rotation.norm();
    if (!(std::abs(n - 1.0) <= kUnitNormTolerance))
      fail(pr, "quaternion [w,x,y,z] is not unit (norm " + fmt(n) + ", tolerance 1e-6)");
    return v;
  }

  Scalar scalar(const json& j, const JsonPath& p) const {
    object(j, p, "a Scalar object {\"type\":\"Scalar\",\"value\":...}");
    return Scalar{numberField(j, "value", p)};
  }

  Measured measured(const json& j, const JsonPath& p, std::size_t kind) const {
    switch (kind) {
      case 0: return pose3(j, p);
      case 1:
        object(j, p, "a Pose2 object");
        return Pose2{numberField(j, "x", p), numberField(j, "y", p), numberField(j, "theta", p)};
      case 2: object(j, p, "a Point2 object"); return Point2{numberField(j, "x", p), numberField(j, "y", p)};
      case 3:
        object(j, p, "a Point3 object");
        return Point3{numberField(j, "x", p), numberField(j, "y", p), numberField(j, "z", p)};
      case 4: return scalar(j, p);
      case 5: {
        object(j, p, "a BearingRange object");
        const JsonPath pb = p.field("bearing");
        const json& b = object(field(j, "bearing", p), pb, "a Rot2 object");
        BearingRange2 br;
        br.bearing.theta = numberField(b, "theta", pb);
        br.range = scalar(field(j, "range", p), p.field("range"));
        return br;
      }
      default: {
        object(j, p, "a BearingRange object");
        const JsonPath pb = p.field("bearing");
        const json& b = object(field(j, "bearing", p), pb, "a Unit3 object");
        BearingRange3 br;
        br.bearing = Unit3{numberField(b, "i", pb), numberField(b, "j", pb), numberField(b, "k", pb)};
        const double n =
            std::sqrt(br.bearing.i * br.bearing.i + br.bearing.j * br.bearing.j + br.bearing.k * br.bearing.k);
        if (!(std::abs(n - 1.0) <= kUnitNormTolerance))
          fail(pb, "Unit3 bearing is not unit (norm " + fmt(n) + ", tolerance 1e-6)");
        br.range = scalar(field(j, "range", p), p.field("range"));
        return br;
      }
    }
  }

  Value value(const json& j, const JsonPath& p, Key* key) const {
    object(j, p, "a value object {\"key\":...,\"type\":...}");
    *key = unsignedInt(field(j, "key", p), p.field("key"), "key");
    const json& tag = field(j, "type", p);
    if (!tag.is_string()) fail(p.field("type"), "expected a value tag string, got " + describe(tag));
    const std::string& t = tag.get_ref<const std::string&>();
    if (t == "Pose3") return pose3(j, p);
    if (t == "Pose2") return Pose2{numberField(j, "x", p), numberField(j, "y", p), numberField(j, "theta", p)};
    if (t == "Point2") return Point2{numberField(j, "x", p), numberField(j, "y", p)};
    if (t == "Point3") return Point3{numberField(j, "x", p), numberField(j, "y", p), numberField(j, "z", p)};
    if (t == "Scalar") return Scalar{numberField(j, "value", p)};
    if (t == "Vector") {
      const JsonPath pd = p.field("data");
      const json& data = field(j, "data", p);
      if (!data.is_array()) fail(pd, "expected an array of numbers, got " + describe(data));
      return VectorValue{numbers(data, pd, data.size())};
    }
    fail(p.field("type"), "unknown value type " + tag.dump());
  }

  std::map<char, Values> perRobotValues(const json& j, const JsonPath& p, const std::vector<char>& robots) const {
    if (!j.is_object()) fail(p, "expected an object keyed by robot id, got " + describe(j));
    std::map<char, Values> out;
    for (char r : robots) {
      const std::string rk(1, r);
      const JsonPath pr = p.field(rk);
      Values& values = out[r];
      const auto it = j.find(rk);
      if (it == j.end() || it->is_null()) continue;
      if (!it->is_array()) fail(pr, "expected an array of values, got " + describe(*it));
      for (std::size_t i = 0; i < it->size(); ++i) {
        const JsonPath pi = pr.index(i);
        Key key = 0;
        Value v = value((*it)[i], pi, &key);
        if (!values.emplace(key, std::move(v)).second)
          fail(pi, "duplicate key " + keyName(key) + " (" + std::to_string(key) + ")");
      }
    }
    return out;
  }

  std::map<char, std::set<FactorId>> perRobotFactorIds(const json& j, const JsonPath& p,
                                                       const std::vector<char>& robots) const {
    if (!j.is_object()) fail(p, "expected an object keyed by robot id, got " + describe(j));
    std::map<char, std::set<FactorId>> out;
    for (char r : robots) {
      const std::string rk(1, r);
      const JsonPath pr = p.field(rk);
      auto& ids = out[r];
      const auto it = j.find(rk);
      if (it == j.end()) continue;
      if (!it->is_array()) fail(pr, "expected an array of [entry, measurement] pairs, got " + describe(*it));
      for (std::size_t i = 0; i < it->size(); ++i) {
        const JsonPath pi = pr.index(i);
        const json& pair = (*it)[i];
        if (!pair.is_array() || pair.size() != 2)
          fail(pi, "expected an [entry, measurement] pair, got " +
                       (pair.is_array() ? "an array of " + std::to_string(pair.size()) : describe(pair)));
        ids.insert(FactorId{unsignedInt(pair[0], pi.index(0), "entry index"),
                            unsignedInt(pair[1], pi.index(1), "measurement index")});
      }
    }
    return out;
  }

  const std::string& source_;
};

std::string stripNlohmannPrefix(const std::string& what) {
  // "[json.exception.parse_error.101] parse error at line 1, column 5: ..." -> "parse error at line 1, ..."
  const auto pos = what.find("] ");
  return (what.rfind("[json.exception.", 0) == 0 && pos != std::string::npos) ? what.substr(pos + 2) : what;
}

}  // namespace

Dataset parseJrl(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw JrlError(source, "",
                   "invalid JSON (" + std::string(text.empty() ? "empty document" : "truncated or malformed") +
                       "): " + stripNlohmannPrefix(e.what()));
  } catch (const json::exception& e) {  // e.g. out_of_range.406 "number overflow parsing '1e999'"
    throw JrlError(source, "", "invalid JSON: " + stripNlohmannPrefix(e.what()));
  }
  try {
    return Reader(source).read(doc);
  } catch (const json::exception& e) {  // safety net: every access above is checked first
    throw JrlError(source, "", "unexpected JSON structure: " + stripNlohmannPrefix(e.what()));
  }
}

Dataset readJrl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JrlError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw JrlError(path, "", "read error");
  return parseJrl(ss.str(), path);
}

}  // namespace cosmo::jrl
