// stats(): the paper's Fig. 1 values for tuhh_r3_01 with the Wi-Fi model, and the tiny example by hand.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"

using namespace cosmo::jrl;

TEST(JrlStats, ReferenceFileMatchesThePaper) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const DatasetStats s = computeStats(readJrl(*path));
  EXPECT_EQ(s.name, "tuhh_r3_01_night_wifi");
  EXPECT_EQ(s.robots, (std::vector<char>{'a', 'b', 'c'}));
  EXPECT_EQ(formatDuration(s.duration_s), "12:06");
  EXPECT_EQ(s.durationRoundedS(), 726);
  EXPECT_NEAR(s.length_m / 1000.0, 2.13, 0.005);
  EXPECT_EQ(s.lc_count, 356u);
  EXPECT_EQ(s.irlc_count, 280u);
  EXPECT_EQ(s.odometry, 1022u);
  EXPECT_EQ(s.priors, 3u);
  EXPECT_EQ(s.factors, 1661u);
  EXPECT_EQ(s.lc_outliers + s.irlc_outliers, 75u);
  EXPECT_NEAR(s.lcOutlierPercent(), 13.5, 0.05);
  EXPECT_NEAR(s.irlcOutlierPercent(), 9.6, 0.05);
  const std::string text = formatStats(s);
  for (const char* want : {"duration  12:06", "length    2.13 km", "LC        356 (13.5 %)", "IRLC      280 (9.6 %)"})
    EXPECT_NE(text.find(want), std::string::npos) << want << "\n" << text;
  const auto j = nlohmann::json::parse(statsJson(s));
  EXPECT_EQ(j.at("name"), "tuhh_r3_01_night_wifi");
  EXPECT_EQ(j.at("robots"), nlohmann::json::parse(R"(["a","b","c"])"));
  EXPECT_EQ(j.at("duration_s"), 726);
  EXPECT_NEAR(j.at("length_m").get<double>(), 2130.0, 5.0);
  EXPECT_EQ(j.at("lc_count"), 356);
  EXPECT_EQ(j.at("lc_outliers"), 48);
  EXPECT_EQ(j.at("irlc_count"), 280);
  EXPECT_EQ(j.at("irlc_outliers"), 27);
}

TEST(JrlStats, TinyExampleByHand) {
  const DatasetStats s = computeStats(readJrl(std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl"));
  EXPECT_EQ(s.entries, 5u);
  EXPECT_EQ(s.factors, 7u);
  EXPECT_EQ(s.priors, 2u);
  EXPECT_EQ(s.odometry, 3u);
  EXPECT_EQ(s.lc_count, 1u);
  EXPECT_EQ(s.lc_outliers, 1u);
  EXPECT_EQ(s.irlc_count, 1u);
  EXPECT_EQ(s.irlc_outliers, 0u);
  EXPECT_DOUBLE_EQ(s.duration_s, 1.0);
  EXPECT_DOUBLE_EQ(s.length_m, 6.0);  // a: 2 + 2 m, b: 2 m; b's copy of a1 is not b's own pose
}

TEST(JrlStats, DurationFormatAndEmptyDataset) {
  EXPECT_EQ(formatDuration(725.874), "12:06");
  EXPECT_EQ(formatDuration(59.4), "00:59");
  EXPECT_EQ(formatDuration(59.5), "01:00");
  EXPECT_EQ(formatDuration(4523.0), "75:23");
  Dataset d;
  d.name = "empty";
  d.robots = {'a'};
  const DatasetStats s = computeStats(d);
  EXPECT_EQ(s.entries, 0u);
  EXPECT_EQ(s.duration_s, 0.0);
  EXPECT_NE(formatStats(s).find("no groundtruth"), std::string::npos);
  EXPECT_NE(formatStats(s).find("no outlier labels"), std::string::npos);
}
