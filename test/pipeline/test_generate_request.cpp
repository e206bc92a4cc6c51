// cosmo_generate's options as a struct (pipeline/generate_request.hpp): the command line the suite writes from a request
// (generateArgs) reads back into the same request (addGenerateOptions), and a request's checks name the option.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cosmo/pipeline/generate_request.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

namespace {

GenerateRequest parsed(const std::vector<std::string>& args) { return generateRequestFromArgs(args); }

}  // namespace

TEST(GenerateRequest, ArgumentsReadBackIntoTheSameRequest) {
  GenerateRequest r;
  r.sequence = "/data/seq/kth_r3_00.yaml";
  r.data_root = "/data";
  r.comms = {"wifi", "proradio", "/tmp/trace.csv"};
  r.seed = 7;
  r.max_seconds = 12.5;
  r.odometry = "reference";
  r.gate_threshold = 0.1 + 0.2;  // not 0.3: its text must read back as the same double
  r.config_dir = "/tmp/config overlay";
  r.noise_models = "/tmp/nm.yaml";
  r.outlier_rule = "squared";
  r.estimation.max_translation_error = 0.25;
  r.serial_odometry = true;
  r.registration_threads = 0;
  r.check = false;
  r.out_dir = "/tmp/out";
  r.quiet = true;
  const std::vector<std::string> args = generateArgs(r);
  EXPECT_EQ(args.front(), r.sequence);
  const GenerateRequest back = parsed(args);
  EXPECT_EQ(generateArgs(back), args);
  EXPECT_EQ(back.comms, r.comms);
  EXPECT_EQ(back.seed, r.seed);
  EXPECT_EQ(back.gate_threshold, r.gate_threshold);
  EXPECT_EQ(back.registration_threads, r.registration_threads);
  EXPECT_EQ(back.config_dir, r.config_dir);
  EXPECT_FALSE(back.check);
  EXPECT_DOUBLE_EQ(back.estimation.max_translation_error, 0.25);
  // the defaults write nothing but the sequence
  GenerateRequest plain;
  plain.sequence = "s.yaml";
  EXPECT_EQ(generateArgs(plain), std::vector<std::string>{"s.yaml"});
  EXPECT_FALSE(parsed({"s.yaml"}).seed.has_value());
  EXPECT_EQ(parsed({"s.yaml", "--reference-odometry"}).odometry, "reference");
  try {
    parsed({"s.yaml", "--odometry", "gps"});
    ADD_FAILURE() << "an odometry that does not exist was read";
  } catch (const std::runtime_error& e) { EXPECT_NE(std::string(e.what()).find("--odometry"), std::string::npos); }
}

TEST(GenerateRequest, ChecksNameTheOption) {
  const auto reason = [](GenerateRequest r) {
    try {
      r.validate();
    } catch (const std::runtime_error& e) { return std::string(e.what()); }
    return std::string("valid");
  };
  GenerateRequest r;
  r.sequence = "s.yaml";
  EXPECT_EQ(reason(r), "valid");
  GenerateRequest gate = r;
  gate.gate_threshold = 1.5;
  EXPECT_EQ(reason(gate).rfind("--gate-threshold: ", 0), 0u) << reason(gate);
  GenerateRequest both = r;
  both.estimate_trial = "a";
  both.noise_models = "x.yaml";
  EXPECT_NE(reason(both).find("give one of them"), std::string::npos);
  GenerateRequest only = r;
  only.estimate_only = true;
  EXPECT_NE(reason(only).find("--estimate-only"), std::string::npos);
  GenerateRequest rule = r;
  rule.outlier_rule = "chi2";
  EXPECT_NE(reason(rule).find("--outlier-rule"), std::string::npos);
}
