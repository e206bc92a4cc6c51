#include "cosmo/suite/slurm.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/suite/out_dir.hpp"
#include "cosmo/suite/scheduler.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// The largest CPU count of the cluster's nodes (sinfo), 0 when unknown.
unsigned largestNode() {
  int status = 0;
  const std::string out = captureCommand({"sinfo", "-h", "-o", "%c"}, status);
  unsigned best = 0;
  std::istringstream in(out);
  std::string w;
  while (in >> w) try {
      best = std::max(best, static_cast<unsigned>(std::stoul(w)));
    } catch (const std::exception&) {}
  return status == 0 ? best : 0;
}

std::string sbatch(std::vector<std::string> args, const SlurmOptions& o, const std::string& script) {
  std::vector<std::string> argv{"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), o.sbatch_options.begin(), o.sbatch_options.end());
  argv.push_back(script);
  int status = 0;
  std::string out = captureCommand(argv, status);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  if (status != 0 || out.empty()) {
    std::string cmd;
    for (const auto& a : argv) cmd += " " + a;
    throw std::runtime_error("sbatch failed (exit " + std::to_string(status) + "):" + cmd + "\n" + out);
  }
  return out.substr(0, out.find(';'));  // "<id>[;<cluster>]"
}

SlurmArray submitArray(const Plan& plan, const std::string& name, const std::vector<std::string>& jobs,
                       const std::string& after, const SlurmOptions& o, const std::string& dir, unsigned node_cpus) {
  SlurmArray a{name, "", jobs};
  std::string list;
  unsigned width = 1;
  for (const auto& id : jobs) {
    list += id + "\n";
    width = std::max(width, jobWidth(plan.job(id).robots, SlotPolicy{1000, 0}));
  }
  const std::string list_path = dir + "/" + name + ".jobs";
  dataset::writeFileAtomically(list_path, list);
  unsigned cpus = o.cpus_per_task ? o.cpus_per_task : width;
  if (!o.cpus_per_task && node_cpus) cpus = std::min(cpus, node_cpus);
  const std::string script = dir + "/" + name + ".sh";
  dataset::writeFileAtomically(script, batchScript(plan, list_path, o.plan_path, o.self_exe, o.run_id, dir, cpus));
  std::vector<std::string> args{"--array=0-" + std::to_string(jobs.size() - 1),
                                "--job-name=cosmo-" + plan.suite_name + "-" + name};
  if (!after.empty()) args.push_back("--dependency=afterany:" + after);
  a.slurm_id = sbatch(args, o, script);
  return a;
}

}  // namespace

std::string batchScript(const Plan& plan, const std::string& list_path, const std::string& plan_path,
                        const std::string& self_exe, const std::string& run_id, const std::string& log_dir,
                        unsigned cpus_per_task) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# cosmo_suite " << plan.suite_name << ": one array task per job listed in " << list_path << "\n"
    << "#SBATCH --cpus-per-task=" << cpus_per_task << "\n"
    << "#SBATCH --output=" << log_dir << "/%x-%A_%a.out\n"
    << "# cosmo_suite job: registration threads = the task's CPUs beyond one per robot (SLURM_CPUS_PER_TASK)\n"
    << "exec " << quoted(self_exe) << " job --plan " << quoted(plan_path) << " --list " << quoted(list_path)
    << " --index \"$SLURM_ARRAY_TASK_ID\" --run " << quoted(run_id) << "\n";
  return s.str();
}

/// Each job's wave: 0 without anything to wait for among `todo`, else one more than the latest it waits for.
std::map<std::string, int> waves(const Plan& plan, const std::vector<std::string>& todo) {
  std::map<std::string, int> wave;
  for (const auto& job : plan.jobs) {  // the plan lists what a job waits for before it
    if (std::find(todo.begin(), todo.end(), job.id) == todo.end()) continue;
    int w = 0;
    for (const auto* deps : {&job.depends_on, &job.after})
      for (const auto& d : *deps)
        if (wave.count(d)) w = std::max(w, wave[d] + 1);
    wave[job.id] = w;
  }
  return wave;
}

