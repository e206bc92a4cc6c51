// JRL reader/writer: byte-identical round trips (tiny example, reference file, all 16 factor types) and
// clear errors naming the JSON path for bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo::jrl;
using cosmo::Matrix6;
namespace fs = std::filesystem;

namespace {

std::string tinyPath() { return std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl"; }

/// what() of the JrlError thrown by parsing `text`; fails the test when nothing (or something else) is thrown.
std::string parseError(const std::string& text) {
  try {
    parseJrl(text, "bad.jrl");
  } catch (const JrlError& e) { return e.what(); } catch (const std::exception& e) {
    ADD_FAILURE() << "not a JrlError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected a JrlError for: " << text.substr(0, 200);
  return "";
}

/// tiny_example with the first occurrence of `from` replaced by `to`.
std::string tinyWith(const std::string& from, const std::string& to) {
  std::string s = cosmo::readWholeFileOrEmpty(tinyPath());
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) s.replace(pos, from.size(), to);
  return s;
}

}  // namespace

TEST(JrlKeys, SymbolLayout) {
  EXPECT_EQ(symbol('a', 0), 6989586621679009792ull);
  EXPECT_EQ(symbol('a', 1), 6989586621679009793ull);
  EXPECT_EQ(symbol('b', 0), 7061644215716937728ull);
  EXPECT_EQ(symbol('c', 0), 7133701809754865664ull);
  EXPECT_EQ(robotOf(symbol('c', 123456)), 'c');
  EXPECT_EQ(indexOf(symbol('c', 123456)), 123456u);
  EXPECT_EQ(keyName(symbol('b', 17)), "b17");
}

TEST(JrlIo, TinyExampleRoundTripIsByteIdentical) {
  const std::string text = cosmo::readWholeFileOrEmpty(tinyPath());
  ASSERT_EQ(text.size(), 4265u);
  const Dataset d = parseJrl(text, "tiny_example.jrl");
  EXPECT_EQ(d.name, "tiny_example");
  ASSERT_EQ(d.robots, (std::vector<char>{'a', 'b'}));
  ASSERT_EQ(d.measurements.at('a').size(), 3u);
  ASSERT_EQ(d.measurements.at('b').size(), 2u);
  const Factor& lc = d.measurements.at('a')[2].factors[1];
  EXPECT_EQ(lc.type, FactorType::BetweenFactorPose3);
  EXPECT_EQ(lc.keys, (std::vector<Key>{symbol('a', 2), symbol('a', 0)}));
  EXPECT_NEAR(lc.pose3().translation().y(), 3.0, 1e-15);
  const Factor& irlc = d.measurements.at('b')[1].factors[1];
  EXPECT_DOUBLE_EQ(irlc.covarianceMatrix()(2, 3), 0.0005);
  EXPECT_DOUBLE_EQ(irlc.covarianceMatrix()(3, 2), 0.0005);
  EXPECT_EQ(d.measurements.at('b')[1].stamp, 1700000000750000000ull);
  ASSERT_TRUE(d.groundtruth && d.initialization && d.outliers && d.potential_outliers);
  EXPECT_EQ(d.groundtruth->at('b').size(), 3u);
  EXPECT_NEAR(pose3At(d.initialization->at('b'), symbol('a', 1)).translation().y(), 0.25, 1e-15);
  EXPECT_EQ(d.outliers->at('a'), (std::set<FactorId>{{2, 1}}));
  EXPECT_TRUE(d.outliers->at('b').empty());
  EXPECT_EQ(d.potential_outliers->at('b'), (std::set<FactorId>{{1, 1}}));
  EXPECT_EQ(dumpJrl(d), text);
}

TEST(JrlIo, WriteJrlIsAtomicAndReadable) {
  const fs::path dir = fs::temp_directory_path() / ("cosmo_jrl_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Dataset d = readJrl(tinyPath());
  const std::string out = (dir / "copy.jrl").string();
  writeJrl(out, d);
  writeJrl(out, d);  // overwrite in place
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(out), cosmo::readWholeFileOrEmpty(tinyPath()));
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1u) << "temporary file left behind";
  EXPECT_THROW(writeJrl((dir / "no_such_dir" / "x.jrl").string(), d), std::runtime_error);
  try {
    readJrl((dir / "missing.jrl").string());
    FAIL();
  } catch (const JrlError& e) { EXPECT_NE(std::string(e.what()).find("missing.jrl"), std::string::npos) << e.what(); }
  fs::remove_all(dir);
}

