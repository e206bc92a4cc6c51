// cosmo_generate: the offline driver's command line. Its options are a pipeline::GenerateRequest
// (pipeline/generate.hpp, where the policy is: the sequence resolved, the noise models, one TeamRun per comm model
// fed and written); this program parses them, runs pipeline::generate and prints what a person reads: the
// pre-flight report, the sequence, progress lines, each dataset's statistics, validation and inlier solve, its
// figures (written beside the JRL), and wall time, CPU and peak memory.
//
//   cosmo_generate SEQUENCE.yaml [--data-root DIR] [--comm wifi,proradio] [--seed N] [--out DIR] [--config-dir DIR]
//                  [--noise-models FILE] [--outlier-rule fidelity|squared] [--odometry loam|reference]
//                  [--registration-threads N] [--max-seconds S] [--gate-threshold X] [--no-check] [--quiet]
//                  [--estimate-noise-models TRIAL [--noise-models-out FILE] [--estimate-only] [--good-translation M]
//                  [--good-rotation RAD]]
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <string>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/comm/connectivity.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/pipeline/generate.hpp"
#include "cosmo/report/figures.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

namespace {

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

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, GenerateRequest& r) {
  CommandLine app("cosmo_generate",
                  "Runs a sequence's robots through the front-end and the radio and writes the team's dataset per "
                  "comm model: <out>/<name>_<comm>.jrl with its stats, metadata, transfer log and figures.");
  addGenerateOptions(app, r);
  if (const auto code = app.parseOrExit(argc, argv)) return code;
  if (r.comms.empty()) {
    std::cerr << "cosmo_generate: --comm: no comm model given\nRun with --help for more information.\n";
    return 2;
  }
  return std::nullopt;
}

/// What a person reads of a run, as it happens.
class Console {
 public:
  explicit Console(const GenerateRequest& r) : quiet_(r.quiet) {}

  GenerateLog log() {
    GenerateLog log;
    log.preflight = [this](const std::string& report) {
      if (!quiet_) print(report);
    };
    log.resolved = [this](const trials::ResolvedSequence& seq) {
      start_stamp_ = seq.timing.start();
      duration_ = seq.seconds();
    };
    log.line = [](const std::string& text) { print(text); };
    log.run_starts = [this](const std::string& label) { start(label); };
    log.progress = [this](const TeamRun& run, StampNs stamp) { progress(run, stamp); };
    log.written = [this](const TeamRun& run, const GeneratedDataset& d) { written(run, d); };
    log.wall_clock = [this] { return total_.elapsedMs() * 1e-3; };
    return log;
  }

  double wallSeconds() const { return total_.elapsedMs() * 1e-3; }

 private:
  static void print(const std::string& text) {
    std::printf("%s", text.c_str());
    std::fflush(stdout);
  }

  /// About every 5 % of the sequence (at least every 10 s of it).
  void progress(const TeamRun& run, StampNs stamp) {
    const double t = toSeconds(stamp - start_stamp_);
    if (quiet_ || t < next_report_) return;
    const auto& c = run.counts();
    std::printf(
        "[%s] %6.1f / %.1f s  keyframes %zu  loop closures intra %zu (+%zu rejected) inter %zu (+%zu rejected)"
        "  transfers %zu delivered, %zu timed out  (%.1f s wall)\n",
        label_.c_str(), t, duration_, c.keyframes, c.intra_accepted, c.intra_rejected, c.inter_accepted,
        c.inter_rejected, c.transfers_delivered, c.transfers_timed_out, run_wall_.elapsedMs() * 1e-3);
    std::fflush(stdout);
    next_report_ = t + std::max(10.0, duration_ / 20.0);
  }

  /// A comm model's run starts: its clocks.
  void start(const std::string& label) {
    label_ = label;
    run_wall_.restart();
    cpu_before_ = cpuSeconds();
    team_cpu_before_ = cpuSeconds(RUSAGE_THREAD);
    next_report_ = 0.0;
  }

  /// The dataset's summary (statistics, validation, the inlier solve), its figures, and the run's clocks.
  void written(const TeamRun& run, const GeneratedDataset& d) {
    const double wall_s = run_wall_.elapsedMs() * 1e-3;
    const jrl::Dataset dataset = run.recorder().build();
    const auto violations = jrl::validate(dataset);
    std::printf("wrote %s (%zu entries; transfer log %s)\n", d.jrl.c_str(), d.report.entries, d.transfers.c_str());
    std::printf("  connectivity (%s):\n", comm::connectivityPath(d.transfers).c_str());
    for (const std::string& line : run.radio().connectivity().describe()) std::printf("    %s\n", line.c_str());
    const comm::RadioStats& radio = run.radio().stats();
    if (const auto& trace = run.radio().params().trace)
      std::printf("  radio trace %s: %llu connectivity samples from its windows, %llu from phi(d) outside them\n",
                  trace->source().c_str(), static_cast<unsigned long long>(radio.trace_samples),
                  static_cast<unsigned long long>(radio.fallback_samples));
    for (const auto& [r, n] : d.feed.dropped)
      std::fprintf(stderr, "warning: robot %c: %zu scans dropped (stamps not increasing)\n", r, n);
    for (const auto& w : run.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!d.report.labelled) std::printf("  no outlier labels: %s\n", d.report.labels_note.c_str());
    std::printf("%s\n", jrl::formatStats(jrl::computeStats(dataset)).c_str());
    std::printf("  validate: %zu violations\n", violations.size());
    for (std::size_t i = 0; i < violations.size() && i < 10; ++i) std::printf("    %s\n", violations[i].str().c_str());
    std::printf("  %s\n  %s\n", backend::inliersSolveLine(dataset).c_str(),
                report::writeFiguresBesideJrl(dataset, d.jrl).c_str());
    const double cpu = cpuSeconds() - cpu_before_, team_cpu = cpuSeconds(RUSAGE_THREAD) - team_cpu_before_;
    std::printf(
        "  wall %.1f s for %.1f s of sequence (%.2fx real time), CPU %.1f s (%.0f %% of one core; the team's "
        "thread %.1f s",
        wall_s, duration_, duration_ / std::max(wall_s, 1e-9), cpu, 100.0 * cpu / std::max(wall_s, 1e-9), team_cpu);
    if (const frontend::RegistrationPool* pool = run.registrationPool())
      std::printf(", %u registration threads %.1f s", pool->threads(), pool->cpuSeconds());
    std::printf("), peak memory %.0f MB\n", peakRssMb());
    const FeedFigures& f = d.feed;
    if (f.wait_odometry_s + f.team_work_s > 0.0)
      std::printf(
          "  the team's thread: %.1f s waiting for the robots' odometry, %.1f s on the team's work (with "
          "waits for registrations), %.1f s finishing (the last transfers and registrations)\n",
          f.wait_odometry_s, f.team_work_s, f.finish_s);
    std::fflush(stdout);
  }

  bool quiet_;
  bench::Stopwatch total_, run_wall_;
  std::string label_;
  StampNs start_stamp_ = 0;
  double duration_ = 0.0, next_report_ = 0.0, cpu_before_ = 0.0, team_cpu_before_ = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  GenerateRequest request;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, request)) return *exit_code;
  try {
    Console console(request);
    generate(request, console.log());
    if (!request.estimate_only) std::printf("total wall %.1f s\n", console.wallSeconds());
  } catch (const std::exception& e) {
    std::cerr << "cosmo_generate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
