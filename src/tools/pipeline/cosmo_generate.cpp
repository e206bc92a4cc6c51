// cosmo_generate: the offline driver. Runs a sequence config's trials through the same core objects as the ROS
// launch (one RobotFrontend per robot, the RadioSimulator, the DatasetRecorder) in one process, without roscore,
// as fast as the CPU allows, and writes <out>/<name>_<comm>.jrl (+ .recorder.yaml), the transfer log
// <out>/<name>_<comm>_transfers.csv (+ .summary.json), and prints the dataset's Fig. 1 statistics.
//
//   cosmo_generate SEQUENCE.yaml [--data-root DIR] [--comm wifi,proradio] [--seed N] [--out DIR] [--config-dir DIR]
//                  [--noise-models FILE] [--outlier-rule fidelity|squared] [--reference-odometry]
//                  [--registration-threads N] [--max-seconds S] [--gate-threshold X] [--no-check] [--quiet]
//                  [--estimate-noise-models TRIAL [--noise-models-out FILE] [--estimate-only] [--good-translation M]
//                  [--good-rotation RAD]]
//
// Noise models: the ones the sequence names (sequence_noise_models.hpp); none: the run stops and says how to make
// them, or --estimate-noise-models makes them first from that trial run alone (trial_noise_models.hpp) and writes
// them beside the outputs (--noise-models-out elsewhere).
//
// Determinism: the same sequence, seed and parameters give a byte-identical JRL (the team's events in one order,
// randomness from the seed only), whatever the threads: the robots' LOAM and keyframes run ahead on one thread per
// robot (OdometryRunAhead), the loop-closure registrations on --registration-threads threads (RegistrationPool),
// their results are consumed in the single-threaded order. Wall time and peak memory are printed at the end (tool
// only).
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/text_list.hpp"
#include "cosmo/pipeline/gate_threshold.hpp"
#include "cosmo/pipeline/kept_scan.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/pipeline/odometry_run_ahead.hpp"
#include "cosmo/pipeline/seed_streams.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/trials/sequence_metadata.hpp"
#include "cosmo/trials/trial_reference.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/pipeline/sequence_references.hpp"
#include "cosmo/pipeline/trial_noise_models.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/trial_probe.hpp"

namespace fs = std::filesystem;
using namespace cosmo;
using namespace cosmo::pipeline;