TEST(JrlIo, ReferenceFileRoundTripIsByteIdentical) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const std::string text = cosmo::readWholeFileOrEmpty(*path);
  ASSERT_EQ(text.size(), 2381116u);
  const Dataset d = parseJrl(text, *path);
  EXPECT_EQ(d.name, "tuhh_r3_01_night_wifi");
  ASSERT_EQ(d.robots, (std::vector<char>{'a', 'b', 'c'}));
  const std::map<char, std::array<std::size_t, 5>> expected = {
      // entries, factors, values, potential outliers, outliers (jrl.md §11)
      {'a', {357, 530, 359, 179, 21}},
      {'b', {535, 922, 624, 387, 51}},
      {'c', {165, 209, 165, 69, 3}}};
  for (const auto& [r, counts] : expected) {
    const auto& entries = d.measurements.at(r);
    std::size_t factors = 0;
    for (const auto& e : entries) factors += e.factors.size();
    EXPECT_EQ(entries.size(), counts[0]) << r;
    EXPECT_EQ(factors, counts[1]) << r;
    EXPECT_EQ(d.groundtruth->at(r).size(), counts[2]) << r;
    EXPECT_EQ(d.initialization->at(r).size(), counts[2]) << r;
    EXPECT_EQ(d.potential_outliers->at(r).size(), counts[3]) << r;
    EXPECT_EQ(d.outliers->at(r).size(), counts[4]) << r;
  }
  EXPECT_EQ(d.measurements.at('a').front().stamp, 1666284719545345152ull);
  EXPECT_EQ(d.measurements.at('c').back().stamp, 1666285209345345068ull);
  EXPECT_TRUE(dumpJrl(d) == text) << "dump differs from the reference bytes";
}

