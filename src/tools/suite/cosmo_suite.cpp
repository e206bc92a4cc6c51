// cosmo_suite: the whole benchmark in one command, on one machine or a Slurm cluster, resumable (docs/suite.md).
//
//   cosmo_suite SUITE.yaml --out DIR [--data-root DIR] [--jobs N] [--cores N] [--slurm [SBATCH OPTIONS] [--wait]]
//   cosmo_suite status [SUITE.yaml] --out DIR [--data-root DIR]
//   cosmo_suite job --plan PLAN (--job ID | --list FILE --index I) --run RUN   (one job: local runs, Slurm tasks)
//   cosmo_suite report --plan PLAN --run RUN                                   (the report of a Slurm run)
//
// The logic is in the suite module (cosmo/suite/); this file reads the options and prints.
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/suite/local_run.hpp"
#include "cosmo/suite/out_dir.hpp"
#include "cosmo/suite/plan.hpp"
#include "cosmo/suite/run_job.hpp"
#include "cosmo/suite/simulate.hpp"
#include "cosmo/suite/slurm.hpp"
#include "cosmo/suite/status.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;
using namespace cosmo::suite;

namespace {

struct Options {
  std::string suite, out, data_root, slurm, plan, job, list, run;
  bool slurm_given = false, wait = false, dry_run = false;
  unsigned jobs = 0, cores = 0, threads = 0;
  int index = -1;
};

fs::path selfExe() { return fs::read_symlink("/proc/self/exe"); }

std::string runId() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%SZ", std::gmtime(&t));
  return std::string(buf) + "-" + std::to_string(::getpid());
}

std::unique_ptr<PaperTable> paperTable() {
  const fs::path p = fs::path(cosmo::defaultConfigDir()) / "paper" / "fig1.yaml";
  if (!fs::exists(p)) return nullptr;
  return std::make_unique<PaperTable>(PaperTable::load(p.string()));
}

Plan makePlan(const Options& o, const SuiteFile& suite) {
  PlanOptions po;
  po.out_dir = fs::absolute(o.out).lexically_normal().string();
  if (!o.data_root.empty()) po.data_root = fs::absolute(o.data_root).lexically_normal().string();
  po.program_dir = selfExe().parent_path().string();
  po.default_config_dir = cosmo::defaultConfigDir();
  po.simulate = simulateWith(po.program_dir, suiteDir(po.out_dir, "logs"));
  return planSuite(suite, po);
}

/// Writes the plan for the job processes: .suite/plans/<run>.json, and .suite/plan.json (the latest).
std::string savePlan(const Plan& plan, const std::string& run) {
  const std::string path = suiteDir(plan.out_dir, "plans") + "/" + run + ".json";
  cosmo::dataset::writeFileAtomically(path, plan.toJson());
  cosmo::dataset::writeFileAtomically(suiteDir(plan.out_dir) + "/plan.json", plan.toJson());
  return path;
}

void finishReport(const Plan& plan, const JobStatuses& statuses, const std::string& note, bool print) {
  writeManifest(plan);
  const auto paper = paperTable();
  const ReportInput input = reportInput(plan, statuses, paper.get(), note);
  for (const auto& p : writeReport(input))
    if (print) std::cout << "wrote " << p << "\n";
  if (print) std::cout << "\n" << reportTableHead(input, 8) << std::flush;
}

bool anyFailed(const JobStatuses& statuses) {
  for (const auto& [id, s] : statuses)
    if (s.rfind("failed", 0) == 0 || s.rfind("not run", 0) == 0) return true;
  return false;
}

int runSuite(const Options& o) {
  const SuiteFile suite = SuiteFile::load(o.suite);  // a bad file stops here, before anything is made
  fs::create_directories(o.out);
  const auto lock = lockOutDir(fs::absolute(o.out).string(), "cosmo_suite " + o.suite);
  const Plan plan = makePlan(o, suite);
  const std::string run = runId();
  const std::string plan_path = savePlan(plan, run);
  std::cout << "suite " << plan.suite_name << ": " << plan.jobs.size() << " jobs -> " << plan.out_dir << " (run "
            << run << ")" << std::endl;
  if (o.dry_run) {
    for (const auto& [id, s] : surveyJobs(plan)) std::cout << "  " << id << ": " << s << "\n";
    return 0;
  }
  if (o.slurm_given) {
    const auto survey = surveyJobs(plan);
    const std::vector<std::string> todo = jobsToRun(plan, survey);
    for (const auto& job : plan.jobs) {
      const bool runs = std::find(todo.begin(), todo.end(), job.id) != todo.end();
      std::cout << "  " << job.id << ": " << survey.at(job.id) << (runs ? " -> submitted" : " -> skipped") << "\n";
    }
    if (todo.empty()) {
      finishReport(plan, folderStatuses(plan, run), "Every job was current.", true);
      return 0;
    }
    SlurmOptions so{splitShellWords(o.slurm), selfExe().string(), plan_path, run, 0};
    const SlurmSubmission sub = submitToSlurm(plan, todo, so);
    for (const auto& a : sub.arrays)
      std::cout << "submitted " << a.name << ": Slurm job " << a.slurm_id << " (" << a.jobs.size() << " tasks)\n";
    std::cout << "submitted the report: Slurm job " << sub.report_job << "\n"
              << "follow it with: cosmo_suite status --out " << plan.out_dir << std::endl;
    if (!o.wait) return 0;
    while (!slurmQueue(sub).empty()) std::this_thread::sleep_for(std::chrono::seconds(2));
    const JobStatuses statuses = folderStatuses(plan, run);
    std::cout << statusCounts(plan, statuses) << "\n";
    finishReport(plan, statuses, statusCounts(plan, statuses) + " (Slurm run " + run + ").", true);
    return anyFailed(statuses) ? 1 : 0;
  }
  LocalRunOptions lo;
  lo.policy = SlotPolicy{o.cores ? o.cores : std::max(1u, std::thread::hardware_concurrency()), o.jobs};
  lo.run_id = run;
  lo.self_exe = selfExe().string();
  lo.plan_path = plan_path;
  const JobStatuses statuses = runLocal(plan, lo, std::cout);
  const std::string counts = statusCounts(plan, statuses);
  std::cout << counts << "\n";
  finishReport(plan, statuses, counts + " (run " + run + ").", true);
  return anyFailed(statuses) ? 1 : 0;
}

