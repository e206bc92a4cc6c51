#include "cosmo/pipeline/generate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "cosmo/comm/comm_model.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/common/config_dir.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/pipeline/trial_noise_models.hpp"
#include "cosmo/sequence/seed_streams.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/sequence_metadata.hpp"
#include "cosmo/trials/trial_reference.hpp"

namespace fs = std::filesystem;

namespace cosmo::pipeline {

namespace {

std::string configDir(const GenerateRequest& r) { return r.config_dir.empty() ? defaultConfigDir() : r.config_dir; }

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buf[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

void say(const GenerateLog& log, const std::string& text) {
  if (log.line) log.line(text);
}

std::string sigmas(const char* what, const dataset::CovarianceEstimate& e) {
  return format(
      "  %s: %zu used, %zu over the thresholds; sigmas rx ry rz %.3g %.3g %.3g rad, tx ty tz %.3g %.3g %.3g "
      "m\n",
      what, e.used, e.rejected, std::sqrt(e.covariance(0, 0)), std::sqrt(e.covariance(1, 1)),
      std::sqrt(e.covariance(2, 2)), std::sqrt(e.covariance(3, 3)), std::sqrt(e.covariance(4, 4)),
      std::sqrt(e.covariance(5, 5)));
}

/// The paper's step on one trial of the sequence, written to `out_path`, then read back.
dataset::NoiseModels estimateFirst(const sequence::SequenceConfig& config, const GenerateRequest& r,
                                   const TeamRunParams& params, const std::string& out_path, const GenerateLog& log) {
  const sequence::TrialConfig& trial = sequence::findTrial(config, r.estimate_trial);
  sequence::SequenceConfig alone = config;
  alone.trials = {trial};
  alone.anchor = trial.robot;
  const sequence::SequenceTiming timing = trials::synchronizeSequence(alone);
  const Trajectory reference = trials::loadSensorReference(trial, timing.of(trial.robot));
  if (reference.empty())
    throw std::runtime_error(config.path + ": trial " + trial.name + " has no reference: the noise models need one");
  say(log, format("noise models: running trial %s (robot %c) alone, %.1f s\n", trial.name.c_str(), trial.robot,
                  timing.durationSeconds()));
  sequence::MergedScanStream stream = trials::openSequenceStream(alone, timing);
  const std::string environment = config.environment.empty() ? fs::path(out_path).stem().string() : config.environment;
  const TrialNoiseModels result =
      estimateTrialNoiseModels(trial.robot, stream, reference, params, sequence::deriveSeed(config.seed, "radio"),
                               r.estimation, trial.name, environment);
  say(log, sigmas("odometry", result.estimate.odometry));
  say(log, sigmas("loop closures", result.estimate.loop_closure));
  std::ostringstream header;
  header << "Noise models of the " << environment << " environment (spec section 6), written by\n"
         << "  cosmo_generate " << config.path << " --estimate-noise-models " << r.estimate_trial << "\n"
         << "from trial " << trial.name << " (robot " << trial.robot
         << ") run alone through the front-end: " << result.estimate.odometry.used << " odometry factors, "
         << result.estimate.loop_closure.used << " good loop closures (" << result.estimate.loop_closure.rejected
         << " left out: error >= " << r.estimation.max_translation_error
         << " m or >= " << r.estimation.max_rotation_error << " rad).\n"
         << "Q = (1/N) sum r r^T, r = Log(m^-1 * m*), rotation first.";
  fs::create_directories(fs::absolute(out_path).parent_path());
  result.estimate.models.save(out_path, header.str());
  say(log, format("noise models: wrote the estimate to %s (this run uses it; other runs of the environment: "
                  "--noise-models %s)\n",
                  out_path.c_str(), out_path.c_str()));
  return dataset::NoiseModels::load(out_path);
}

trials::SequenceChoice sequenceChoice(const GenerateRequest& r) {
  trials::SequenceChoice c;
  c.sequence = r.sequence;
  c.data_root = r.data_root;
  c.config_dir = configDir(r);
  c.noise_models = r.noise_models;
  c.estimate_trial = r.estimate_trial;
  c.seed = r.seed;
  c.gate_threshold = r.gate_threshold;
  c.max_seconds = r.max_seconds;
  c.check = r.check;
  return c;
}

trials::ResolvedSequence resolve(const GenerateRequest& r, const GenerateLog& log) {
  try {
    trials::ResolvedSequence seq = trials::resolveSequence(sequenceChoice(r), trials::readTrialBases,
                                                           [&](const std::string& text) { say(log, text + "\n"); });
    if (log.preflight && !seq.check_report.empty()) log.preflight(seq.check_report);
    return seq;
  } catch (const trials::PreflightFailed& failed) {
    say(log, failed.report);
    throw std::runtime_error("the pre-flight check failed (above); --no-check runs anyway");
  }
}

/// The team's parameters but the radio (per comm model) and the noise models.
TeamRunParams teamRunParams(const GenerateRequest& r, const sequence::SequenceConfig& config) {
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(configDir(r));
  params.frontend.registration = config.registrationParams(configDir(r));  // the sequence's `registration:` keys
  params.frontend.odometry = frontend::parseOdometryKind(r.odometry);
  params.outlier_rule = *dataset::parseOutlierRule(r.outlier_rule);
  params.metadata = trials::sequenceMetadata(config);
  params.registration_threads = r.registration_threads ? *r.registration_threads
                                : r.serial_odometry    ? 0u
                                                       : std::max(1u, std::thread::hardware_concurrency());
  return params;
}

std::string sequenceLines(const trials::ResolvedSequence& seq, const dataset::NoiseModels& noise) {
  const sequence::SequenceConfig& config = seq.config;
  std::string out = format("sequence %s (%s, seed %llu): %zu trials, %.1f s, noise models %s\n", config.name.c_str(),
                           config.source.c_str(), config.seed, config.trials.size(), seq.timing.durationSeconds(),
                           noise.describe().c_str());
  for (const auto& t : seq.timing.trials())
    out += format("  robot %c  %-22s starts at +%7.2f s, %7.1f s long (offset %+.3f s)\n", t.robot,
                  config.trial(t.robot).name.c_str(), toSeconds(t.start() - seq.timing.start()),
                  toSeconds(t.end() - t.start()), static_cast<double>(t.offset_ns) * 1e-9);
  return out;
}

/// One comm model's run: the team fed, finished at the end, its dataset and transfer log written.
GeneratedDataset runComm(const std::string& comm, const GenerateRequest& r, const trials::ResolvedSequence& seq,
                         TeamRunParams params, ComputedScans& computed, const GenerateLog& log) {
  const comm::CommModel model = comm::resolveCommModel(comm, configDir(r));
  if (log.run_starts) log.run_starts(model.label);
  params.radio = model.params;
  const StampNs origin = radioGridOrigin(seq.timing.start(), params.radio.step);
  TeamRun run(seq.config.name + "_" + model.label, seq.references, params,
              sequence::deriveSeed(seq.config.seed, "radio"), origin);
  FeedPlan plan;
  plan.config = &seq.config;
  plan.timing = &seq.timing;
  plan.references = &seq.references;
  plan.end = seq.end;
  plan.sources = [&seq] { return trials::openTrialSources(seq.config); };
  plan.serial = r.serial_odometry;
  plan.computed = r.comms.size() > 1 ? &computed : nullptr;
  if (log.progress) plan.progress = [&](StampNs stamp) { log.progress(run, stamp); };
  plan.wall_clock = log.wall_clock;
  GeneratedDataset d;
  d.label = model.label;
  d.feed = feed(run, plan);
  const fs::path base = fs::path(r.out_dir) / (seq.config.name + "_" + model.label);
  d.jrl = base.string() + ".jrl";
  d.report = run.recorder().write(d.jrl);
  d.transfers = base.string() + "_transfers.csv";
  writeTransferLog(d.transfers, run.radio());
  if (log.written) log.written(run, d);
  return d;
}

}  // namespace

GenerateResult generate(const GenerateRequest& r, const GenerateLog& log) {
  r.validate();
  GenerateResult result;
  result.sequence = resolve(r, log);
  const trials::ResolvedSequence& seq = result.sequence;
  if (log.resolved) log.resolved(seq);
  TeamRunParams params = teamRunParams(r, seq.config);
  // the single-trial run of the estimate uses the first comm model (no transfers alone)
  params.radio = comm::resolveCommModel(r.comms.front(), configDir(r)).params;
  params.noise =
      seq.noise ? *seq.noise
                : estimateFirst(seq.config, r, params,
                                r.noise_models_out.empty() ? sequence::estimatedNoiseModelsPath(seq.config, r.out_dir)
                                                           : r.noise_models_out,
                                log);
  result.noise = params.noise;
  if (r.estimate_only) return result;
  fs::create_directories(r.out_dir);
  say(log, sequenceLines(seq, params.noise));
  ComputedScans computed(
      params.frontend.spill_keyframes ? std::make_shared<frontend::SpillFile>(params.frontend.spill_dir) : nullptr);
  for (const std::string& comm : r.comms) result.datasets.push_back(runComm(comm, r, seq, params, computed, log));
  return result;
}

}  // namespace cosmo::pipeline