TEST(JrlIo, AllSixteenFactorTypesRoundTrip) {
  // Written by hand (with whitespace, integers where doubles are allowed, unsorted outlier ids); the writer
  // must produce nlohmann's canonical compact form of the same document.
  const std::string text = R"({
 "name": "all_types", "robots": [120, 121],
 "measurements": {"x": [
  {"stamp": 10, "measurements": [
   {"type":"PriorFactorPose3","key":8646911284551352320,"prior":{"type":"Pose3","translation":[1,2,3],"rotation":[-0.5,0.5,0.5,0.5]},"covariance":[1,0,0,0,0,0, 0,1,0,0,0,0, 0,0,1,0,0,0, 0,0,0,1,0,0, 0,0,0,0,1,0, 0,0,0,0,0,1]},
   {"type":"BetweenFactorPose3","key1":8646911284551352320,"key2":8646911284551352321,"measurement":{"type":"Pose3","translation":[1.5,0.0,-0.0],"rotation":[1.0,0.0,0.0,0.0]},"covariance":[1e-4,0,0,0,0,0, 0,1e-4,0,0,0,0, 0,0,1e-4,0,0,0, 0,0,0,0.01,0,0, 0,0,0,0,0.01,0, 0,0,0,0,0,0.01]},
   {"type":"PriorFactorPose2","key":8646911284551352322,"prior":{"type":"Pose2","x":1.0,"y":2.0,"theta":0.1},"covariance":[1,0,0,0,1,0,0,0,1]},
   {"type":"BetweenFactorPose2","key1":8646911284551352322,"key2":8646911284551352323,"measurement":{"type":"Pose2","x":1.0,"y":0.0,"theta":0.1},"covariance":[1,0,0,0,1,0,0,0,1]},
   {"type":"PriorFactorPoint2","key":8646911284551352324,"prior":{"type":"Point2","x":1.0,"y":2.0},"covariance":[1,0,0,1]},
   {"type":"BetweenFactorPoint2","key1":8646911284551352324,"key2":8646911284551352325,"measurement":{"type":"Point2","x":1.0,"y":2.0},"covariance":[1,0,0,1]},
   {"type":"PriorFactorPoint3","key":8646911284551352326,"prior":{"type":"Point3","x":1.0,"y":2.0,"z":3.0},"covariance":[1,0,0,0,1,0,0,0,1]},
   {"type":"BetweenFactorPoint3","key1":8646911284551352326,"key2":8646911284551352327,"measurement":{"type":"Point3","x":1.0,"y":0.0,"z":0.0},"covariance":[1,0,0,0,1,0,0,0,1]}
  ]},
  {"stamp": 20, "measurements": [
   {"type":"RangeFactorPose2","key1":8646911284551352322,"key2":8646911284551352323,"measurement":{"type":"Scalar","value":5.2},"covariance":[0.01]},
   {"type":"RangeFactorPose3","key1":8646911284551352320,"key2":8646911284551352321,"measurement":{"type":"Scalar","value":5.2},"covariance":[0.01]},
   {"type":"RangeFactor2D","key1":8646911284551352322,"key2":8646911284551352324,"measurement":{"type":"Scalar","value":5.2},"covariance":[0.01]},
   {"type":"RangeFactor3D","key1":8646911284551352320,"key2":8646911284551352326,"measurement":{"type":"Scalar","value":5.2},"covariance":[0.01]},
   {"type":"BearingRangeFactorPose2","key1":8646911284551352322,"key2":8646911284551352323,"measurement":{"type":"BearingRange","bearing":{"type":"Rot2","theta":0.3},"range":{"type":"Scalar","value":5.2}},"covariance":[1,0,0,1]},
   {"type":"BearingRangeFactor2D","key1":8646911284551352322,"key2":8646911284551352324,"measurement":{"type":"BearingRange","bearing":{"type":"Rot2","theta":0.3},"range":{"type":"Scalar","value":5.2}},"covariance":[1,0,0,1]},
   {"type":"BearingRangeFactorPose3","key1":8646911284551352320,"key2":8646911284551352321,"measurement":{"type":"BearingRange","bearing":{"type":"Unit3","i":0.6,"j":0.8,"k":0.0},"range":{"type":"Scalar","value":5.2}},"covariance":[1,0,0,0,1,0,0,0,1]},
   {"type":"BearingRangeFactor3D","key1":8646911284551352320,"key2":8646911284551352326,"measurement":{"type":"BearingRange","bearing":{"type":"Unit3","i":0.0,"j":0.0,"k":-1.0},"range":{"type":"Scalar","value":1e-05}},"covariance":[1,0,0,0,1,0,0,0,1]}
  ]},
  {"stamp": 30}
 ], "y": null, "z": [{"stamp": 1}]},
 "groundtruth": {"x": [
   {"key": 8646911284551352321, "type": "Pose2", "x": 1, "y": 2, "theta": 3},
   {"key": 8646911284551352320, "type": "Pose3", "translation": [0,0,0], "rotation": [1,0,0,0]},
   {"key": 5, "type": "Point2", "x": 1, "y": 2},
   {"key": 6, "type": "Point3", "x": 1, "y": 2, "z": 1e300},
   {"key": 7, "type": "Vector", "data": [1, 2.5, -3]},
   {"key": 8, "type": "Vector", "data": []},
   {"key": 9, "type": "Scalar", "value": -0.0}
 ], "y": []},
 "potential_outlier_factors": {"x": [[1,3],[0,1],[1,3]], "y": []},
 "outlier_factors": {"x": [[0,1]], "y": []}
})";
  const Dataset d = parseJrl(text, "all_types.jrl");
  ASSERT_EQ(d.measurements.at('x').size(), 3u);
  EXPECT_EQ(d.measurements.at('x')[0].factors.size(), 8u);
  EXPECT_EQ(d.measurements.at('x')[1].factors.size(), 8u);
  EXPECT_TRUE(d.measurements.at('x')[2].factors.empty());
  EXPECT_TRUE(d.measurements.at('y').empty());
  std::set<FactorType> seen;
  for (const auto& e : d.measurements.at('x'))
    for (const auto& f : e.factors) seen.insert(f.type);
  EXPECT_EQ(seen.size(), 16u);
  EXPECT_EQ(d.groundtruth->at('x').size(), 7u);
  EXPECT_FALSE(d.initialization.has_value());
  EXPECT_EQ(d.potential_outliers->at('x').size(), 2u);
  const auto& br = std::get<BearingRange3>(d.measurements.at('x')[1].factors[6].measured);
  EXPECT_DOUBLE_EQ(br.bearing.j, 0.8);
  const auto& q = std::get<Pose3Value>(d.measurements.at('x')[0].factors[0].measured).rotation;
  EXPECT_EQ(q.w(), -0.5);  // sign kept

  // Robot 'z' is not listed: ignored, like the reference parser. Canonical form = nlohmann's dump of the
  // document with that key dropped, "y": [] written as null, and the outlier set sorted/unique.
  nlohmann::json canon = nlohmann::json::parse(text);
  canon["measurements"].erase("z");
  canon["groundtruth"]["y"] = nullptr;
  canon["potential_outlier_factors"]["x"] = nlohmann::json::parse("[[0,1],[1,3]]");
  for (auto& e : canon["measurements"]["x"])
    if (e.contains("measurements"))
      for (auto& f : e["measurements"])
        for (auto& c : f["covariance"]) c = c.get<double>();
  for (auto& v : canon["groundtruth"]["x"])
    for (auto& [k, field] : v.items()) {
      if (k == "key" || k == "type") continue;
      if (field.is_array())
        for (auto& c : field) c = c.get<double>();
      else
        field = field.get<double>();
    }
  // groundtruth values are written sorted by key
  auto& gt = canon["groundtruth"]["x"];
  std::sort(gt.begin(), gt.end(), [](const auto& a, const auto& b) {
    return a["key"].template get<std::uint64_t>() < b["key"].template get<std::uint64_t>();
  });
  // integer translation / rotation of the first prior
  auto& prior = canon["measurements"]["x"][0]["measurements"][0]["prior"];
  for (const char* k : {"translation", "rotation"})
    for (auto& c : prior[k]) c = c.get<double>();
  EXPECT_EQ(dumpJrl(d), canon.dump());
  // and the written form reads back to the same bytes
  EXPECT_EQ(dumpJrl(parseJrl(dumpJrl(d), "again")), dumpJrl(d));
}

