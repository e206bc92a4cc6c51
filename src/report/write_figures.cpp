// Writing the figures next to a JRL (or into a folder), with PNG copies through ImageMagick when installed.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cosmo/report/figures.hpp"

namespace fs = std::filesystem;

namespace cosmo::report {

namespace {

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write");
}

std::string shellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool converterInstalled() { return std::system("command -v convert >/dev/null 2>&1") == 0; }

/// PNG of an SVG with ImageMagick; false when the conversion fails (the SVG stays). Without the date and time chunks
/// (ImageMagick writes the SVG's file times into them), so the same figure is the same bytes.
bool convertToPng(const std::string& svg, const std::string& png) {
  const std::string cmd = "convert -background white -define png:exclude-chunks=date,time " + shellQuoted(svg) + " " +
                          shellQuoted(png) + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0 && fs::exists(png);
}

}  // namespace

std::vector<std::string> writeDatasetFigures(const jrl::Dataset& dataset, const std::string& jrl_path,
                                             const std::string& out_dir, bool png) {
  const fs::path jrl(jrl_path);
  const fs::path dir = out_dir.empty() ? jrl.parent_path() : fs::path(out_dir);
  if (!dir.empty()) fs::create_directories(dir);
  const std::string stem = (dir / jrl.stem()).string();
  FigureOptions options;
  options.source = jrl.filename().string();
  std::vector<std::pair<std::string, std::string>> figures{
      {stem + ".trajectories.svg", trajectoriesSvg(dataset, options)}, {stem + ".frontend.svg", frontendSvg(dataset)}};
  const std::string connectivity = comm::datasetConnectivityPath(jrl_path);
  if (fs::exists(connectivity))
    figures.emplace_back(stem + ".connectivity.svg",
                         connectivitySvg(comm::Connectivity::read(connectivity), jrl.stem().string()));
  std::vector<std::string> written;
  const bool with_png = png && converterInstalled();
  for (const auto& [path, text] : figures) {
    writeText(path, text);
    written.push_back(path);
    const std::string png_path = path.substr(0, path.size() - 4) + ".png";
    if (with_png && convertToPng(path, png_path)) written.push_back(png_path);
  }
  return written;
}

std::string writeFiguresBesideJrl(const jrl::Dataset& dataset, const std::string& jrl_path) {
  try {
    std::string line = "figures:";
    const auto written = writeDatasetFigures(dataset, jrl_path);
    for (std::size_t i = 0; i < written.size(); ++i) {
      const bool png_of_previous = i > 0 && fs::path(written[i]).extension() == ".png";
      line += png_of_previous ? "/.png" : (i ? ", " : " ") + written[i];
    }
    return line;
  } catch (const std::exception& e) { return std::string("figures not written: ") + e.what(); }
}

}  // namespace cosmo::report