int status(const Options& o) {
  const std::string out = fs::absolute(o.out).lexically_normal().string();
  const Plan plan = o.suite.empty() ? Plan::fromJson(cosmo::readWholeFile(out + "/.suite/plan.json"), out + "/.suite/plan.json")
                                    : makePlan(o, SuiteFile::load(o.suite));
  const JobStatuses statuses = folderStatuses(plan, "");
  for (const auto& job : plan.jobs) std::cout << job.id << ": " << statuses.at(job.id) << "\n";
  std::cout << statusCounts(plan, statuses) << "\n";
  return 0;
}

int job(const Options& o) {
  const Plan plan = Plan::fromJson(cosmo::readWholeFile(o.plan), o.plan);
  std::string id = o.job;
  if (id.empty()) {
    std::istringstream list(cosmo::readWholeFile(o.list));
    for (int i = 0; i <= o.index && std::getline(list, id); ++i) {
    }
  }
  unsigned threads = o.threads;
  if (threads == 0) {
    const char* cpus = std::getenv("SLURM_CPUS_PER_TASK");
    threads = registrationThreads(plan.job(id).robots, cpus ? static_cast<unsigned>(std::atoi(cpus)) : 1u);
  }
  const JobOutcome r = runJob(plan, id, RunJobOptions{threads, o.run});
  if (r == JobOutcome::Failed) std::cerr << "cosmo_suite job " << id << ": " << readFailure(plan.out_dir, id) << "\n";
  return r == JobOutcome::Done ? kExitDone : r == JobOutcome::Current ? kExitCurrent : kExitFailed;
}

int report(const Options& o) {
  const Plan plan = Plan::fromJson(cosmo::readWholeFile(o.plan), o.plan);
  const JobStatuses statuses = folderStatuses(plan, o.run);
  finishReport(plan, statuses, statusCounts(plan, statuses) + " (Slurm run " + o.run + ").", true);
  return anyFailed(statuses) ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  cosmo::CommandLine app("cosmo_suite",
                         "The whole benchmark in one command, resumable, on one machine or a Slurm cluster "
                         "(docs/suite.md).");
  app.add_option("suite", o.suite, "the suite file (config/suites/*.yaml)")->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "the output folder (datasets, manifest.jsonl, report.md / .html)");
  app.add_option("--data-root", o.data_root, "the folder the suite's sequences read their trials below");
  app.add_option("--jobs", o.jobs, "jobs side by side (default: as many as fit the cores, robots + 1 each)");
  app.add_option("--cores", o.cores, "cores to fill (default: this machine's)");
  app.add_option("--slurm", o.slurm, "submit to Slurm, with these sbatch options (e.g. \"-p long --time=4:00:00\")")
      ->expected(0, 1);
  app.add_flag("--wait", o.wait, "with --slurm: wait until every task has ended, then print the result");
  app.add_flag("--dry-run", o.dry_run, "plan and say what each job's folder holds; run nothing");
  CLI::App* st = app.add_subcommand("status", "each job's state: done, stale, missing, failed, running, queued");
  st->add_option("suite", o.suite, "the suite file (default: the output folder's last plan)");
  st->add_option("--out", o.out, "the output folder")->required();
  st->add_option("--data-root", o.data_root, "as for the run");
  CLI::App* jb = app.add_subcommand("job", "run one job of a plan (what the suite and its Slurm tasks run)");
  jb->add_option("--plan", o.plan, "the plan file")->required();
  jb->add_option("--job", o.job, "the job's id");
  jb->add_option("--list", o.list, "a file of job ids, one a line (a Slurm array)");
  jb->add_option("--index", o.index, "the line of --list (0-based)");
  jb->add_option("--run", o.run, "the run's id")->required();
  jb->add_option("--registration-threads", o.threads, "cosmo_generate --registration-threads (default: "
                 "SLURM_CPUS_PER_TASK beyond one per robot)");
  CLI::App* rp = app.add_subcommand("report", "write the manifest and the report of a plan (a Slurm run's end)");
  rp->add_option("--plan", o.plan, "the plan file")->required();
  rp->add_option("--run", o.run, "the run's id")->required();
  app.require_subcommand(0, 1);
  if (const auto code = app.parseOrExit(argc, argv)) return *code;
  o.slurm_given = app.count("--slurm") > 0;
  try {
    if (st->parsed()) return status(o);
    if (jb->parsed()) {
      if (o.job.empty() == o.list.empty()) throw CLI::ValidationError("job: give --job ID or --list FILE --index I");
      return job(o);
    }
    if (rp->parsed()) return report(o);
    if (o.suite.empty() || o.out.empty()) {
      std::cerr << app.help();
      return 2;
    }
    return runSuite(o);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_suite: " << e.what() << "\n";
    return 2;
  }
}