TEST(JrlErrors, CovarianceCountNamesThePlace) {
  const std::string bad =
      tinyWith("\"covariance\":[0.001,0.0,0.0,0.0,0.0,0.0,0.0,0.001,0.0,0.0,0.0,0.0,0.0,0.0,0.001,0.0005,",
               "\"covariance\":[0.0,0.0,0.0,0.0,0.0,0.0,0.001,0.0,0.0,0.0,0.0,0.0,0.0,0.001,0.0005,");
  const std::string what = parseError(bad);
  EXPECT_NE(what.find("bad.jrl: measurements.b[1].measurements[1].covariance: expected 36 numbers, got 35"),
            std::string::npos)
      << what;
}

TEST(JrlErrors, RejectsBadInputWithItsPath) {
  struct Case {
    std::string from, to, expect;
  };
  const std::vector<Case> cases = {
      {"\"robots\":[97,98]", "\"robots\":[\"a\",\"b\"]", "robots[0]: robot ids are integer char codes"},
      {"\"robots\":[97,98]", "\"robots\":[97,97]", "robots[1]: duplicate robot"},
      {"\"robots\":[97,98]", "\"robots\":[97,-98]", "robots[1]: robot code -98"},
      {"\"robots\":[97,98]", "\"robots\":97", "robots: expected an array"},
      {"\"key\":6989586621679009792,\"prior\"", "\"key\":6.989586621679009792e18,\"prior\"",
       "measurements.a[0].measurements[0].key: expected an integer key, got floating-point number"},
      {"\"key\":6989586621679009792,\"prior\"", "\"key\":\"6989586621679009792\",\"prior\"",
       "measurements.a[0].measurements[0].key: expected an integer key, got string"},
      {"\"key\":6989586621679009792,\"prior\"", "\"key\":-1,\"prior\"",
       "measurements.a[0].measurements[0].key: expected a non-negative integer key"},
      {"\"key\":6989586621679009792,\"prior\"", "\"prior\"",
       "measurements.a[0].measurements[0]: missing field \"key\""},
      {"\"stamp\":1700000000500000000", "\"stamp\":1700000000.5", "measurements.a[1].stamp: expected an integer stamp"},
      {"\"stamp\":1700000000500000000", "\"stamp\":-1", "measurements.a[1].stamp: expected a non-negative integer"},
      {"\"stamp\":1700000000500000000", "\"stamp_\":1", "measurements.a[1]: missing field \"stamp\""},
      {"\"rotation\":[1.0,0.0,0.0,0.0],\"translation\":[0.0,0.0,0.0],\"type\":\"Pose3\"},\"type\":\"Prior",
       "\"rotation\":[1.0,0.0,0.1,0.0],\"translation\":[0.0,0.0,0.0],\"type\":\"Pose3\"},\"type\":\"Prior",
       "measurements.a[0].measurements[0].prior.rotation: quaternion [w,x,y,z] is not unit"},
      {"\"translation\":[2.0,0.0,0.0]", "\"translation\":[2.0,null,0.0]",
       "groundtruth.a[1].translation[1]: expected a number, got null"},
      {"\"translation\":[2.0,0.0,0.0]", "\"translation\":[2.0,0.0]",
       "groundtruth.a[1].translation: expected 3 numbers, got 2"},
      {"\"translation\":[2.0,0.0,0.0]", "\"translation\":[2.0,\"0\",0.0]",
       "groundtruth.a[1].translation[1]: expected a number, got string"},
      {"\"translation\":[2.0,0.0,0.0]", "\"translation\":[2.0,1e999,0.0]",
       "invalid JSON: number overflow parsing '1e999'"},
      {"\"type\":\"PriorFactorPose3\"", "\"type\":\"PriorFactorPose4\"",
       "measurements.a[0].measurements[0].type: unknown factor type \"PriorFactorPose4\""},
      {"\"translation\":[2.0,0.0,0.0],\"type\":\"Pose3\"", "\"translation\":[2.0,0.0,0.0],\"type\":\"Rot3\"",
       "groundtruth.a[1].type: unknown value type \"Rot3\""},
      {"{\"key\":6989586621679009793,\"rotation\":[1.0,0.0,0.0,0.0],\"translation\":[2.0,0.0,0.0]",
       "{\"key\":6989586621679009792,\"rotation\":[1.0,0.0,0.0,0.0],\"translation\":[2.0,0.0,0.0]",
       "groundtruth.a[1]: duplicate key a0"},
      {"\"name\":\"tiny_example\",", "", "missing field \"name\""},
      {"\"name\":\"tiny_example\",", "\"name\":7,", "name: expected a string, got integer 7"},
      {"\"outlier_factors\":{\"a\":[[2,1]]", "\"outlier_factors\":{\"a\":null", "outlier_factors.a: expected an array"},
      {"\"outlier_factors\":{\"a\":[[2,1]]", "\"outlier_factors\":{\"a\":[[2,1,0]]",
       "outlier_factors.a[0]: expected an [entry, measurement] pair"},
      {"\"outlier_factors\":{\"a\":[[2,1]]", "\"outlier_factors\":{\"a\":[[2,1.5]]",
       "outlier_factors.a[0][1]: expected an integer measurement index"},
      {"\"outlier_factors\":{\"a\":[[2,1]],\"b\":[]}", "\"outlier_factors\":[[2,1]]",
       "outlier_factors: expected an object keyed by robot id"},
      {"\"measurement\":{\"rotation\":[1.0,0.0,0.0,0.0],\"translation\":[2.25,0.0,0.0],\"type\":\"Pose3\"}",
       "\"measurement\":{\"rotation\":[1.0,0.0,0.0,0.0],\"type\":\"Pose3\"}",
       "measurements.a[1].measurements[0].measurement: missing field \"translation\""},
      {"\"measurements\":{\"a\":[", "\"measurements\":{\"a\":[7,", "measurements.a[0]: expected an entry object"},
  };
  for (const auto& c : cases) {
    const std::string what = parseError(tinyWith(c.from, c.to));
    EXPECT_NE(what.find(c.expect), std::string::npos) << "got: " << what << "\nexpected: " << c.expect;
    EXPECT_EQ(what.rfind("bad.jrl: ", 0), 0u) << what;
  }
}