namespace {

RadioParams radioFor(const std::string& comm, const std::string& config_dir, std::string& label) {
  if (comm.size() > 5 && comm.substr(comm.size() - 5) == ".yaml") {
    label = fs::path(comm).stem().string();
    return RadioParams::fromConfig(ConfigNode::load(comm));
  }
  if (comm.size() > 4 && comm.substr(comm.size() - 4) == ".csv") {  // a radio trace, Wi-Fi's phi(d) outside it
    label = fs::path(comm).stem().string();
    RadioParams p = radioFor("wifi", config_dir, label);
    label = fs::path(comm).stem().string();
    p.trace = std::make_shared<const RadioTrace>(RadioTrace::read(comm));
    return p;
  }
  label = comm == "pro-radio" || comm == "pro_radio" ? "proradio" : comm;
  const fs::path file = fs::path(config_dir) / "comm" / (label + ".yaml");
  if (fs::exists(file)) return RadioParams::fromConfig(ConfigNode::load(file.string()));
  return RadioParams::byName(label);
}

/// CPU seconds (user + system) of every thread of this process so far.
/// CPU seconds of the process (RUSAGE_SELF) or of the calling thread (RUSAGE_THREAD).
double cpuSeconds(int who = RUSAGE_SELF) {
  struct rusage ru {};
  getrusage(who, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

double peakRssMb() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

void printSigmas(const char* what, const CovarianceEstimate& e) {
  std::printf(
      "  %s: %zu used, %zu over the thresholds; sigmas rx ry rz %.3g %.3g %.3g rad, tx ty tz %.3g %.3g %.3g m\n", what,
      e.used, e.rejected, std::sqrt(e.covariance(0, 0)), std::sqrt(e.covariance(1, 1)), std::sqrt(e.covariance(2, 2)),
      std::sqrt(e.covariance(3, 3)), std::sqrt(e.covariance(4, 4)), std::sqrt(e.covariance(5, 5)));
}

/// --estimate-noise-models: the paper's step on one trial of the sequence, written to `out_path` (default: beside
/// the outputs, estimatedNoiseModelsPath), then read back.
NoiseModels estimateFirst(const SequenceConfig& config, const std::string& which, const TeamRunParams& params,
                          const NoiseModelEstimationParams& estimation, const std::string& out_path) {
  const TrialConfig& trial = findTrial(config, which);
  SequenceConfig alone = config;
  alone.trials = {trial};
  alone.anchor = trial.robot;
  const SequenceTiming timing = ros_glue::synchronizeSequence(alone);
  const Trajectory reference = trials::loadSensorReference(trial, timing.of(trial.robot));
  if (reference.empty())
    throw std::runtime_error(config.path + ": trial " + trial.name + " has no reference: the noise models need one");
  std::printf("noise models: running trial %s (robot %c) alone, %.1f s\n", trial.name.c_str(), trial.robot,
              timing.durationSeconds());
  std::fflush(stdout);
  MergedScanStream stream = ros_glue::openSequenceStream(alone, timing);
  const std::string environment = config.environment.empty() ? fs::path(out_path).stem().string() : config.environment;
  const TrialNoiseModels result = estimateTrialNoiseModels(
      trial.robot, stream, reference, params, deriveSeed(config.seed, "radio"), estimation, trial.name, environment);
  printSigmas("odometry", result.estimate.odometry);
  printSigmas("loop closures", result.estimate.loop_closure);
  std::ostringstream header;
  header << "Noise models of the " << environment << " environment (spec section 6), written by\n"
         << "  cosmo_generate " << config.path << " --estimate-noise-models " << which << "\n"
         << "from trial " << trial.name << " (robot " << trial.robot
         << ") run alone through the front-end: " << result.estimate.odometry.used << " odometry factors, "
         << result.estimate.loop_closure.used << " good loop closures (" << result.estimate.loop_closure.rejected
         << " left out: error >= " << estimation.max_translation_error << " m or >= " << estimation.max_rotation_error
         << " rad).\n"
         << "Q = (1/N) sum r r^T, r = Log(m^-1 * m*), rotation first.";
  fs::create_directories(fs::absolute(out_path).parent_path());
  result.estimate.models.save(out_path, header.str());
  std::printf("noise models: wrote the estimate to %s (this run uses it; other runs of the environment: "
              "--noise-models %s)\n",
              out_path.c_str(), out_path.c_str());
  return NoiseModels::load(out_path);
}

struct Options {
  std::string sequence_path, out_dir = ".", config_dir = defaultConfigDir(), noise_path, rule_name = "fidelity";
  std::string estimate_trial, noise_out, data_root;
  NoiseModelEstimationParams estimation;
  std::vector<std::string> comms{"wifi"};
  bool seed_given = false, reference_odometry = false, quiet = false, serial_odometry = false, skip_check = false;
  bool estimate_only = false;
  unsigned long long seed = 0;
  double max_seconds = 0.0;
  std::optional<double> gate_threshold;
  int registration_threads = -1;  // -1: the default
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  CommandLine app("cosmo_generate",
                  "Runs a sequence's robots through the front-end and the radio and writes the team's dataset per "
                  "comm model: <out>/<name>_<comm>.jrl with its stats, metadata, transfer log and figures.");
  addSequence(app, o.sequence_path, o.data_root);
  app.add_flag("--no-check", o.skip_check,
               "skip the pre-flight check (cosmo_check) that stops a run that would be unlabelled");
  std::string comms = "wifi";
  app.add_option("--comm", comms,
                 "comm models, comma separated (wifi, proradio, a config/comm/*.yaml, or a radio trace .csv replayed "
                 "with Wi-Fi's phi(d) outside its windows); the robots' odometry and keyframes are computed once for "
                 "all of them")
      ->capture_default_str()
      ->type_name("LIST");
  app.add_option("--seed", o.seed, "overrides the sequence config's seed");
  app.add_option("--out", o.out_dir, "output folder")->capture_default_str()->type_name("DIR");
  app.add_option("--config-dir", o.config_dir,
                 "frontend/odometry/place_recognition/registration/comm/noise_models configs (default: the source "
                 "tree's config/)")
      ->type_name("DIR");
  addNoiseModels(app, o.noise_path,
                 "default: the sequence's noise_models, else <config-dir>/noise_models/<environment>.yaml; none: the "
                 "run stops");
  app.add_option("--outlier-rule", o.rule_name, "fidelity or squared")->capture_default_str();
  app.add_option("--estimate-noise-models", o.estimate_trial,
                 "first make the noise models as the paper does: run TRIAL (robot id or trial name) alone through "
                 "the front-end, compare with its reference, keep the good loop closures, write the sample "
                 "covariances, then generate the sequence with them")
      ->type_name("TRIAL");
  app.add_option("--noise-models-out", o.noise_out,
                 "where the estimate goes (default: beside the outputs, <out>/<environment, else the sequence's "
                 "name>.noise_models.yaml)")
      ->type_name("FILE");
  app.add_flag("--estimate-only", o.estimate_only, "with --estimate-noise-models: write the estimate and stop");
  addClosureThresholds(app, "good", o.estimation.max_translation_error, o.estimation.max_rotation_error);
  app.add_flag("--reference-odometry", o.reference_odometry,
               "take odometry from the reference trajectories instead of LOAM");
  app.add_flag("--serial-odometry", o.serial_odometry,
               "everything in the main thread (default: one thread per robot reads its own bag and runs its LOAM "
               "and keyframes ahead of the team; the output is the same byte for byte)");
  app.add_option("--registration-threads", o.registration_threads,
                 "threads running the loop-closure registrations while the team's thread goes on (0: on the team's "
                 "thread; default: the machine's cores; 0 with --serial-odometry); the output is the same byte for "
                 "byte")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-seconds", o.max_seconds, "stop after S seconds of sequence time (quick looks)")
      ->type_name("S");
  double gate = 0.0;
  app.add_option("--gate-threshold", gate,
                 "the registration gate's acceptance threshold (gate: strict, min_structure_overlap: X in [0, 1], on "
                 "top of the sequence's registration: keys; a sweep 0.40-0.70)")
      ->type_name("X");
  app.add_flag("--quiet", o.quiet, "less output: the pre-flight report only when it fails, no progress line");
  if (const auto code = app.parseOrExit(argc, argv)) return code;
  o.comms = splitList(comms);
  o.seed_given = app.count("--seed") > 0;
  if (app.count("--gate-threshold")) o.gate_threshold = gate;
  if (o.comms.empty()) {
    std::cerr << "cosmo_generate: --comm: no comm model given\nRun with --help for more information.\n";
    return 2;
  }
  return std::nullopt;
}

/// The options that change the sequence's config: --seed, --gate-threshold.
void applyConfigOptions(const Options& o, SequenceConfig& config) {
  if (o.seed_given) config.seed = o.seed;
  if (!o.gate_threshold) return;
  try {
    applyGateThreshold(config, *o.gate_threshold);
  } catch (const std::invalid_argument& e) { throw std::runtime_error(std::string("--gate-threshold: ") + e.what()); }
}

/// The options that need each other or a range.
void checkOptions(const Options& o) {
  if (!(o.estimation.max_translation_error > 0) || !(o.estimation.max_rotation_error > 0))
    throw std::runtime_error("--good-translation / --good-rotation: expected positive numbers");
  if (!o.estimate_trial.empty() && !o.noise_path.empty())
    throw std::runtime_error("--estimate-noise-models and --noise-models: give one of them");
  if (o.estimate_only && o.estimate_trial.empty())
    throw std::runtime_error("--estimate-only: give the trial with --estimate-noise-models TRIAL");
}

/// The pre-flight check (cosmo_check): stop before hours of work that give no labels.
void preflightCheck(const SequenceConfig& config, const Options& o) {
  if (o.skip_check) return;
  std::string check;
  const bool ok =
      ros_glue::checkSequence(config,
                              o.estimate_trial.empty() ? chooseNoiseModels(config, o.config_dir, o.noise_path)
                                                       : "estimated first from trial " + o.estimate_trial,
                              check);
  if (!o.quiet || !ok) std::printf("%s", check.c_str());
  if (!ok) throw std::runtime_error("the pre-flight check failed (above); --no-check runs anyway");
}

/// The team's parameters; the noise models are the sequence's, or estimated first (--estimate-noise-models).
TeamRunParams teamRunParams(const SequenceConfig& config, const Options& o) {
  const auto rule = parseOutlierRule(o.rule_name);
  if (!rule) throw std::runtime_error("--outlier-rule: expected fidelity or squared, got '" + o.rule_name + "'");
  checkOptions(o);
  preflightCheck(config, o);
  TeamRunParams params;
  params.frontend = FrontendParams::loadDir(o.config_dir);
  params.frontend.registration = config.registrationParams(o.config_dir);  // the sequence's `registration:` keys
  params.outlier_rule = *rule;
  params.metadata = trials::sequenceMetadata(config);
  params.reference_odometry = o.reference_odometry;
  params.registration_threads = o.registration_threads >= 0 ? static_cast<unsigned>(o.registration_threads)
                                : o.serial_odometry         ? 0u
                                                            : std::max(1u, std::thread::hardware_concurrency());
  std::string first_label;  // the single-trial run of the estimate uses the first comm model (no transfers alone)
  params.radio = radioFor(o.comms.front(), o.config_dir, first_label);
  params.noise = o.estimate_trial.empty()
                     ? loadSequenceNoiseModels(config, o.config_dir, o.noise_path)
                     : estimateFirst(config, o.estimate_trial, params, o.estimation,
                                     o.noise_out.empty() ? estimatedNoiseModelsPath(config, o.out_dir) : o.noise_out);
  return params;
}

void printSequence(const SequenceConfig& config, const SequenceTiming& timing, const TeamRunParams& params) {
  std::printf("sequence %s (%s, seed %llu): %zu trials, %.1f s, noise models %s\n", config.name.c_str(),
              config.source.c_str(), config.seed, config.trials.size(), timing.durationSeconds(),
              params.noise.describe().c_str());
  for (const auto& t : timing.trials())
    std::printf("  robot %c  %-22s starts at +%7.2f s, %7.1f s long (offset %+.3f s)\n", t.robot,
                config.trial(t.robot).name.c_str(), toSeconds(t.start() - timing.start()),
                toSeconds(t.end() - t.start()), static_cast<double>(t.offset_ns) * 1e-9);
}

/// The progress line, about every 5 % of the sequence (at least every 10 s of it).
class ProgressLine {
 public:
  ProgressLine(const TeamRun& run, std::string label, StampNs start, double duration, bool quiet,
               const bench::Stopwatch& wall)
      : run_(run), label_(std::move(label)), start_(start), duration_(duration), quiet_(quiet), wall_(wall) {}

  void operator()(StampNs stamp) {
    const double t = toSeconds(stamp - start_);
    if (quiet_ || t < next_report_) return;
    const auto& c = run_.counts();
    std::printf(
        "[%s] %6.1f / %.1f s  keyframes %zu  loop closures intra %zu (+%zu rejected) inter %zu (+%zu rejected)"
        "  transfers %zu delivered, %zu timed out  (%.1f s wall)\n",
        label_.c_str(), t, duration_, c.keyframes, c.intra_accepted, c.intra_rejected, c.inter_accepted,
        c.inter_rejected, c.transfers_delivered, c.transfers_timed_out, wall_.elapsedMs() * 1e-3);
    std::fflush(stdout);
    next_report_ = t + std::max(10.0, duration_ / 20.0);
  }

 private:
  const TeamRun& run_;
  std::string label_;
  StampNs start_;
  double duration_, next_report_ = 0.0;
  bool quiet_;
  const bench::Stopwatch& wall_;
};

/// The robots' own results (odometry, keyframe scans) do not depend on the comm model: with several models they
/// are computed once and replayed for the others. Their keyframe scans wait in a spill file (KeptScan), not in
/// memory.
struct ComputedScans {
  std::vector<AheadScan> scans;
  std::vector<std::shared_ptr<const KeptScan>> keyframes;  // one per keyframe of `scans`, in order
  std::shared_ptr<SpillFile> spill;
  std::map<char, std::size_t> dropped;
  bool ready = false;

  void keep(const AheadScan& s) {
    scans.push_back(s);
    if (!s.keyframe_scan) return;
    keyframes.push_back(std::make_shared<const KeptScan>(s.keyframe_scan, spill));
    scans.back().keyframe_scan = std::make_shared<const Scan>();  // a marker: the scan is kept above
  }
};

/// How a run fed the team: scans dropped per robot, and where the team's thread spent its time (run-ahead path).
struct FeedFigures {
  std::map<char, std::size_t> dropped;
  double wait_odometry_s = 0.0, team_work_s = 0.0, finish_s = 0.0;
};

/// The team's scans of `computed` again.
FeedFigures replayComputed(TeamRun& run, const ComputedScans& computed, ProgressLine& progress) {
  std::size_t next_keyframe = 0;
  for (const AheadScan& s : computed.scans) {
    run.addPrepared(s.robot, s.stamp, s.odometry,
                    s.keyframe_scan ? computed.keyframes.at(next_keyframe++)->get() : nullptr);
    progress(s.stamp);
  }
  FeedFigures f;
  f.dropped = computed.dropped;
  return f;
}

/// The robots' own work (LOAM, keyframes) on worker threads; this thread runs the team. `computed`: kept for the
/// other comm models when given.
FeedFigures runAhead(TeamRun& run, const SequenceConfig& config, const SequenceTiming& timing,
                     const TeamRunParams& params, const std::map<char, Trajectory>& references, StampNs end,
                     ComputedScans* computed, ProgressLine& progress) {
  FeedFigures f;
  OdometryRunAhead ahead(ros_glue::openTrialSources(config), timing, params.frontend, references);
  AheadScan s;
  for (;;) {
    bench::Stopwatch waited;
    const bool more = ahead.next(s);
    f.wait_odometry_s += waited.elapsedMs() * 1e-3;
    if (!more || s.stamp > end) break;
    if (computed) computed->keep(s);
    bench::Stopwatch worked;
    run.addPrepared(s.robot, s.stamp, s.odometry, std::move(s.keyframe_scan));
    f.team_work_s += worked.elapsedMs() * 1e-3;
    progress(s.stamp);
  }
  ahead.stop();  // the workers may have run past --max-seconds
  f.dropped = ahead.dropped();
  if (computed) {
    computed->dropped = f.dropped;
    computed->ready = true;
  }
  return f;
}

/// Everything in this thread, scan by scan in the team's order.
FeedFigures runSerial(TeamRun& run, const SequenceConfig& config, const SequenceTiming& timing, StampNs end,
                      ProgressLine& progress) {
  MergedScanStream stream = ros_glue::openSequenceStream(config, timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) {
    if (scan.stamp > end) break;
    run.addScan(robot, scan);
    progress(scan.stamp);
  }
  FeedFigures f;
  f.dropped = stream.dropped();
  return f;
}

/// What a run wrote: the JRL and the transfer log.
struct Written {
  fs::path jrl, csv;
  BuildReport report;
};

Written writeOutputs(const TeamRun& run, const fs::path& out_dir, const std::string& name) {
  Written w;
  w.jrl = out_dir / (name + ".jrl");
  w.report = run.recorder().write(w.jrl.string());
  w.csv = out_dir / (name + "_transfers.csv");
  writeTransferLog(w.csv.string(), run.radio());
  return w;
}

/// The dataset's summary on stdout (statistics, validation, the inlier solve) and the figures beside the JRL.
void printDataset(const TeamRun& run, const Written& w) {
  const fs::path& jrl = w.jrl;
  const BuildReport& report = w.report;
  const fs::path& csv = w.csv;
  const jrl::Dataset dataset = run.recorder().build();
  const auto violations = jrl::validate(dataset);
  std::printf("wrote %s (%zu entries; transfer log %s)\n", jrl.string().c_str(), report.entries, csv.string().c_str());
  const RadioStats& radio = run.radio().stats();
  if (const auto& trace = run.radio().params().trace)
    std::printf("  radio trace %s: %llu connectivity samples from its windows, %llu from phi(d) outside them\n",
                trace->source().c_str(), static_cast<unsigned long long>(radio.trace_samples),
                static_cast<unsigned long long>(radio.fallback_samples));
  if (!report.labelled) std::printf("  no outlier labels: %s\n", report.labels_note.c_str());
  std::printf("%s\n", jrl::formatStats(jrl::computeStats(dataset)).c_str());
  std::printf("  validate: %zu violations\n", violations.size());
  for (std::size_t i = 0; i < violations.size() && i < 10; ++i) std::printf("    %s\n", violations[i].str().c_str());
  std::printf("  %s\n  %s\n", backend::inliersSolveLine(dataset).c_str(),
              report::writeFiguresBesideJrl(dataset, jrl.string()).c_str());
}

/// Wall time, CPU (the process, the team's thread, the registration threads) and peak memory of one run.
struct RunClock {
  bench::Stopwatch wall;
  double cpu_before = cpuSeconds(), team_cpu_before = cpuSeconds(RUSAGE_THREAD);

  void print(const TeamRun& run, double wall_s, double duration, const FeedFigures& f) const {
    const double cpu = cpuSeconds() - cpu_before, team_cpu = cpuSeconds(RUSAGE_THREAD) - team_cpu_before;
    std::printf(
        "  wall %.1f s for %.1f s of sequence (%.2fx real time), CPU %.1f s (%.0f %% of one core; the team's "
        "thread %.1f s",
        wall_s, duration, duration / std::max(wall_s, 1e-9), cpu, 100.0 * cpu / std::max(wall_s, 1e-9), team_cpu);
    if (const RegistrationPool* pool = run.registrationPool())
      std::printf(", %u registration threads %.1f s", pool->threads(), pool->cpuSeconds());
    std::printf("), peak memory %.0f MB\n", peakRssMb());
    if (f.wait_odometry_s + f.team_work_s > 0.0)
      std::printf(
          "  the team's thread: %.1f s waiting for the robots' odometry, %.1f s on the team's work (with "
          "waits for registrations), %.1f s finishing (the last transfers and registrations)\n",
          f.wait_odometry_s, f.team_work_s, f.finish_s);
  }
};

/// The sequence as every comm model's run sees it.
struct Sequence {
  SequenceConfig config;
  SequenceTiming timing;
  std::map<char, Trajectory> references;
  StampNs end = 0;  ///< the sequence end, or --max-seconds after its start
};

/// One comm model's run: the team fed with the robots' scans (computed, or replayed from `computed`), finished
/// at the end, its outputs written.
void runComm(const std::string& comm, const Sequence& seq, TeamRunParams params, const Options& o,
             ComputedScans& computed) {
  std::string label;
  params.radio = radioFor(comm, o.config_dir, label);
  const StampNs origin = radioGridOrigin(seq.timing.start(), params.radio.step);
  const RunClock clock;
  TeamRun run(seq.config.name + "_" + label, seq.references, params, deriveSeed(seq.config.seed, "radio"), origin);
  const double duration = toSeconds(seq.end - seq.timing.start());
  ProgressLine progress(run, label, seq.timing.start(), duration, o.quiet, clock.wall);
  FeedFigures f;
  if (computed.ready)
    f = replayComputed(run, computed, progress);
  else if (!o.reference_odometry && !o.serial_odometry)
    f = runAhead(run, seq.config, seq.timing, params, seq.references, seq.end, o.comms.size() > 1 ? &computed : nullptr,
                 progress);
  else
    f = runSerial(run, seq.config, seq.timing, seq.end, progress);
  bench::Stopwatch finishing;
  run.finish(seq.end);
  f.finish_s = finishing.elapsedMs() * 1e-3;
  for (const auto& [r, n] : f.dropped)
    std::fprintf(stderr, "warning: robot %c: %zu scans dropped (stamps not increasing)\n", r, n);
  for (const auto& w : run.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const Written written = writeOutputs(run, o.out_dir, seq.config.name + "_" + label);
  const double wall = clock.wall.elapsedMs() * 1e-3;
  printDataset(run, written);
  clock.print(run, wall, duration, f);
}

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  Options o;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    bench::Stopwatch total;
    Sequence seq;
    seq.config = SequenceConfig::load(o.sequence_path, o.data_root);
    applyConfigOptions(o, seq.config);
    const TeamRunParams params = teamRunParams(seq.config, o);
    if (o.estimate_only) return 0;
    fs::create_directories(o.out_dir);
    seq.timing = ros_glue::synchronizeSequence(seq.config);
    printSequence(seq.config, seq.timing, params);
    seq.references = trials::loadSequenceReferences(seq.config, seq.timing);
    seq.end = o.max_seconds > 0 ? std::min(seq.timing.end(), seq.timing.start() + toStampNs(o.max_seconds))
                                : seq.timing.end();
    ComputedScans computed;
    computed.spill = params.frontend.spill_keyframes ? std::make_shared<SpillFile>(params.frontend.spill_dir) : nullptr;
    for (const std::string& comm : o.comms) runComm(comm, seq, params, o, computed);
    std::printf("total wall %.1f s\n", total.elapsedMs() * 1e-3);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_generate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
