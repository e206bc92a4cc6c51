#include "cosmo/suite/local_run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>
#include <thread>

#include "cosmo/suite/child_process.hpp"
#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/out_dir.hpp"
#include "cosmo/suite/progress.hpp"
#include "cosmo/suite/run_job.hpp"
#include "cosmo/common/whole_file.hpp"

namespace cosmo::suite {
namespace {

std::size_t datasets(const Job& job) { return job.kind == Job::Kind::Estimate ? 0 : job.comms.size(); }
double work(const Job& job) { return job.seconds * static_cast<double>(std::max<std::size_t>(1, job.comms.size())); }

struct Running {
  pid_t pid;
  int job;
  double started;
};

class LocalRun {
 public:
  LocalRun(const Plan& plan, const LocalRunOptions& o, std::ostream& out, const std::vector<std::string>& todo)
      : plan_(plan), o_(o), out_(out), sched_(plan, todo, o.policy), todo_(todo), t0_(monotonicSeconds()) {}

  JobStatuses run(JobStatuses statuses) {
    statuses_ = std::move(statuses);
    double last_progress = t0_;
    while (!sched_.allFinished()) {
      for (int next; (next = sched_.next()) >= 0;) start(next);
      reap();
      if (monotonicSeconds() - last_progress >= o_.progress_every_s) {
        out_ << progressLine(counts()) << std::endl;
        last_progress = monotonicSeconds();
      }
      if (!running_.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    for (std::size_t i = 0; i < plan_.jobs.size(); ++i)
      if (sched_.state(static_cast<int>(i)) == Scheduler::State::Blocked)
        statuses_[plan_.jobs[i].id] = "not run: it needs " + sched_.blockedBy(static_cast<int>(i)) + ", which failed";
    out_ << progressLine(counts()) << std::endl;
    return statuses_;
  }

 private:
  const Plan& plan_;
  const LocalRunOptions& o_;
  std::ostream& out_;
  Scheduler sched_;
  std::vector<std::string> todo_;
  std::vector<Running> running_;
  JobStatuses statuses_;
  double t0_, processed_s_ = 0.0;

  void start(int i) {
    const Job& job = plan_.jobs[i];
    const unsigned width = sched_.width(i), threads = registrationThreads(job.robots, width);
    const std::vector<std::string> argv{o_.self_exe, "job", "--plan", o_.plan_path, "--job", job.id,
                                        "--registration-threads", std::to_string(threads), "--run", o_.run_id};
    const pid_t pid = spawnChild(argv, jobLogPath(plan_.out_dir, job.id) + ".suite");
    running_.push_back({pid, i, monotonicSeconds()});
    sched_.started(i);
    out_ << "[suite] start " << job.id << " (" << job.robots << " robots, " << width << " cores, " << threads
         << " registration threads)" << std::endl;
  }

  void reap() {
    for (auto it = running_.begin(); it != running_.end();) {
      ChildResult r;
      if (!waitChild(it->pid, false, r, it->started)) {
        ++it;
        continue;
      }
      finish(it->job, r);
      it = running_.erase(it);
    }
  }

  void finish(int i, const ChildResult& r) {
    const Job& job = plan_.jobs[i];
    const bool ok = r.exit_code == kExitDone || r.exit_code == kExitCurrent;
    sched_.finished(i, ok);
    processed_s_ += work(job);
    if (r.exit_code == kExitDone) {
      statuses_[job.id] = "done";
      out_ << "[suite] done " << job.id << " in " << formatDuration(r.wall_s) << std::endl;
    } else if (r.exit_code == kExitCurrent) {
      statuses_[job.id] = "skipped as current";
      out_ << "[suite] " << job.id << " is current (its input's new version gave the same bytes)" << std::endl;
    } else {
      std::string reason = readFailure(plan_.out_dir, job.id);
      if (reason.empty()) reason = "the job process ended with " + r.describe();
      statuses_[job.id] = "failed: " + reason;
      out_ << "[suite] FAILED " << job.id << ": " << reason << "\n  log: " << jobLogPath(plan_.out_dir, job.id)
           << std::endl;
    }
  }

  ProgressCounts counts() const {
    ProgressCounts c;
    c.elapsed_s = monotonicSeconds() - t0_;
    c.processed_s = processed_s_;
    for (std::size_t i = 0; i < plan_.jobs.size(); ++i) {
      const Job& job = plan_.jobs[i];
      const auto st = sched_.state(static_cast<int>(i));
      const auto status = statuses_.count(job.id) ? statuses_.at(job.id) : "";
      if (st == Scheduler::State::Running) {
        c.running += datasets(job);
        const LogProgress p = readLogProgress(readWholeFileOrEmpty(jobLogPath(plan_.out_dir, job.id)));
        c.processed_s += std::min(p.done_s, work(job));
        c.remaining_s += std::max(0.0, work(job) - p.done_s);
      } else if (st == Scheduler::State::Waiting) {
        c.left += datasets(job);
        c.remaining_s += work(job);
      } else if (status.rfind("skipped", 0) == 0) {
        c.skipped += datasets(job);
      } else if (status == "done") {
        c.done += datasets(job);
      } else {
        c.failed += datasets(job);
      }
    }
    return c;
  }
};

}  // namespace

std::vector<std::string> jobsToRun(const Plan& plan, const std::map<std::string, std::string>& survey) {
  std::vector<std::string> todo;
  for (const auto& job : plan.jobs) {
    bool run = survey.at(job.id) != "current";
    for (const auto& dep : job.depends_on) run |= std::find(todo.begin(), todo.end(), dep) != todo.end();
    if (run) todo.push_back(job.id);
  }
  return todo;
}

std::map<std::string, std::string> surveyJobs(const Plan& plan) {
  std::map<std::string, std::string> survey;
  IdentityCache cache;
  for (const auto& job : plan.jobs) {
    const auto lock = lockJob(plan.out_dir, job.id, false);
    if (!lock) {
      survey[job.id] = "running: another process is writing it";
      continue;
    }
    if (removePartial(plan.out_dir, job.id)) {
      survey[job.id] = "partial: a run was killed while it wrote this job";
      continue;
    }
    const JobState s = checkJob(plan, job, cache);
    survey[job.id] = s.kind == JobState::Kind::Current ? "current"
                     : s.kind == JobState::Kind::Stale ? "stale: " + s.reason
                                                       : "missing";
  }
  return survey;
}

JobStatuses runLocal(const Plan& plan, const LocalRunOptions& options, std::ostream& out) {
  const std::map<std::string, std::string> survey = surveyJobs(plan);
  const std::vector<std::string> todo = jobsToRun(plan, survey);
  JobStatuses statuses;
  for (const auto& job : plan.jobs) {
    const std::string& s = survey.at(job.id);
    const bool runs = std::find(todo.begin(), todo.end(), job.id) != todo.end();
    if (!runs) statuses[job.id] = "skipped as current";
    out << "[suite] " << job.id << ": " << (runs ? (s == "current" ? "current, checked again after its dependency"
                                                                   : s + " -> to do")
                                                 : "current -> skipped")
        << std::endl;
  }
  LocalRun run(plan, options, out, todo);
  return run.run(statuses);
}

}  // namespace cosmo::suite