TEST(JrlErrors, TruncatedAndNonJson) {
  const std::string text = cosmo::readWholeFileOrEmpty(tinyPath());
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{100}, text.size() / 2, text.size() - 1}) {
    const std::string what = parseError(text.substr(0, n));
    EXPECT_NE(what.find("invalid JSON"), std::string::npos) << what;
  }
  EXPECT_NE(parseError("[1,2,3]").find("expected a JSON object at the top level"), std::string::npos);
  EXPECT_NE(parseError(text + "x").find("invalid JSON"), std::string::npos);
}

TEST(JrlErrors, BareRangeNumberRejected) {
  const std::string text = R"({"name":"r","robots":[97],"measurements":{"a":[{"stamp":1,"measurements":[
    {"type":"RangeFactor3D","key1":1,"key2":2,"measurement":5.2,"covariance":[0.01]}]}]}})";
  EXPECT_NE(parseError(text).find("measurements.a[0].measurements[0].measurement: expected a Scalar object"),
            std::string::npos);
}

TEST(JrlWriter, RejectsNonFiniteAndWrongShapes) {
  Dataset d;
  d.name = "w";
  d.robots = {'a'};
  Matrix6 cov = Matrix6::Identity();
  d.measurements['a'].push_back({1, {Factor::priorPose3(symbol('a', 0), cosmo::Pose3::Identity(), cov)}});
  EXPECT_NO_THROW(dumpJrl(d));
  d.measurements['a'][0].factors[0].covariance[7] = std::nan("");
  try {
    dumpJrl(d);
    FAIL();
  } catch (const JrlError& e) {
    EXPECT_NE(std::string(e.what()).find("measurements.a[0].measurements[0].covariance[7]"), std::string::npos)
        << e.what();
  }
  d.measurements['a'][0].factors[0].covariance.resize(35, 0.0);
  EXPECT_THROW(dumpJrl(d), JrlError);
  d.measurements['a'][0].factors[0] = Factor::priorPose3(symbol('a', 0), cosmo::Pose3::Identity(), cov);
  d.measurements['a'][0].factors[0].keys.push_back(3);
  EXPECT_THROW(dumpJrl(d), JrlError);
  d.measurements['a'][0].factors[0].keys.pop_back();
  d.measurements['q'];  // robot not listed
  EXPECT_THROW(dumpJrl(d), JrlError);
}

