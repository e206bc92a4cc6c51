// The report's tables as a browser and a markdown viewer see them: report.html parsed back into tables and cells
// (no markdown left in a cell, every row as wide as its header, every figure followed by its table, text escaped),
// report.md's table lines as wide as their headers.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cosmo/comm/connectivity.hpp"
#include "cosmo/suite/paper_table.hpp"
#include "cosmo/suite/report.hpp"
#include "suite_fixture.hpp"

using namespace cosmo::suite;
using suite_test::Folder;
using suite_test::group;
using suite_test::record;

namespace {

struct Cell {
  bool header = false;
  std::string text;  ///< entities decoded, <br> as a line break
};
using HtmlRow = std::vector<Cell>;
using HtmlTable = std::vector<HtmlRow>;

struct ParsedHtml {
  std::vector<HtmlTable> tables;
  std::vector<std::string> figures_and_tables;  ///< "img", "nofig" and "table" in document order
};

std::string decodeEntities(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const std::size_t end = s.find(';', i);
    EXPECT_NE(end, std::string::npos) << "a bare & in " << s;
    if (end == std::string::npos) return out + s.substr(i);
    const std::string name = s.substr(i + 1, end - i - 1);
    out += name == "lt" ? "<" : name == "gt" ? ">" : name == "amp" ? "&" : name == "quot" ? "\"" : "&" + name + ";";
    i = end;
  }
  return out;
}

/// The tables (rows of th / td cells) and the order of figures and tables of an HTML page; fails the test on
/// text between cells of a row or a cell outside a row.
ParsedHtml parseHtml(const std::string& html) {
  ParsedHtml p;
  HtmlTable* table = nullptr;
  Cell* cell = nullptr;
  std::size_t i = 0;
  while (i < html.size()) {
    if (html[i] != '<') {
      const std::size_t end = std::min(html.find('<', i), html.size());
      const std::string text = html.substr(i, end - i);
      if (cell) {
        cell->text += decodeEntities(text);
      } else if (table) {
        EXPECT_EQ(text.find_first_not_of(" \n"), std::string::npos) << "text outside the cells: " << text;
      }
      i = end;
      continue;
    }
    const std::size_t end = html.find('>', i);
    if (end == std::string::npos) {
      ADD_FAILURE() << "an unclosed tag at " << i;
      break;
    }
    const std::string tag = html.substr(i + 1, end - i - 1);
    const std::string name = tag.substr(0, tag.find_first_of(" /"));
    if (name == "table") {
      p.tables.emplace_back();
      table = &p.tables.back();
      p.figures_and_tables.push_back("table");
    } else if (name == "img") {
      p.figures_and_tables.push_back("img");
    } else if (name == "div" && tag.find("class=\"nofig\"") != std::string::npos) {
      p.figures_and_tables.push_back("nofig");
    } else if (tag == "/table") {
      EXPECT_FALSE(cell) << "a cell left open";
      table = nullptr;
    } else if (name == "tr") {
      EXPECT_TRUE(table) << "a row outside a table";
      if (table) table->emplace_back();
    } else if (name == "th" || name == "td") {
      EXPECT_TRUE(table && !table->empty()) << "a cell outside a row";
      EXPECT_FALSE(cell) << "a cell inside a cell";
      if (table && !table->empty()) {
        table->back().push_back({name == "th", ""});
        cell = &table->back().back();
      }
    } else if (tag == "/th" || tag == "/td") {
      cell = nullptr;
    } else if (name == "br" && cell) {
      cell->text += "\n";
    } else if (cell) {
      ADD_FAILURE() << "a tag <" << tag << "> in a cell";
    }
    i = end + 1;
  }
  return p;
}

/// The cells of a markdown table line, split at the '|' that are not escaped.
std::vector<std::string> markdownCells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      cells.push_back(cell);
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return cells;
}

const char* kFailed = "failed: cosmo_generate failed (exit code 1)\nlast lines: <stderr> & \"quoted\" | piped";