SlurmSubmission submitToSlurm(const Plan& plan, const std::vector<std::string>& todo, const SlurmOptions& o) {
  if (todo.empty()) throw std::runtime_error("nothing to submit: every job is current");
  SlurmSubmission sub;
  sub.run_id = o.run_id;
  const std::string dir = suiteDir(plan.out_dir, "slurm/" + o.run_id);
  const unsigned node_cpus = largestNode();
  const std::map<std::string, int> wave = waves(plan, todo);
  int last = 0;
  for (const auto& [id, w] : wave) last = std::max(last, w);
  std::map<std::string, std::string> array_of;  // job -> the Slurm id of its array
  for (int w = 0; w <= last; ++w) {
    std::vector<std::string> jobs;
    std::string after;
    for (const auto& job : plan.jobs) {
      if (!wave.count(job.id) || wave.at(job.id) != w) continue;
      jobs.push_back(job.id);
      for (const auto* deps : {&job.depends_on, &job.after})
        for (const auto& d : *deps)
          if (array_of.count(d) && after.find(array_of[d]) == std::string::npos)
            after += (after.empty() ? "" : ":") + array_of[d];
    }
    sub.arrays.push_back(submitArray(plan, "wave" + std::to_string(w), jobs, after, o, dir, node_cpus));
    for (const auto& id : jobs) array_of[id] = sub.arrays.back().slurm_id;
  }
  std::string all;
  for (const auto& a : sub.arrays) all += (all.empty() ? "" : ":") + a.slurm_id;
  const std::string report = dir + "/report.sh";
  dataset::writeFileAtomically(report, "#!/bin/bash\n#SBATCH --cpus-per-task=1\n#SBATCH --output=" + dir +
                                           "/report-%j.out\nexec " + quoted(o.self_exe) + " report --plan " +
                                           quoted(o.plan_path) + " --run " + quoted(o.run_id) + "\n");
  sub.report_job = sbatch({"--job-name=cosmo-report", "--dependency=afterany:" + all}, o, report);
  dataset::writeFileAtomically(dir + "/submitted.json", sub.toJson() + "\n");
  dataset::writeFileAtomically(suiteDir(plan.out_dir, "slurm") + "/last", o.run_id + "\n");
  return sub;
}

std::string SlurmSubmission::toJson() const {
  nlohmann::json arrays_json = nlohmann::json::array();
  for (const auto& a : arrays) arrays_json.push_back({{"name", a.name}, {"slurm_id", a.slurm_id}, {"jobs", a.jobs}});
  return nlohmann::json{{"run", run_id}, {"arrays", arrays_json}, {"report_job", report_job}}.dump(1);
}

SlurmSubmission SlurmSubmission::fromJson(const std::string& text, const std::string& where) {
  try {
    const auto o = nlohmann::json::parse(text);
    SlurmSubmission s;
    s.run_id = o.at("run").get<std::string>();
    s.report_job = o.at("report_job").get<std::string>();
    for (const auto& a : o.at("arrays"))
      s.arrays.push_back({a.at("name").get<std::string>(), a.at("slurm_id").get<std::string>(),
                          a.at("jobs").get<std::vector<std::string>>()});
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": not a Slurm submission record: " + e.what());
  }
}

std::map<std::string, std::string> slurmQueue(const SlurmSubmission& submission) {
  std::string ids;
  for (const auto& a : submission.arrays) ids += (ids.empty() ? "" : ",") + a.slurm_id;
  if (!submission.report_job.empty()) ids += (ids.empty() ? "" : ",") + submission.report_job;
  std::map<std::string, std::string> states;
  if (ids.empty()) return states;
  int status = 0;
  const std::string out = captureCommand({"squeue", "-h", "-r", "-j", ids, "-o", "%i %T"}, status);
  if (status != 0) return states;
  std::istringstream in(out);
  std::string id, state;
  while (in >> id >> state) states[id] = state;
  return states;
}

bool readLastSubmission(const std::string& out_dir, SlurmSubmission& submission) {
  std::ifstream last(fs::path(out_dir) / ".suite" / "slurm" / "last");
  std::string run;
  if (!(last >> run)) return false;
  const fs::path path = fs::path(out_dir) / ".suite" / "slurm" / run / "submitted.json";
  const std::optional<std::string> text = readWholeFileIfAny(path.string());
  if (!text) return false;
  submission = SlurmSubmission::fromJson(*text, path.string());
  return true;
}

std::vector<std::string> splitShellWords(const std::string& text) {
  std::vector<std::string> words;
  std::string w;
  bool in_word = false;
  char quote = 0;
  for (const char c : text) {
    if (quote) {
      if (c == quote)
        quote = 0;
      else
        w += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(w);
      w.clear();
      in_word = false;
    } else {
      w += c;
      in_word = true;
    }
  }
  if (quote) throw std::runtime_error("--slurm: unbalanced quote in '" + text + "'");
  if (in_word) words.push_back(w);
  return words;
}

std::string captureCommand(const std::vector<std::string>& argv, int& status) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    ::execvp(args[0], args.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  std::string out;
  char buf[4096];
  ssize_t n;
  while ((n = ::read(fds[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) out.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {}
  status = pid < 0 ? 127 : WIFEXITED(st) ? WEXITSTATUS(st) : 128;
  return out;
}

}  // namespace cosmo::suite
