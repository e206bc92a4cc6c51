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
#include "cosmo/common/text_list.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/pipeline/trial_noise_models.hpp"
#include "cosmo/sequence/gate_threshold.hpp"
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

std::string sigmas(const char* what, const CovarianceEstimate& e) {
  return format("  %s: %zu used, %zu over the thresholds; sigmas rx ry rz %.3g %.3g %.3g rad, tx ty tz %.3g %.3g %.3g "
                "m\n",
                what, e.used, e.rejected, std::sqrt(e.covariance(0, 0)), std::sqrt(e.covariance(1, 1)),
                std::sqrt(e.covariance(2, 2)), std::sqrt(e.covariance(3, 3)), std::sqrt(e.covariance(4, 4)),
                std::sqrt(e.covariance(5, 5)));
}

/// The paper's step on one trial of the sequence, written to `out_path`, then read back.
NoiseModels estimateFirst(const sequence::SequenceConfig& config, const GenerateRequest& r, const TeamRunParams& params,
                          const std::string& out_path, const GenerateLog& log) {
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
         << " left out: error >= " << r.estimation.max_translation_error << " m or >= "
         << r.estimation.max_rotation_error << " rad).\n"
         << "Q = (1/N) sum r r^T, r = Log(m^-1 * m*), rotation first.";
  fs::create_directories(fs::absolute(out_path).parent_path());
  result.estimate.models.save(out_path, header.str());
  say(log, format("noise models: wrote the estimate to %s (this run uses it; other runs of the environment: "
                  "--noise-models %s)\n",
                  out_path.c_str(), out_path.c_str()));
  return NoiseModels::load(out_path);
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
    trials::ResolvedSequence seq = trials::resolveSequence(sequenceChoice(r));
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
  params.frontend = FrontendParams::loadDir(configDir(r));
  params.frontend.registration = config.registrationParams(configDir(r));  // the sequence's `registration:` keys
  params.frontend.odometry = parseOdometryKind(r.odometry);
  params.outlier_rule = *parseOutlierRule(r.outlier_rule);
  params.metadata = trials::sequenceMetadata(config);
  params.registration_threads = r.registration_threads ? *r.registration_threads
                                : r.serial_odometry    ? 0u
                                                       : std::max(1u, std::thread::hardware_concurrency());
  return params;
}

