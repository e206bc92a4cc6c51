// cosmo_generate: the offline driver. Runs a sequence config's trials through the same core objects as the ROS
// launch (one RobotFrontend per robot, the RadioSimulator, the DatasetRecorder) in one process, without roscore,
// as fast as the CPU allows, and writes <out>/<name>_<comm>.jrl (+ .recorder.yaml), the transfer log
// <out>/<name>_<comm>_transfers.csv (+ .summary.json), and prints the dataset's Fig. 1 statistics.
//
//   cosmo_generate SEQUENCE.yaml [--data-root DIR] [--comm wifi,proradio] [--seed N] [--out DIR] [--config-dir DIR]
//                  [--noise-models FILE] [--outlier-rule fidelity|squared] [--reference-odometry]
//                  [--registration-threads N] [--max-seconds S] [--no-check] [--quiet]
//                  [--estimate-noise-models TRIAL [--noise-models-out FILE] [--good-translation M] [--good-rotation RAD]]
//
// Noise models: the ones the sequence names (sequence_noise_models.hpp); none: the run stops and says how to make
// them, or --estimate-noise-models makes them first from that trial run alone (trial_noise_models.hpp).
//
// Determinism: the same sequence, seed and parameters give a byte-identical JRL (the team's events in one order,
// randomness from the seed only), whatever the threads: the robots' LOAM and keyframes run ahead on one thread per
// robot (OdometryRunAhead), the loop-closure registrations on --registration-threads threads (RegistrationPool),
// their results are consumed in the single-threaded order. Wall time and peak memory are printed at the end (tool only).
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/pipeline/kept_scan.hpp"
#include "cosmo/bench/stopwatch.hpp"
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

void usage() {
  std::cerr << "usage: cosmo_generate SEQUENCE.yaml [--data-root DIR] [--comm wifi,proradio] [--seed N] [--out DIR]\n"
               "         [--config-dir DIR] [--noise-models FILE] [--outlier-rule fidelity|squared]\n"
               "         [--reference-odometry] [--serial-odometry] [--registration-threads N] [--max-seconds S] [--no-check] [--quiet]\n"
               "  --data-root DIR      the folder the trials' bags and references are below (default: the config's\n"
               "                       data_root key, else $COSMO_DATA_ROOT, else the config's folder)\n"
               "  --no-check           skip the pre-flight check (cosmo_check) that stops a run that would be unlabelled\n"
               "  --comm LIST          comm models, comma separated (wifi, proradio, or a config/comm/*.yaml); default wifi.\n"
               "                       The robots' odometry and keyframes are computed once for all of them\n"
               "  --seed N             overrides the sequence config's seed\n"
               "  --out DIR            output folder (default: current folder)\n"
               "  --config-dir DIR     frontend/odometry/place_recognition/registration/comm/noise_models configs\n"
               "                       (default: the source tree's config/)\n"
               "  --noise-models FILE  noise-model YAML (default: the sequence's noise_models, else\n"
               "                       <config-dir>/noise_models/<environment>.yaml; none: the run stops)\n"
               "  --estimate-noise-models TRIAL  first make the noise models as the paper does: run TRIAL (robot id or\n"
               "                       trial name) alone through the front-end, compare with its reference, keep the\n"
               "                       good loop closures, write the sample covariances, then generate the sequence\n"
               "                       with them\n"
               "  --noise-models-out FILE  where the estimate goes (default: the sequence's noise-model file, when it\n"
               "                       does not exist or says its models are unknown)\n"
               "  --good-translation M, --good-rotation RAD  good loop closures for the estimate: errors under\n"
               "                       these (default 0.5 m, 0.05 rad)\n"
               "  --reference-odometry take odometry from the reference trajectories instead of LOAM\n"
               "  --serial-odometry    everything in the main thread (default: one thread per robot reads its own bag and\n"
               "                       runs its LOAM and keyframes ahead of the team; the output is the same byte\n"
               "                       for byte)\n"
               "  --registration-threads N  threads running the loop-closure registrations while the team's thread goes\n"
               "                       on (0: on the team's thread; default: the machine's cores; 0 with --serial-odometry);\n"
               "                       the output is the same byte for byte\n"
               "  --max-seconds S      stop after S seconds of sequence time (quick looks)\n";
}

