#pragma once
// Parameters of the simulated radio (spec section 5, paper Fig. "Model Hyperparameters"): one shared channel of
// bandwidth B, connectivity probability phi(d) = min(P_max, alpha (beta^(d / r_max) - beta)) clamped at 0,
// initialization within d_init, interference within d_intf, step delta and timeout T.
#include <memory>
#include <string>

#include "cosmo/common/config.hpp"

namespace cosmo::comm {

class RadioTrace;

struct RadioParams {
  /// Channel bandwidth B in kB/s (1 kB = 1000 bytes).
  double bandwidth_kBps = 2000.0;
  /// Two available robots closer than this (m) try to start a communication.
  double d_init = 30.0;
  /// Another active communication with an endpoint within this distance (m) of either endpoint interferes.
  double d_intf = 40.0;
  /// Connectivity model phi(d) = min(p_max, alpha (beta^(d / r_max) - beta)), clamped at 0.
  double p_max = 0.7;
  double alpha = 1.1;
  double beta = 0.1;
  double r_max = 70.0;
  /// Simulation step delta (s).
  double step = 0.1;
  /// Timeout T (s) of a stale communication; see timeout_mode.
  double timeout = 2.0;

  /// NoProgress (default): a communication fails when no byte got through for `timeout` seconds (a link that
  /// keeps making progress, however slowly, is not stale). TotalDuration: it fails when it has lasted
  /// `timeout` seconds in total.
  enum class TimeoutMode { NoProgress, TotalDuration } timeout_mode = TimeoutMode::NoProgress;

  /// PaperFactor (default, the paper's model): payload = f * S with S = 12 bytes per point and
  /// f ~ N(0.653, 0.04) drawn once per keyframe from the seed. RealCompressed: payload = the size liblzma
  /// actually produced for the scan.
  enum class SizeModel { PaperFactor, RealCompressed } size_model = SizeModel::PaperFactor;
  /// Mean and standard deviation of the paper's compression factor f.
  double size_factor_mean = 0.653;
  double size_factor_stddev = 0.04;

  /// Comm model `trace`: a radio trace replayed instead of phi(d) inside its windows (comm/link_model.hpp); the
  /// values above still hold outside them. Null: the distance model alone. Config key `trace: FILE` (relative to
  /// the config file's folder).
  std::shared_ptr<const RadioTrace> trace;

  /// Connectivity probability at distance d (m).
  double phi(double d) const;
  /// Bandwidth in bytes per second.
  double bandwidthBps() const { return bandwidth_kBps * 1000.0; }

  /// Throws std::runtime_error naming the field when a value is out of range.
  void validate(const std::string& where = "RadioParams") const;

  /// Reads a config/comm/*.yaml file (keys at the root or under `comm:`); a missing key keeps the Wi-Fi
  /// value, unless `preset: proradio` picks the Pro-Radio values as the base; `trace: FILE` reads that trace.
  static RadioParams fromConfig(const ConfigNode& node);
  /// The paper's Wi-Fi model (B 2000 kB/s, d_init 30 m, d_intf 40 m, P_max 0.7, alpha 1.1, beta 0.1, r_max 70 m).
  static RadioParams wifi();
  /// The paper's Pro-Radio model (B 1000 kB/s, d_init 150 m, d_intf 150 m, P_max 0.8, alpha 1.8, beta 0.3,
  /// r_max 200 m).
  static RadioParams proRadio();
  /// "wifi" or "proradio" (also "pro-radio", "pro_radio"); throws std::invalid_argument otherwise.
  static RadioParams byName(const std::string& name);

  /// The YAML keys, one per member (common/param_list.hpp); `preset`, `timeout_mode`, `size_model` and `trace` are
  /// read by fromConfig.
  template <class Visitor>
  void visit(Visitor&& v) {
    v("bandwidth_kBps", bandwidth_kBps);
    v("d_init", d_init);
    v("d_intf", d_intf);
    v("p_max", p_max);
    v("alpha", alpha);
    v("beta", beta);
    v("r_max", r_max);
    v("step", step);
    v("timeout", timeout);
    v("size_factor_mean", size_factor_mean);
    v("size_factor_stddev", size_factor_stddev);
  }
};

std::string toString(RadioParams::TimeoutMode mode);
std::string toString(RadioParams::SizeModel model);
/// "no_progress" | "total_duration"; throws std::invalid_argument naming `where` otherwise.
RadioParams::TimeoutMode timeoutModeFromString(const std::string& s, const std::string& where = "timeout_mode");
/// "paper" | "real"; throws std::invalid_argument naming `where` otherwise.
RadioParams::SizeModel sizeModelFromString(const std::string& s, const std::string& where = "size_model");

}  // namespace cosmo::comm
