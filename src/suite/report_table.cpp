#include "report_table.hpp"

#include <stdexcept>

namespace cosmo::suite::report_table {
namespace {

void checkCells(const Table& t) {
  for (const auto& row : t.rows)
    if (row.size() != t.header.size())
      throw std::logic_error("report table: a row of " + std::to_string(row.size()) + " cells under a header of " +
                             std::to_string(t.header.size()));
}

std::string markdownCell(const std::string& s) {
  std::string o;
  for (const char c : s) o += c == '|' ? "\\|" : c == '\n' ? "<br>" : std::string(1, c);
  return o;
}

std::string markdownLine(const std::vector<std::string>& cells) {
  std::string line = "|";
  for (const auto& c : cells) line += c.empty() ? " |" : " " + markdownCell(c) + " |";
  return line + "\n";
}

std::string htmlLine(const std::vector<std::string>& cells, const char* tag) {
  std::string line = "<tr>";
  for (const auto& c : cells) {
    std::string text = escapeHtml(c);
    for (std::size_t p = 0; (p = text.find('\n', p)) != std::string::npos;) text.replace(p, 1, "<br>");
    line += std::string("<") + tag + ">" + text + "</" + tag + ">";
  }
  return line + "</tr>\n";
}

}  // namespace

std::string markdown(const Table& table) {
  checkCells(table);
  std::string out = markdownLine(table.header) + "|";
  for (std::size_t i = 0; i < table.header.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : table.rows) out += markdownLine(row);
  return out;
}

std::string html(const Table& table) {
  checkCells(table);
  std::string out = "<table>\n" + htmlLine(table.header, "th");
  for (const auto& row : table.rows) out += htmlLine(row, "td");
  return out + "</table>\n";
}

std::string escapeHtml(const std::string& s) {
  std::string o;
  for (const char c : s)
    o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return o;
}

}  // namespace cosmo::suite::report_table
