#pragma once
// The output folder of a suite and how it stays consistent when a run is killed at any moment:
//
//   <out>/<group>/               a finished job's files and its record (suite.json), moved into place whole
//   <out>/noise_models/<name>/   a finished estimate
//   <out>/manifest.jsonl         one line per finished job (its record), rewritten whole after each job
//   <out>/report.md, report.html
//   <out>/.suite/                the suite's own: lock, plans, logs, failures, locks per job, tmp/ (jobs being
//                                written), trash/ (replaced folders being removed), config/ (config copies)
//
// A job writes into .suite/tmp/<job>.<pid>/ and, complete, renames it to its folder (a folder it replaces is
// first renamed into .suite/trash/); a run killed before that leaves only a tmp folder, which the next run removes
// and redoes ("partial"). One lock (flock) per output folder keeps two suites apart; one per job keeps a local run
// and Slurm tasks from writing the same job.
#include <memory>
#include <string>
#include <vector>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

/// <out>/.suite/<sub> (created).
std::string suiteDir(const std::string& out_dir, const std::string& sub = "");

/// An exclusive flock on a file, released when the object goes.
class FileLock {
 public:
  /// Blocks until the lock is ours when `wait`; otherwise throws std::runtime_error with `busy_message` and the
  /// holder's note (what it wrote into the file) when another process holds it.
  FileLock(const std::string& path, bool wait, const std::string& busy_message);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  /// Writes a note for whoever finds the lock taken (pid, command, start time).
  void note(const std::string& text);

 private:
  int fd_ = -1;
};

/// The lock of a whole output folder, held by a running suite (local run or Slurm submission).
std::unique_ptr<FileLock> lockOutDir(const std::string& out_dir, const std::string& command);
/// The lock of one job (held by the process that writes it). `wait`: false returns nullptr when it is taken.
std::unique_ptr<FileLock> lockJob(const std::string& out_dir, const std::string& job_id, bool wait);

/// A fresh .suite/tmp/<job>.<pid>/ for a job to write into.
std::string makeJobTmpDir(const std::string& out_dir, const std::string& job_id);
/// Moves a complete tmp folder to the job's folder, replacing (and then removing) what was there.
void moveIntoPlace(const std::string& out_dir, const std::string& tmp_dir, const std::string& job_folder);
/// Removes what a killed run left of `job_id` (its tmp folders) and the trash; true when there were tmp folders.
/// Call with the job's lock held.
bool removePartial(const std::string& out_dir, const std::string& job_id);

/// Rewrites <out>/manifest.jsonl: the record of each of the plan's jobs that has one, in the plan's order (under
/// a lock of its own: Slurm tasks finish at the same time).
void writeManifest(const Plan& plan);

/// flush + fsync of a file or folder (best effort: a failure is ignored).
void syncPath(const std::string& path);

}  // namespace cosmo::suite