TEST(JrlModel, Pose3FactorConstructorsMatchTheFileConvention) {
  Matrix6 cov = Matrix6::Identity() * 1e-4;
  cov(2, 3) = cov(3, 2) = 5e-5;
  const cosmo::Pose3 T = cosmo::makePose(1.0, -2.0, 0.5, 0.1, -0.2, 2.5);
  const Factor f = Factor::betweenPose3(symbol('a', 3), symbol('b', 7), T, cov);
  EXPECT_EQ(f.keys, (std::vector<Key>{symbol('a', 3), symbol('b', 7)}));
  EXPECT_TRUE(f.pose3().isApprox(T, 1e-12));
  EXPECT_TRUE(f.covarianceMatrix().isApprox(Eigen::MatrixXd(cov)));
  EXPECT_DOUBLE_EQ(f.covariance[2 * 6 + 3], 5e-5);
  const Dataset one = [&] {
    Dataset d;
    d.name = "one";
    d.robots = {'a', 'b'};
    d.measurements['a'].push_back({5, {f}});
    return d;
  }();
  const Dataset back = parseJrl(dumpJrl(one));
  EXPECT_TRUE(back.measurements.at('a')[0].factors[0].pose3().isApprox(T, 1e-12));
  EXPECT_TRUE(back.measurements.at('b').empty());
  // An absent robot is written as null entries, like the reference Writer.
  EXPECT_NE(dumpJrl(one).find("\"b\":null"), std::string::npos);
}
