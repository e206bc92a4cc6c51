// The dataset figures (issue 25): content of the SVGs (robots, closures solid / dashed, table, scale bar),
// determinism, and the files written next to a JRL (with PNGs when ImageMagick is installed); the connectivity
// timeline when the radio run's connectivity is beside the JRL.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <unistd.h>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/common/whole_file.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "cosmo/report/figures.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(ReportFigures, TinyExampleTrajectoriesFigure) {
  const jrl::Dataset d = jrl::readJrl(kTiny);
  const std::string svg = report::trajectoriesSvg(d, {"tiny_example.jrl"});
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(count(svg, "<polyline"), 2u);  // one reference trajectory per robot
  // Two loop closures: the outlier dashed (plus the legend's dashed sample), the inlier solid.
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2u);
  for (const char* text : {">tiny_example<", ">tiny_example.jrl<", ">trials<", ">LC<", ">IRLC<", "1 (100.0 % outliers)",
                           "1 (0.0 % outliers)", " m</text>", "x [m]", "y [m]"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  EXPECT_EQ(svg, report::trajectoriesSvg(d, {"tiny_example.jrl"}));
}

TEST(ReportFigures, TinyExampleFrontendFigure) {
  const jrl::Dataset d = jrl::readJrl(kTiny);
  const std::string svg = report::frontendSvg(d);
  EXPECT_EQ(count(svg, "<polyline"), 6u);  // reference and odometry per robot, reference again in (b)
  EXPECT_EQ(count(svg, "<circle"), 5u);    // a dot per keyframe (own poses)
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2u);
  EXPECT_EQ(svg, report::frontendSvg(d));
}

TEST(ReportFigures, FiveRobotsTwoThousandClosuresStayReadable) {
  std::mt19937_64 rng(4);
  jrl::SyntheticParams p;
  p.robots = {'a', 'b', 'c', 'd', 'e'};
  p.poses_per_robot = 700;
  const jrl::Dataset d = jrl::makeSyntheticDataset(p, rng);
  const jrl::DatasetStats s = jrl::computeStats(d);
  ASSERT_GT(s.lc_count + s.irlc_count, 1900u);
  const std::string svg = report::trajectoriesSvg(d);
  EXPECT_EQ(count(svg, "<polyline"), 5u);
  EXPECT_EQ(count(svg, "<line"),
            s.lc_count + s.irlc_count + 3u /*scale bar*/ + 8u /*legend*/ + count(svg, "stroke=\"#dddddd\""));
  // Every robot has its own colour.
  std::set<std::string> colors;
  const std::regex re("<polyline fill=\"none\" stroke-linejoin=\"round\" stroke=\"(#[0-9a-f]{6})\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    colors.insert((*it)[1]);
  EXPECT_EQ(colors.size(), 5u);
}

TEST(ReportFigures, WritesBothFiguresBesideTheJrl) {
  const fs::path dir = fs::temp_directory_path() / ("cosmo_test_figures_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const jrl::Dataset d = jrl::readJrl(kTiny);
  const std::string jrl_path = (dir / "tiny_example.jrl").string();
  auto written = report::writeDatasetFigures(d, jrl_path, "", false);
  EXPECT_EQ(written, (std::vector<std::string>{(dir / "tiny_example.trajectories.svg").string(),
                                               (dir / "tiny_example.frontend.svg").string()}));
  for (const auto& p : written) EXPECT_GT(fs::file_size(p), 1000u);
  written = report::writeDatasetFigures(d, jrl_path, (dir / "out").string(), true);
  EXPECT_TRUE(fs::exists(dir / "out" / "tiny_example.frontend.svg"));
  if (std::system("command -v convert >/dev/null 2>&1") == 0) {
    EXPECT_EQ(written.size(), 4u);
    EXPECT_TRUE(fs::exists(dir / "out" / "tiny_example.trajectories.png"));
  } else {
    std::cout << "ImageMagick convert not installed: no PNG checked\n";
  }
  EXPECT_THROW(report::writeDatasetFigures(d, "/proc/no/such/dir/x.jrl", "", false), std::exception);
  fs::remove_all(dir);
}

// With the radio run's connectivity beside the JRL, a third figure: the timeline of each pair (its up intervals as
// bands, its throughput as a line) and the robots in range, the same bytes each time.
TEST(ReportFigures, ConnectivityTimelineWhenTheRunsConnectivityIsBesideTheJrl) {
  const fs::path dir = fs::temp_directory_path() / ("cosmo_test_conn_figure_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  comm::ConnectivityTracker tracker({'a', 'b', 'c'}, 0.1, 1.0);
  for (int i = 1; i <= 300; ++i) {
    if (i < 100) tracker.addBytes('a', 'b', 80000.0);
    tracker.endStep(
        0.1 * i, [&](char a, char b) { return a == 'a' ? (i < 120 || i > 200) : i > 50; }, [](char) { return true; });
  }
  std::ofstream(dir / "tiny_example_connectivity.json") << tracker.result().toJson().dump();
  const jrl::Dataset d = jrl::readJrl(kTiny);
  const std::string jrl_path = (dir / "tiny_example.jrl").string();
  const auto written = report::writeDatasetFigures(d, jrl_path, "", false);
  ASSERT_EQ(written.size(), 3u);
  EXPECT_EQ(written[2], (dir / "tiny_example.connectivity.svg").string());
  const std::string svg = cosmo::readWholeFileOrEmpty(written[2]);
  EXPECT_NE(svg.find("tiny_example: connectivity over time"), std::string::npos);
  EXPECT_NE(svg.find("a–b: 73.0 % connected, 1 disconnection"), std::string::npos);
  EXPECT_NE(svg.find("b–c: 83.3 % connected, 0 disconnections"), std::string::npos);
  EXPECT_EQ(count(svg, "fill=\"#7fcf7f\""), 5u);  // ab and ac up twice each, bc once
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(report::writeDatasetFigures(d, jrl_path, "", false)[2]), svg);
  fs::remove_all(dir);
}

TEST(ReportFigures, ReferenceFileTable) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const std::string svg = report::trajectoriesSvg(jrl::readJrl(*path));
  for (const char* text : {">12:06<", ">2.13 km<", ">356 (13.5 % outliers)<", ">280 (9.6 % outliers)<"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
}