std::vector<std::string> splitComma(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

RadioParams radioFor(const std::string& comm, const std::string& config_dir, std::string& label) {
  if (comm.size() > 5 && comm.substr(comm.size() - 5) == ".yaml") {
    label = fs::path(comm).stem().string();
    return RadioParams::fromConfig(ConfigNode::load(comm));
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
  std::printf("  %s: %zu used, %zu over the thresholds; sigmas rx ry rz %.3g %.3g %.3g rad, tx ty tz %.3g %.3g %.3g m\n",
              what, e.used, e.rejected, std::sqrt(e.covariance(0, 0)), std::sqrt(e.covariance(1, 1)),
              std::sqrt(e.covariance(2, 2)), std::sqrt(e.covariance(3, 3)), std::sqrt(e.covariance(4, 4)),
              std::sqrt(e.covariance(5, 5)));
}

/// --estimate-noise-models: the paper's step on one trial of the sequence, written to `out_path` (default: the
/// sequence's own noise-model file, which must not hold known models), then read back.
NoiseModels estimateFirst(const SequenceConfig& config, const std::string& which, const TeamRunParams& params,
                          const NoiseModelEstimationParams& estimation, std::string out_path,
                          const std::string& config_dir) {
  const TrialConfig& trial = findTrial(config, which);
  if (out_path.empty()) {
    out_path = sequenceNoiseModelsPath(config, config_dir);
    if (fs::exists(out_path)) {
      bool unknown = false;
      try {
        NoiseModels::load(out_path);
      } catch (const NoiseModelsUnknown&) {
        unknown = true;
      }
      if (!unknown)
        throw std::runtime_error(out_path + " already holds noise models: pass --noise-models-out FILE to write the "
                                 "estimate elsewhere (or leave out --estimate-noise-models to use them)");
    }
  }
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
  const TrialNoiseModels result = estimateTrialNoiseModels(trial.robot, stream, reference, params,
                                                           deriveSeed(config.seed, "radio"), estimation,
                                                           trial.name, environment);
  printSigmas("odometry", result.estimate.odometry);
  printSigmas("loop closures", result.estimate.loop_closure);
  std::ostringstream header;
  header << "Noise models of the " << environment << " environment (spec section 6), written by\n"
         << "  cosmo_generate " << config.path << " --estimate-noise-models " << which << "\n"
         << "from trial " << trial.name << " (robot " << trial.robot << ") run alone through the front-end: "
         << result.estimate.odometry.used << " odometry factors, " << result.estimate.loop_closure.used
         << " good loop closures (" << result.estimate.loop_closure.rejected << " left out: error >= "
         << estimation.max_translation_error << " m or >= " << estimation.max_rotation_error << " rad).\n"
         << "Q = (1/N) sum r r^T, r = Log(m^-1 * m*), rotation first.";
  result.estimate.models.save(out_path, header.str());
  std::printf("wrote %s\n", out_path.c_str());
  return NoiseModels::load(out_path);
}

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  std::string sequence_path, out_dir = ".", config_dir = defaultConfigDir(), noise_path, rule_name = "fidelity";
  std::string estimate_trial, noise_out;
  NoiseModelEstimationParams estimation;
  std::vector<std::string> comms{"wifi"};
  bool seed_given = false, reference_odometry = false, quiet = false, serial_odometry = false, skip_check = false;
  std::string data_root;
  unsigned long long seed = 0;
  double max_seconds = 0.0;
  int registration_threads = -1;  // -1: the default
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        usage();
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (a == "--comm") comms = splitComma(value());
      else if (a == "--seed") { seed = std::stoull(value()); seed_given = true; }
      else if (a == "--out") out_dir = value();
      else if (a == "--config-dir") config_dir = value();
      else if (a == "--data-root") data_root = value();
      else if (a == "--no-check") skip_check = true;
      else if (a == "--noise-models") noise_path = value();
      else if (a == "--outlier-rule") rule_name = value();
      else if (a == "--estimate-noise-models") estimate_trial = value();
      else if (a == "--noise-models-out") noise_out = value();
      else if (a == "--good-translation") estimation.max_translation_error = std::stod(value());
      else if (a == "--good-rotation") estimation.max_rotation_error = std::stod(value());
      else if (a == "--reference-odometry") reference_odometry = true;
      else if (a == "--serial-odometry") serial_odometry = true;
      else if (a == "--registration-threads") registration_threads = std::stoi(value());
      else if (a == "--max-seconds") max_seconds = std::stod(value());
      else if (a == "--quiet") quiet = true;
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] == '-') { std::cerr << "unknown option " << a << "\n"; usage(); return 2; }
      else if (sequence_path.empty()) sequence_path = a;
      else { std::cerr << "unexpected argument " << a << "\n"; usage(); return 2; }
    } catch (const std::exception&) {
      std::cerr << "bad value for " << a << "\n";
      return 2;
    }
  }
  if (sequence_path.empty() || comms.empty()) {
    usage();
    return 2;
  }
  try {
    bench::Stopwatch total;
    SequenceConfig config = SequenceConfig::load(sequence_path, data_root);
    if (seed_given) config.seed = seed;
    const auto rule = parseOutlierRule(rule_name);
    if (!rule) throw std::runtime_error("--outlier-rule: expected fidelity or squared, got '" + rule_name + "'");
    if (!(estimation.max_translation_error > 0) || !(estimation.max_rotation_error > 0))
      throw std::runtime_error("--good-translation / --good-rotation: expected positive numbers");
    if (!estimate_trial.empty() && !noise_path.empty())
      throw std::runtime_error("--estimate-noise-models and --noise-models: give one of them");
    if (!skip_check) {  // the pre-flight check (cosmo_check): stop before hours of work that give no labels
      std::string check;
      const bool ok = ros_glue::checkSequence(
          config, estimate_trial.empty() ? chooseNoiseModels(config, config_dir, noise_path)
                                         : "estimated first from trial " + estimate_trial, check);
      if (!quiet || !ok) std::printf("%s", check.c_str());
      if (!ok) throw std::runtime_error("the pre-flight check failed (above); --no-check runs anyway");
    }
    TeamRunParams params;
    params.frontend = FrontendParams::loadDir(config_dir);
    params.outlier_rule = *rule;
    params.metadata = trials::sequenceMetadata(config);
    params.reference_odometry = reference_odometry;
    params.registration_threads = registration_threads >= 0 ? static_cast<unsigned>(registration_threads)
                                  : serial_odometry           ? 0u
                                                              : std::max(1u, std::thread::hardware_concurrency());
    std::string first_label;  // the single-trial run of the estimate uses the first comm model (no transfers alone)
    params.radio = radioFor(comms.front(), config_dir, first_label);
    params.noise = estimate_trial.empty()
                       ? loadSequenceNoiseModels(config, config_dir, noise_path)
                       : estimateFirst(config, estimate_trial, params, estimation, noise_out, config_dir);
    fs::create_directories(out_dir);

    const SequenceTiming timing = ros_glue::synchronizeSequence(config);
    std::printf("sequence %s (%s, seed %llu): %zu trials, %.1f s, noise models %s\n", config.name.c_str(),
                config.source.c_str(), config.seed, config.trials.size(), timing.durationSeconds(),
                params.noise.describe().c_str());
    for (const auto& t : timing.trials())
      std::printf("  robot %c  %-22s starts at +%7.2f s, %7.1f s long (offset %+.3f s)\n", t.robot,
                  config.trial(t.robot).name.c_str(), toSeconds(t.start() - timing.start()),
                  toSeconds(t.end() - t.start()), static_cast<double>(t.offset_ns) * 1e-9);
    const std::map<char, Trajectory> references = trials::loadSequenceReferences(config, timing);

    // Radio steps on the absolute grid k * delta (as the comm_broker node does on ROS time).
    const StampNs end = max_seconds > 0 ? std::min(timing.end(), timing.start() + toStampNs(max_seconds)) : timing.end();
    // The robots' own results (odometry, keyframe scans) do not depend on the comm model: with several models they
    // are computed once and replayed for the others.
    // Their keyframe scans wait in a spill file (KeptScan), not in memory.
    std::vector<AheadScan> computed;
    std::vector<std::shared_ptr<const KeptScan>> computed_keyframes;  // one per keyframe of `computed`, in order
    const auto computed_spill = params.frontend.spill_keyframes
                                    ? std::make_shared<SpillFile>(params.frontend.spill_dir) : nullptr;
    std::map<char, std::size_t> computed_dropped;
    bool replay = false;
    for (const std::string& comm : comms) {
      std::string label;
      params.radio = radioFor(comm, config_dir, label);
      const StampNs origin = radioGridOrigin(timing.start(), params.radio.step);
      bench::Stopwatch sw;
      const double cpu_before = cpuSeconds(), team_cpu_before = cpuSeconds(RUSAGE_THREAD);
      TeamRun run(config.name + "_" + label, references, params, deriveSeed(config.seed, "radio"), origin);
      double next_report = 0.0;
      const double duration = toSeconds(end - timing.start());
      auto progress = [&](StampNs stamp) {
        const double t = toSeconds(stamp - timing.start());
        if (quiet || t < next_report) return;
        const auto& c = run.counts();
        std::printf("[%s] %6.1f / %.1f s  keyframes %zu  loop closures intra %zu (+%zu rejected) inter %zu (+%zu rejected)"
                    "  transfers %zu delivered, %zu timed out  (%.1f s wall)\n",
                    label.c_str(), t, duration, c.keyframes, c.intra_accepted, c.intra_rejected, c.inter_accepted,
                    c.inter_rejected, c.transfers_delivered, c.transfers_timed_out, sw.elapsedMs() * 1e-3);
        std::fflush(stdout);
        next_report = t + std::max(10.0, duration / 20.0);
      };
      std::map<char, std::size_t> dropped;
      double wait_odometry_s = 0.0, team_work_s = 0.0;  // the team thread's wall time (run-ahead path)
      if (replay) {
        std::size_t next_keyframe = 0;
        for (const AheadScan& s : computed) {
          run.addPrepared(s.robot, s.stamp, s.odometry,
                          s.keyframe_scan ? computed_keyframes.at(next_keyframe++)->get() : nullptr);
          progress(s.stamp);
        }
        dropped = computed_dropped;
      } else if (!reference_odometry && !serial_odometry) {
        // The robots' own work (LOAM, keyframes) on worker threads; this thread runs the team.
        const bool keep = comms.size() > 1;
        OdometryRunAhead ahead(ros_glue::openTrialSources(config), timing, params.frontend, references);
        AheadScan s;
        for (;;) {
          bench::Stopwatch waited;
          const bool more = ahead.next(s);
          wait_odometry_s += waited.elapsedMs() * 1e-3;
          if (!more || s.stamp > end) break;
          if (keep) {
            computed.push_back(s);
            if (s.keyframe_scan) {
              computed_keyframes.push_back(std::make_shared<const KeptScan>(s.keyframe_scan, computed_spill));
              computed.back().keyframe_scan = std::make_shared<const Scan>();  // a marker: the scan is kept above
            }
          }
          bench::Stopwatch worked;
          run.addPrepared(s.robot, s.stamp, s.odometry, std::move(s.keyframe_scan));
          team_work_s += worked.elapsedMs() * 1e-3;
          progress(s.stamp);
        }
        ahead.stop();  // the workers may have run past --max-seconds
        dropped = ahead.dropped();
        computed_dropped = dropped;
        replay = keep;
      } else {
        MergedScanStream stream = ros_glue::openSequenceStream(config, timing);
        char robot;
        Scan scan;
        while (stream.next(robot, scan)) {
          if (scan.stamp > end) break;
          run.addScan(robot, scan);
          progress(scan.stamp);
        }
        dropped = stream.dropped();
      }
      bench::Stopwatch finishing;
      run.finish(end);
      const double finish_s = finishing.elapsedMs() * 1e-3;
      for (const auto& [r, n] : dropped)
        std::fprintf(stderr, "warning: robot %c: %zu scans dropped (stamps not increasing)\n", r, n);
      for (const auto& w : run.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());

      const fs::path jrl = fs::path(out_dir) / (config.name + "_" + label + ".jrl");
      const BuildReport report = run.recorder().write(jrl.string());
      const fs::path csv = fs::path(out_dir) / (config.name + "_" + label + "_transfers.csv");
      writeTransferLog(csv.string(), run.radio().transferLog(), run.radio().stats(), run.radio().params());
      const double wall = sw.elapsedMs() * 1e-3;
      const jrl::Dataset dataset = run.recorder().build();
      const auto violations = jrl::validate(dataset);
      std::printf("wrote %s (%zu entries; transfer log %s)\n", jrl.string().c_str(), report.entries, csv.string().c_str());
      if (!report.labelled) std::printf("  no outlier labels: %s\n", report.labels_note.c_str());
      std::printf("%s\n", jrl::formatStats(jrl::computeStats(dataset)).c_str());
      std::printf("  validate: %zu violations\n", violations.size());
      for (std::size_t i = 0; i < violations.size() && i < 10; ++i)
        std::printf("    %s\n", violations[i].str().c_str());
      std::printf("  %s\n  %s\n", backend::inliersSolveLine(dataset).c_str(),
                  report::writeFiguresBesideJrl(dataset, jrl.string()).c_str());
      const double cpu = cpuSeconds() - cpu_before, team_cpu = cpuSeconds(RUSAGE_THREAD) - team_cpu_before;
      std::printf("  wall %.1f s for %.1f s of sequence (%.2fx real time), CPU %.1f s (%.0f %% of one core; the team's "
                  "thread %.1f s", wall, duration, duration / std::max(wall, 1e-9), cpu,
                  100.0 * cpu / std::max(wall, 1e-9), team_cpu);
      if (const RegistrationPool* pool = run.registrationPool())
        std::printf(", %u registration threads %.1f s", pool->threads(), pool->cpuSeconds());
      std::printf("), peak memory %.0f MB\n", peakRssMb());
      if (wait_odometry_s + team_work_s > 0.0)
        std::printf("  the team's thread: %.1f s waiting for the robots' odometry, %.1f s on the team's work (with "
                    "waits for registrations), %.1f s finishing (the last transfers and registrations)\n",
                    wait_odometry_s, team_work_s, finish_s);
    }
    std::printf("total wall %.1f s\n", total.elapsedMs() * 1e-3);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_generate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