/// Three groups of two datasets (two figures, one group failed with a status of two lines, markup in it) and an
/// estimate, beside the paper's values.
struct Fixture {
  Folder f;
  PaperTable paper = PaperTable::load(std::string(COSMO_SOURCE_DIR) + "/config/paper/fig1.yaml");
  std::vector<Job> jobs{group("s1", "tuhh_r3_01"), group("s2", "tuhh_r3_01"), group("s3", "tuhh_r3_01"), Job{}};
  ReportInput in;

  Fixture() {
    jobs[3].kind = Job::Kind::Estimate;
    jobs[3].id = "noise_models/tuhh_r3_01";
    JobRecord r1 = record("s1", 350, 1.1), r2 = record("s2", 360, 1.3);
    r1.datasets[0].figure = "s1_wifi.trajectories.svg";
    r2.datasets[1].figure = "s2_proradio.trajectories.svg";
    const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"40\" height=\"30\"></svg>";
    f.write("s1/s1_wifi.trajectories.svg", svg);
    f.write("s2/s2_proradio.trajectories.svg", svg);
    in.suite_name = "report <test>";
    in.suite_path = "suite.yaml";
    in.out_dir = f.root.string();
    in.note = "4 jobs.";
    in.paper = &paper;
    in.jobs = {{&jobs[0], r1, "done"},
               {&jobs[1], r2, "skipped as current"},
               {&jobs[2], std::nullopt, kFailed},
               {&jobs[3], std::nullopt, "done"}};
  }
};

}  // namespace

TEST(ReportHtml, EveryCellIsPlainTextAndEveryRowAsWideAsItsHeader) {
  Fixture fx;
  const ParsedHtml p = parseHtml(reportHtml(fx.in));
  // The datasets table, a table per dataset (six), the variants' table.
  ASSERT_EQ(p.tables.size(), 8u);
  for (const HtmlTable& t : p.tables) {
    ASSERT_GE(t.size(), 2u);
    const std::size_t width = t.front().size();
    EXPECT_GE(width, 3u);
    for (const Cell& c : t.front()) EXPECT_TRUE(c.header) << c.text;
    for (std::size_t r = 1; r < t.size(); ++r) {
      EXPECT_EQ(t[r].size(), width) << "row " << r << " of the table headed " << t.front()[1].text;
      for (const Cell& c : t[r]) EXPECT_FALSE(c.header) << c.text;
    }
    for (const HtmlRow& row : t)
      for (const Cell& c : row) {
        if (c.text == kFailed) continue;  // the status, which holds a '|' of its own
        EXPECT_EQ(c.text.find('|'), std::string::npos) << c.text;
        EXPECT_EQ(c.text.find("---"), std::string::npos) << c.text;
      }
  }
  // The per-dataset table: an empty corner, then ours, the paper's, the difference.
  const HtmlTable& first = p.tables[1];
  EXPECT_EQ(first[0][0].text, "");
  EXPECT_EQ(first[0][1].text, "ours");
  EXPECT_EQ(first[1][0].text, "duration");
  EXPECT_EQ(first[1][1].text, "12:07");
  EXPECT_EQ(first[1][3].text, "+00:01");
  EXPECT_EQ(first[5][2].text, "");
  EXPECT_EQ(first[6][3].text, "the run of all comm models");
  // The failed group's status: both lines in one cell, its markup as text.
  const HtmlTable& failed = p.tables[5];
  EXPECT_EQ(failed.back()[0].text, "status");
  EXPECT_EQ(failed.back()[1].text, kFailed);
}

TEST(ReportHtml, EveryFigureIsFollowedByItsTable) {
  Fixture fx;
  const std::string html = reportHtml(fx.in);
  const ParsedHtml p = parseHtml(html);
  std::size_t figures = 0, cards = 0;
  for (std::size_t i = 0; i < p.figures_and_tables.size(); ++i) {
    const std::string& what = p.figures_and_tables[i];
    if (what != "img" && what != "nofig") continue;
    ++cards;
    figures += what == "img";
    ASSERT_LT(i + 1, p.figures_and_tables.size());
    EXPECT_EQ(p.figures_and_tables[i + 1], "table") << "figure " << cards;
  }
  EXPECT_EQ(figures, 2u);
  EXPECT_EQ(cards, 6u);
  EXPECT_EQ(html.find("<stderr>"), std::string::npos);
  EXPECT_NE(html.find("<title>Suite report &lt;test&gt;</title>"), std::string::npos);
}

