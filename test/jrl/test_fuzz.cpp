// Randomized fuzzing of the JRL reader: seeded mutations (truncations, byte flips, deletions, duplications,
// value type swaps, tag/field-name swaps) of small valid documents (tiny example + test/jrl/corpus/*.jrl).
// Every input must parse or throw std::runtime_error (JrlError), never crash or throw anything else; what
// parses must be writable, re-read to the same bytes, and checkable by validate().
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>

#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo::jrl;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> seeds() {
  const fs::path root = fs::path(COSMO_SOURCE_DIR) / "test" / "jrl";
  std::vector<std::string> out{cosmo::readWholeFileOrEmpty(root / "data" / "tiny_example.jrl")};
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(root / "corpus"))
    if (e.path().extension() == ".jrl") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // deterministic order
  for (const auto& f : files) out.push_back(cosmo::readWholeFileOrEmpty(f));
  return out;
}

const std::vector<std::string> kValues = {"\"s\"",
                                          "null",
                                          "[]",
                                          "{}",
                                          "true",
                                          "-1",
                                          "1.5",
                                          "1e999",
                                          "18446744073709551616",
                                          "0",
                                          "-0.0",
                                          "\"a\"",
                                          "[1,2]",
                                          "[[0,0]]",
                                          "97",
                                          "{\"type\":\"Scalar\",\"value\":1}",
                                          "6989586621679009792",
                                          "1e-320",
                                          "-1e308"};
const std::vector<std::string> kNames = {"key",
                                         "key1",
                                         "key2",
                                         "type",
                                         "prior",
                                         "measurement",
                                         "covariance",
                                         "stamp",
                                         "measurements",
                                         "rotation",
                                         "translation",
                                         "robots",
                                         "name",
                                         "groundtruth",
                                         "initialization",
                                         "outlier_factors",
                                         "potential_outlier_factors",
                                         "Pose3",
                                         "Pose2",
                                         "Point2",
                                         "Point3",
                                         "Vector",
                                         "Scalar",
                                         "Rot2",
                                         "Unit3",
                                         "BearingRange",
                                         "PriorFactorPose2",
                                         "BetweenFactorPoint3",
                                         "RangeFactor3D",
                                         "BearingRangeFactorPose3",
                                         "BearingRangeFactor2D",
                                         "a",
                                         "b",
                                         "x",
                                         "data",
                                         "value",
                                         "bearing",
                                         "range",
                                         "theta",
                                         ""};

std::string mutate(std::string s, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
  const int rounds = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < rounds && !s.empty(); ++k) {
    switch (rng() % 7) {
      case 0:  // truncate
        s.resize(pick(s.size()));
        break;
      case 1:  // byte flip
        s[pick(s.size())] = static_cast<char>(rng() & 0xff);
        break;
      case 2: {  // delete a range
        const std::size_t a = pick(s.size()), n = 1 + pick(std::min<std::size_t>(40, s.size() - a));
        s.erase(a, n);
        break;
      }
      case 3: {  // duplicate a range somewhere else
        const std::size_t a = pick(s.size()), n = 1 + pick(std::min<std::size_t>(60, s.size() - a));
        s.insert(pick(s.size() + 1), s.substr(a, n));
        break;
      }
      case 4: {  // swap a number for another JSON value
        std::size_t p = pick(s.size());
        while (p < s.size() && !(std::isdigit(static_cast<unsigned char>(s[p])) || s[p] == '-')) ++p;
        if (p >= s.size()) break;
        std::size_t e = p;
        while (e < s.size() && std::strchr("0123456789+-.eE", s[e])) ++e;
        s.replace(p, e - p, kValues[pick(kValues.size())]);
        break;
      }
      case 5: {  // swap a string (field name or tag) for another known one
        std::size_t p = s.find('"', pick(s.size()));
        if (p == std::string::npos) break;
        const std::size_t e = s.find('"', p + 1);
        if (e == std::string::npos) break;
        s.replace(p + 1, e - p - 1, kNames[pick(kNames.size())]);
        break;
      }
      default:  // swap a bracketed value for another JSON value
      {
        std::size_t p = s.find_first_of("[{", pick(s.size()));
        if (p == std::string::npos) break;
        const char open = s[p], close = open == '[' ? ']' : '}';
        int depth = 0;
        std::size_t e = p;
        for (; e < s.size(); ++e) {
          depth += s[e] == open ? 1 : s[e] == close ? -1 : 0;
          if (depth == 0) break;
        }
        if (e >= s.size()) break;
        s.replace(p, e - p + 1, kValues[pick(kValues.size())]);
        break;
      }
    }
  }
  return s;
}

}  // namespace

TEST(JrlFuzz, MutatedDocumentsParseOrThrowRuntimeError) {
  const auto corpus = seeds();
  ASSERT_GE(corpus.size(), 3u);
  // Deterministic by default; COSMO_FUZZ_SEED / COSMO_FUZZ_ITERATIONS allow longer exploratory runs.
  const char* seed_env = std::getenv("COSMO_FUZZ_SEED");
  const char* iter_env = std::getenv("COSMO_FUZZ_ITERATIONS");
  std::mt19937_64 rng(seed_env ? std::strtoull(seed_env, nullptr, 10) : 20261122ull);
  const int kIterations = iter_env ? std::max(100, std::atoi(iter_env)) : 6000;
  int parsed = 0, rejected = 0;
  for (int i = 0; i < kIterations; ++i) {
    const std::string input = mutate(corpus[static_cast<std::size_t>(i) % corpus.size()], rng);
    try {
      const Dataset d = parseJrl(input, "fuzz");
      ++parsed;
      const std::string out = dumpJrl(d);
      ASSERT_EQ(dumpJrl(parseJrl(out, "fuzz-redump")), out) << "iteration " << i << " input:\n" << input;
      (void)validate(d);
    } catch (const std::runtime_error& e) {
      ++rejected;
      ASSERT_NE(std::string(e.what()).find("fuzz"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      FAIL() << "iteration " << i << ": unexpected " << typeid(e).name() << ": " << e.what() << "\ninput:\n" << input;
    }
  }
  // Both outcomes must actually be exercised.
  EXPECT_GT(parsed, kIterations / 50) << "parsed " << parsed << ", rejected " << rejected;
  EXPECT_GT(rejected, kIterations / 2) << "parsed " << parsed << ", rejected " << rejected;
  std::cout << "fuzz: " << parsed << " parsed, " << rejected << " rejected of " << kIterations << "\n";
}

TEST(JrlFuzz, CorpusSeedsAreValidDocuments) {
  for (const auto& s : seeds()) EXPECT_NO_THROW(parseJrl(s, "seed"));
}
