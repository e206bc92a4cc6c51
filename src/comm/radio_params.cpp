#include "cosmo/comm/radio_params.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/common/param_list.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace cosmo::comm {

double RadioParams::phi(double d) const {
  const double p = std::min(p_max, alpha * (std::pow(beta, d / r_max) - beta));
  return std::max(0.0, p);
}

void RadioParams::validate(const std::string& where) const {
  auto require = [&](bool ok, const char* field, const char* rule) {
    if (!ok) throw std::runtime_error(where + ": " + field + " must be " + rule);
  };
  require(std::isfinite(bandwidth_kBps) && bandwidth_kBps > 0, "bandwidth_kBps", "> 0");
  require(std::isfinite(d_init) && d_init >= 0, "d_init", ">= 0");
  require(std::isfinite(d_intf) && d_intf >= 0, "d_intf", ">= 0");
  require(std::isfinite(p_max) && p_max >= 0 && p_max <= 1, "p_max", "in [0, 1]");
  require(std::isfinite(alpha), "alpha", "finite");
  require(std::isfinite(beta) && beta > 0, "beta", "> 0");
  require(std::isfinite(r_max) && r_max > 0, "r_max", "> 0");
  require(std::isfinite(step) && step > 0, "step", "> 0");
  require(std::isfinite(timeout) && timeout > 0, "timeout", "> 0");
  require(std::isfinite(size_factor_mean) && size_factor_mean > 0, "size_factor_mean", "> 0");
  require(std::isfinite(size_factor_stddev) && size_factor_stddev >= 0, "size_factor_stddev", ">= 0");
}

RadioParams RadioParams::wifi() { return RadioParams{}; }

RadioParams RadioParams::proRadio() {
  RadioParams p;
  p.bandwidth_kBps = 1000.0;
  p.d_init = 150.0;
  p.d_intf = 150.0;
  p.p_max = 0.8;
  p.alpha = 1.8;
  p.beta = 0.3;
  p.r_max = 200.0;
  return p;
}

RadioParams RadioParams::byName(const std::string& name) {
  if (name == "wifi" || name == "wi-fi" || name == "WiFi") return wifi();
  if (name == "proradio" || name == "pro-radio" || name == "pro_radio" || name == "ProRadio") return proRadio();
  throw std::runtime_error("unknown communication model '" + name + "' (expected wifi or proradio)");
}

std::string toString(RadioParams::TimeoutMode mode) {
  return mode == RadioParams::TimeoutMode::NoProgress ? "no_progress" : "total_duration";
}

std::string toString(RadioParams::SizeModel model) {
  return model == RadioParams::SizeModel::PaperFactor ? "paper" : "real";
}

RadioParams::TimeoutMode timeoutModeFromString(const std::string& s, const std::string& where) {
  if (s == "no_progress") return RadioParams::TimeoutMode::NoProgress;
  if (s == "total_duration") return RadioParams::TimeoutMode::TotalDuration;
  throw std::runtime_error(where + ": unknown timeout mode '" + s + "' (expected no_progress or total_duration)");
}

RadioParams::SizeModel sizeModelFromString(const std::string& s, const std::string& where) {
  if (s == "paper") return RadioParams::SizeModel::PaperFactor;
  if (s == "real") return RadioParams::SizeModel::RealCompressed;
  throw std::runtime_error(where + ": unknown size model '" + s + "' (expected paper or real)");
}

RadioParams RadioParams::fromConfig(const ConfigNode& root) {
  const ConfigNode node = root.has("comm") ? root["comm"] : root;
  std::string preset = "wifi";
  node.read("preset", preset);
  RadioParams p;
  try {
    p = byName(preset);
  } catch (const std::runtime_error& e) { throw std::runtime_error(node["preset"].where + ": " + e.what()); }
  readParams(node, p, {"preset", "timeout_mode", "size_model", "trace"});
  if (node.has("timeout_mode")) {
    std::string s;
    node.read("timeout_mode", s);
    p.timeout_mode = timeoutModeFromString(s, node["timeout_mode"].where);
  }
  if (node.has("size_model")) {
    std::string s;
    node.read("size_model", s);
    p.size_model = sizeModelFromString(s, node["size_model"].where);
  }
  if (node.has("trace")) {
    std::string file;
    node.read("trace", file);
    std::filesystem::path path(file);
    if (path.is_relative() && !node.file.empty()) path = std::filesystem::path(node.file).parent_path() / path;
    p.trace = std::make_shared<const RadioTrace>(RadioTrace::read(path.string()));
  }
  p.validate(node.where.empty() ? "RadioParams" : node.where);
  return p;
}

}  // namespace cosmo::comm
