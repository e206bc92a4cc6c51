#include "cosmo/trials/reference_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cosmo/common/pose_io.hpp"

namespace cosmo::trials {

namespace {

bool isNumber(const std::string& token) {
  if (token.empty()) return false;
  try {
    std::size_t used = 0;
    std::stod(token, &used);
    return used == token.size();
  } catch (const std::exception&) { return false; }
}

std::vector<std::string> split(const std::string& line, bool commas) {
  std::vector<std::string> out;
  if (commas) {
    std::stringstream ss(line);
    std::string tok;
    while (std::getline(ss, tok, ',')) {
      const auto a = tok.find_first_not_of(" \t\r"), b = tok.find_last_not_of(" \t\r");
      out.push_back(a == std::string::npos ? "" : tok.substr(a, b - a + 1));
    }
  } else {
    std::istringstream ss(line);
    std::string tok;
    while (ss >> tok) out.push_back(tok);
  }
  return out;
}

bool allNumbers(const std::vector<std::string>& tokens) {
  for (const auto& t : tokens)
    if (!isNumber(t)) return false;
  return !tokens.empty();
}

[[noreturn]] void noFormat(const std::string& path, int line, const std::string& text) {
  throw std::runtime_error(path + ":" + std::to_string(line) +
                           ": not a reference trajectory (expected MCD pose_inW.csv `num,t,x,y,z,qx,qy,qz,qw`, "
                           "CU-Multi `timestamp,x,y,z,qx,qy,qz,qw` CSV, TUM `t x y z qx qy qz qw` or KITTI 12 "
                           "numbers per line); the line reads: " +
                           text.substr(0, 80));
}

}  // namespace

std::string referenceFormatName(ReferenceFormat format) {
  switch (format) {
    case ReferenceFormat::McdPoseCsv: return "MCD pose_inW.csv";
    case ReferenceFormat::CuMultiCsv: return "CU-Multi ground-truth CSV";
    case ReferenceFormat::Tum: return "TUM";
    case ReferenceFormat::Kitti: return "KITTI";
  }
  return "?";
}

ReferenceFormat detectReferenceFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the reference file");
  std::string line;
  bool comments = false;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (line[0] == '#') {
      comments = true;
      continue;
    }
    const bool commas = line.find(',') != std::string::npos;
    const auto tokens = split(line, commas);
    if (commas && !allNumbers(tokens)) {  // a header line
      if (tokens.size() == 9 && tokens[0] == "num") return ReferenceFormat::McdPoseCsv;
      if (tokens.size() == 8 && (tokens[0] == "timestamp" || tokens[0] == "t" || tokens[0] == "time"))
        return ReferenceFormat::CuMultiCsv;
      noFormat(path, n, line);
    }
    if (!allNumbers(tokens)) noFormat(path, n, line);
    if (commas && tokens.size() == 9 && !comments) return ReferenceFormat::McdPoseCsv;
    if (commas && tokens.size() == 8) return ReferenceFormat::CuMultiCsv;
    if (!commas && tokens.size() == 8) return ReferenceFormat::Tum;
    if (!commas && tokens.size() == 12 && !comments) return ReferenceFormat::Kitti;
    noFormat(path, n, line);
  }
  throw std::runtime_error(path + ": empty reference file (no poses)");
}

Trajectory readReference(const std::string& path) {
  switch (detectReferenceFormat(path)) {
    case ReferenceFormat::McdPoseCsv: return readMcdPoseCsv(path);
    case ReferenceFormat::CuMultiCsv: return readCuMultiGroundTruth(path);
    case ReferenceFormat::Tum: {
      Trajectory t = readTumTrajectory(path);
      if (t.empty()) throw std::runtime_error(path + ": no poses");
      return t;
    }
    case ReferenceFormat::Kitti: return readKittiReference(path);
  }
  throw std::logic_error("readReference: unknown format");
}

}  // namespace cosmo::trials
