#pragma once
// Which job runs next on one machine, and with how many threads.
//
// A cosmo_generate run keeps one thread busy per robot (its odometry worker reads and decodes the robot's bag and
// runs LOAM ahead of the team) and runs its loop-closure registrations on a pool; the team's own thread mostly
// waits for them. So a group of R robots is given a width of R + 1 cores (R odometry workers, one registration
// thread), at most the machine's cores, and the suite starts a job only when its width fits in the free cores (or
// nothing runs): the machine is filled without being oversubscribed. `--jobs N` instead runs N jobs side by side,
// each with a width of cores / N. A job's registration threads are its width minus its robots, at least 1.
//
// Order: noise-model estimates first (others wait for them), then the longest work first (sequence seconds x
// robots), which keeps the last job from starting late; ties in the plan's order. A job whose dependency failed
// is not run; a job that only starts after another (`after`: a first pass over a compressed bag) starts when that
// one has ended, however it ended.
#include <string>
#include <vector>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

struct SlotPolicy {
  unsigned cores = 1;
  unsigned jobs = 0;  ///< --jobs N; 0 = as many as fit by width
};

/// The cores a job of `robots` is given.
unsigned jobWidth(int robots, const SlotPolicy& policy);
/// cosmo_generate --registration-threads for a job of `robots` and `width`.
unsigned registrationThreads(int robots, unsigned width);

class Scheduler {
 public:
  enum class State { Waiting, Running, Done, Failed, Blocked };

  /// The jobs of `plan` whose ids are in `todo` (the others are done or current); `policy` decides widths.
  Scheduler(const Plan& plan, const std::vector<std::string>& todo, const SlotPolicy& policy);

  /// The next job to start now (its index in the plan), or -1 when none can start (cores busy, dependencies
  /// pending, or nothing left).
  int next() const;
  void started(int job);
  /// Marks a job finished; a failure blocks the jobs that depend on it.
  void finished(int job, bool ok);

  State state(int job) const { return states_.at(job); }
  unsigned width(int job) const;
  bool allFinished() const;
  unsigned freeCores() const { return free_; }
  /// Jobs in `state` (todo jobs only).
  std::size_t count(State state) const;
  /// What blocked a job ("" if not blocked): the failed dependency's id.
  const std::string& blockedBy(int job) const { return blocked_by_.at(job); }

 private:
  const Plan& plan_;
  SlotPolicy policy_;
  std::vector<State> states_;
  std::vector<bool> todo_;
  std::vector<std::string> blocked_by_;
  std::vector<int> order_;
  unsigned free_ = 0;
  unsigned running_ = 0;

  bool dependenciesDone(int job) const;
};

}  // namespace cosmo::suite