std::string sequenceLines(const trials::ResolvedSequence& seq, const NoiseModels& noise) {
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
  const CommModel model = resolveCommModel(comm, configDir(r));
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

void GenerateRequest::validate() const {
  if (comms.empty()) throw std::runtime_error("--comm: no comm model given");
  if (!parseOutlierRule(outlier_rule))
    throw std::runtime_error("--outlier-rule: expected fidelity or squared, got '" + outlier_rule + "'");
  if (odometry != "loam" && odometry != "reference")
    throw std::runtime_error("--odometry: expected loam or reference, got '" + odometry + "'");
  if (!(estimation.max_translation_error > 0) || !(estimation.max_rotation_error > 0))
    throw std::runtime_error("--good-translation / --good-rotation: expected positive numbers");
  if (!estimate_trial.empty() && !noise_models.empty())
    throw std::runtime_error("--estimate-noise-models and --noise-models: give one of them");
  if (estimate_only && estimate_trial.empty())
    throw std::runtime_error("--estimate-only: give the trial with --estimate-noise-models TRIAL");
  if (gate_threshold) {
    try {
      sequence::gateThresholdKeys(*gate_threshold);
    } catch (const std::invalid_argument& e) { throw std::runtime_error(std::string("--gate-threshold: ") + e.what()); }
  }
}

GenerateResult generate(const GenerateRequest& r, const GenerateLog& log) {
  r.validate();
  GenerateResult result;
  result.sequence = resolve(r, log);
  const trials::ResolvedSequence& seq = result.sequence;
  if (log.resolved) log.resolved(seq);
  TeamRunParams params = teamRunParams(r, seq.config);
  // the single-trial run of the estimate uses the first comm model (no transfers alone)
  params.radio = resolveCommModel(r.comms.front(), configDir(r)).params;
  params.noise = seq.noise ? *seq.noise
                           : estimateFirst(seq.config, r, params,
                                           r.noise_models_out.empty()
                                               ? sequence::estimatedNoiseModelsPath(seq.config, r.out_dir)
                                               : r.noise_models_out,
                                           log);
  result.noise = params.noise;
  if (r.estimate_only) return result;
  fs::create_directories(r.out_dir);
  say(log, sequenceLines(seq, params.noise));
  ComputedScans computed(params.frontend.spill_keyframes ? std::make_shared<SpillFile>(params.frontend.spill_dir)
                                                         : nullptr);
  for (const std::string& comm : r.comms) result.datasets.push_back(runComm(comm, r, seq, params, computed, log));
  return result;
}

void addGenerateOptions(CLI::App& app, GenerateRequest& r) {
  addSequence(app, r.sequence, r.data_root);
  app.add_flag_callback("--no-check", [&r] { r.check = false; },
                        "skip the pre-flight check (cosmo_check) that stops a run that would be unlabelled");
  app.add_option_function<std::string>(
         "--comm", [&r](const std::string& list) { r.comms = splitList(list); },
         "comm models, comma separated (wifi, proradio, a config/comm/*.yaml, or a radio trace .csv replayed "
         "with Wi-Fi's phi(d) outside its windows); the robots' odometry and keyframes are computed once for "
         "all of them (default: wifi)")
      ->type_name("LIST");
  app.add_option_function<unsigned long long>(
      "--seed", [&r](unsigned long long seed) { r.seed = seed; }, "overrides the sequence config's seed");
  app.add_option("--out", r.out_dir, "output folder")->capture_default_str()->type_name("DIR");
  app.add_option("--config-dir", r.config_dir,
                 "frontend/odometry/place_recognition/registration/comm/noise_models configs (default: the source "
                 "tree's config/)")
      ->type_name("DIR");
  addNoiseModels(app, r.noise_models,
                 "default: the sequence's noise_models, else <config-dir>/noise_models/<environment>.yaml; none: the "
                 "run stops");
  app.add_option("--outlier-rule", r.outlier_rule, "fidelity or squared")->capture_default_str();
  app.add_option("--estimate-noise-models", r.estimate_trial,
                 "first make the noise models as the paper does: run TRIAL (robot id or trial name) alone through "
                 "the front-end, compare with its reference, keep the good loop closures, write the sample "
                 "covariances, then generate the sequence with them")
      ->type_name("TRIAL");
  app.add_option("--noise-models-out", r.noise_models_out,
                 "where the estimate goes (default: beside the outputs, <out>/<environment, else the sequence's "
                 "name>.noise_models.yaml)")
      ->type_name("FILE");
  app.add_flag("--estimate-only", r.estimate_only, "with --estimate-noise-models: write the estimate and stop");
  addClosureThresholds(app, "good", r.estimation.max_translation_error, r.estimation.max_rotation_error);
  app.add_option("--odometry", r.odometry,
                 "loam, or reference: each robot's odometry from its reference trajectory (held at its ends; robots "
                 "without one use LOAM)")
      ->capture_default_str()
      ->check(CLI::IsMember({"loam", "reference"}));
  app.add_flag_callback("--reference-odometry", [&r] { r.odometry = "reference"; }, "the same as --odometry reference")
      ->group("");
  app.add_flag("--serial-odometry", r.serial_odometry,
               "everything in the main thread (default: one thread per robot reads its own bag and runs its LOAM "
               "and keyframes ahead of the team; the output is the same byte for byte)");
  app.add_option_function<unsigned>(
         "--registration-threads", [&r](unsigned n) { r.registration_threads = n; },
         "threads running the loop-closure registrations while the team's thread goes on (0: on the team's "
         "thread; default: the machine's cores; 0 with --serial-odometry); the output is the same byte for byte")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-seconds", r.max_seconds, "stop after S seconds of sequence time (quick looks)")
      ->type_name("S");
  app.add_option_function<double>(
         "--gate-threshold", [&r](double x) { r.gate_threshold = x; },
         "the registration gate's acceptance threshold (gate: strict, min_structure_overlap: X in [0, 1], on top of "
         "the sequence's registration: keys; a sweep 0.40-0.70)")
      ->type_name("X");
  app.add_flag("--quiet", r.quiet, "less output: the pre-flight report only when it fails, no progress line");
}

std::vector<std::string> generateArgs(const GenerateRequest& r) {
  const GenerateRequest d;
  std::vector<std::string> a{r.sequence};
  const auto number = [](double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  if (!r.data_root.empty()) a.insert(a.end(), {"--data-root", r.data_root});
  if (r.comms != d.comms) {
    std::string list;
    for (const auto& c : r.comms) list += (list.empty() ? "" : ",") + c;
    a.insert(a.end(), {"--comm", list});
  }
  if (r.seed) a.insert(a.end(), {"--seed", std::to_string(*r.seed)});
  if (r.max_seconds > 0) a.insert(a.end(), {"--max-seconds", number(r.max_seconds)});
  if (r.odometry != d.odometry) a.insert(a.end(), {"--odometry", r.odometry});
  if (r.gate_threshold) a.insert(a.end(), {"--gate-threshold", number(*r.gate_threshold)});
  if (!r.config_dir.empty()) a.insert(a.end(), {"--config-dir", r.config_dir});
  if (!r.noise_models.empty()) a.insert(a.end(), {"--noise-models", r.noise_models});
  if (r.outlier_rule != d.outlier_rule) a.insert(a.end(), {"--outlier-rule", r.outlier_rule});
  if (!r.estimate_trial.empty()) a.insert(a.end(), {"--estimate-noise-models", r.estimate_trial});
  if (!r.noise_models_out.empty()) a.insert(a.end(), {"--noise-models-out", r.noise_models_out});
  if (r.estimate_only) a.push_back("--estimate-only");
  if (r.estimation.max_translation_error != d.estimation.max_translation_error)
    a.insert(a.end(), {"--good-translation", number(r.estimation.max_translation_error)});
  if (r.estimation.max_rotation_error != d.estimation.max_rotation_error)
    a.insert(a.end(), {"--good-rotation", number(r.estimation.max_rotation_error)});
  if (r.serial_odometry) a.push_back("--serial-odometry");
  if (r.registration_threads) a.insert(a.end(), {"--registration-threads", std::to_string(*r.registration_threads)});
  if (!r.check) a.push_back("--no-check");
  if (r.out_dir != d.out_dir) a.insert(a.end(), {"--out", r.out_dir});
  if (r.quiet) a.push_back("--quiet");
  return a;
}

}  // namespace cosmo::pipeline