TEST(ReportHtml, TheMarkdownTablesKeepTheirWidthToo) {
  Fixture fx;
  const std::string md = reportMarkdown(fx.in);
  std::istringstream in(md);
  std::string line;
  std::size_t width = 0, tables = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '|') {
      width = 0;
      continue;
    }
    const auto cells = markdownCells(line);
    if (width == 0) {
      width = cells.size();
      ++tables;
    }
    EXPECT_EQ(cells.size(), width) << line;
  }
  EXPECT_EQ(tables, 9u);  // the datasets, the figures, six datasets, the variants
  EXPECT_NE(md.find("| status | failed: cosmo_generate failed (exit code 1)<br>last lines: <stderr> & \"quoted\" \\| "
                    "piped | | |"),
            std::string::npos)
      << md;
}

// A dataset whose folder holds its radio run's connectivity (and its figure) gets a Connectivity section: the
// figure, then a table with a row per robot pair, in both forms.
TEST(ReportHtml, TheConnectivitySectionShowsEachPairUnderItsFigure) {
  Fixture fx;
  JobRecord r1 = *fx.in.jobs[0].record;
  r1.datasets[0].jrl = "s1_wifi.jrl";
  fx.in.jobs[0].record = r1;
  cosmo::comm::Connectivity c;
  c.step_s = 0.1;
  c.steps = 1000;
  c.robots = "abc";
  c.end_s = 100.0;
  for (const char* ab : {"ab", "ac", "bc"}) {
    cosmo::comm::PairConnectivity p;
    p.a = ab[0];
    p.b = ab[1];
    p.connected_s = ab[1] == 'b' ? 31.24 : 70.0;
    p.bytes_connected = 800000.0 * p.connected_s;
    p.bytes = p.bytes_connected;
    p.disconnections = 1;
    p.delivered_ab = 12;
    p.dropped_ba = 2;
    c.pairs.push_back(p);
  }
  fx.f.write("s1/s1_wifi_connectivity.json", c.toJson().dump());
  fx.f.write("s1/s1_wifi.connectivity.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>");

  const std::string html = reportHtml(fx.in);
  const ParsedHtml p = parseHtml(html);
  ASSERT_EQ(p.tables.size(), 9u);  // the eight above and the connectivity table
  const HtmlTable& t = p.tables.back();
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0][1].text, "connected");
  EXPECT_EQ(t[1][0].text, "a–b");
  EXPECT_EQ(t[1][1].text, "31.2 % (31.2 s)");
  EXPECT_EQ(t[1][2].text, "1");
  EXPECT_EQ(t[1][3].text, "a→b 12 / 0, b→a 0 / 2");
  EXPECT_EQ(t[1][4].text, "800 kB/s");
  EXPECT_EQ(t[2][1].text, "70.0 % (70.0 s)");
  ASSERT_GE(p.figures_and_tables.size(), 2u);
  EXPECT_EQ(p.figures_and_tables[p.figures_and_tables.size() - 2], "img");
  EXPECT_EQ(p.figures_and_tables.back(), "table");
  EXPECT_NE(html.find("<h2>Connectivity</h2>"), std::string::npos);

  const std::string md = reportMarkdown(fx.in);
  EXPECT_NE(md.find("## Connectivity"), std::string::npos);
  EXPECT_NE(md.find("![s1_wifi connectivity](s1/s1_wifi.connectivity.svg)"), std::string::npos) << md;
  EXPECT_NE(md.find("| a–b | 31.2 % (31.2 s) | 1 | a→b 12 / 0, b→a 0 / 2 | 800 kB/s | 25.0 MB |"), std::string::npos)
      << md;
}
