// The report: the paper's Fig. 1 table as the paper's source prints it, ours beside it with the difference, the
// statuses, the variants' summary, and an HTML file that needs nothing beside it.
#include <gtest/gtest.h>

#include <fstream>

#include "cosmo/suite/paper_table.hpp"
#include "cosmo/suite/report.hpp"
#include "suite_fixture.hpp"

using namespace cosmo::suite;
using suite_test::Folder;
using suite_test::group;
using suite_test::record;

namespace {

PaperTable paper() { return PaperTable::load(std::string(COSMO_SOURCE_DIR) + "/config/paper/fig1.yaml"); }

}  // namespace

TEST(PaperTable, HoldsThePapersTwelveSequences) {
  const PaperTable t = paper();
  EXPECT_EQ(t.size(), 12u);
  const auto r = t.find("tuhh_r3_01");
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->duration_s, 12 * 60 + 6);  // 12:06
  EXPECT_DOUBLE_EQ(r->length_m, 2130);
  EXPECT_EQ(r->lc, 356u);
  EXPECT_DOUBLE_EQ(r->lc_pct, 13.5);
  EXPECT_EQ(r->irlc.at("wifi").first, 280u);
  EXPECT_EQ(r->irlc.at("proradio").first, 719u);
  EXPECT_EQ(t.find("kittredge_loop")->irlc.at("wifi").first, 2821u);
  EXPECT_FALSE(t.find("synthetic_ci"));
}

TEST(Report, OursBesideThePapersWithTheDifferenceStatusesAndVariants) {
  Folder f;
  const PaperTable t = paper();
  std::vector<Job> jobs{group("tuhh_r3_01_s1", "tuhh_r3_01"), group("tuhh_r3_01_s2", "tuhh_r3_01"),
                        group("tuhh_r3_01_s3", "tuhh_r3_01")};
  ReportInput in;
  in.suite_name = "t";
  in.out_dir = f.root.string();
  in.paper = &t;
  in.jobs = {{&jobs[0], record("tuhh_r3_01_s1", 350, 1.1), "done"},
             {&jobs[1], record("tuhh_r3_01_s2", 360, 1.3), "skipped as current"},
             {&jobs[2], std::nullopt, "failed: cosmo_generate failed (exit code 1)\nlast lines"}};
  const std::string md = reportMarkdown(in);
  EXPECT_NE(md.find("| tuhh_r3_01_s1_wifi | done | 12:07 (12:06) | 2.15 km (2.13 km) | 350 (10.0 %) (356 (13.5 %)) | "
                    "300 (10.0 %) (280 (9.6 %)) | 1.100 m (init 25.700 m) | 730 s wall, 1400 s CPU, 512 MB |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| duration | 12:07 | 12:06 | +00:01 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| LC (outliers) | 350 (10.0 %) | 356 (13.5 %) | -6 (-3.5 pt) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| IRLC (outliers) | 300 (10.0 %) | 719 (6.4 %) | -419 (+3.6 pt) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| tuhh_r3_01_s3_proradio | failed: cosmo_generate failed (exit code 1) |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| tuhh_r3_01 | wifi | 2 | 355.0 (350.0 – 360.0) |"), std::string::npos) << md;
  EXPECT_NE(md.find("1.200 (1.100 – 1.300)"), std::string::npos) << md;
}

TEST(Report, TheHtmlCarriesItsFiguresInline) {
  Folder f;
  Job j = group("g", "g");
  JobRecord r = record("g", 10, 0.5);
  r.datasets[0].figure = "tuhh_r3_01_wifi.trajectories.svg";
  f.write("g/tuhh_r3_01_wifi.trajectories.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>");
  ReportInput in;
  in.suite_name = "t";
  in.out_dir = f.root.string();
  in.jobs = {{&j, r, "done"}};
  const std::string html = reportHtml(in);
  EXPECT_NE(html.find("src=\"data:image/svg+xml;base64,PHN2ZyB4bWxucz0i"), std::string::npos);
  EXPECT_EQ(html.find("src=\"g/"), std::string::npos);  // nothing read from beside the file
  EXPECT_NE(reportMarkdown(in).find("![g_wifi](g/tuhh_r3_01_wifi.trajectories.svg)"), std::string::npos);
}
