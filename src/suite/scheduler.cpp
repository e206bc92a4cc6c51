#include "cosmo/suite/scheduler.hpp"

#include <algorithm>
#include <numeric>

namespace cosmo::suite {

unsigned jobWidth(int robots, const SlotPolicy& policy) {
  const unsigned cores = std::max(1u, policy.cores);
  if (policy.jobs > 0) return std::max(1u, cores / policy.jobs);
  return std::min(cores, static_cast<unsigned>(std::max(1, robots)) + 1u);
}

unsigned registrationThreads(int robots, unsigned width) {
  return width > static_cast<unsigned>(robots) ? width - static_cast<unsigned>(robots) : 1u;
}

Scheduler::Scheduler(const Plan& plan, const std::vector<std::string>& todo, const SlotPolicy& policy)
    : plan_(plan), policy_(policy), states_(plan.jobs.size(), State::Done), todo_(plan.jobs.size(), false),
      blocked_by_(plan.jobs.size()), free_(std::max(1u, policy.cores)) {
  for (std::size_t i = 0; i < plan.jobs.size(); ++i)
    if (std::find(todo.begin(), todo.end(), plan.jobs[i].id) != todo.end()) {
      todo_[i] = true;
      states_[i] = State::Waiting;
    }
  order_.resize(plan.jobs.size());
  std::iota(order_.begin(), order_.end(), 0);
  const auto work = [&](int i) { return plan.jobs[i].seconds * plan.jobs[i].robots; };
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
    const bool ea = plan.jobs[a].kind == Job::Kind::Estimate, eb = plan.jobs[b].kind == Job::Kind::Estimate;
    if (ea != eb) return ea;
    return work(a) > work(b);
  });
}

unsigned Scheduler::width(int job) const { return std::min(jobWidth(plan_.jobs[job].robots, policy_), std::max(1u, policy_.cores)); }

bool Scheduler::dependenciesDone(int job) const {
  const Job& j = plan_.jobs[job];
  for (std::size_t i = 0; i < plan_.jobs.size(); ++i) {
    const std::string& id = plan_.jobs[i].id;
    if (std::find(j.depends_on.begin(), j.depends_on.end(), id) != j.depends_on.end() && states_[i] != State::Done)
      return false;
    if (std::find(j.after.begin(), j.after.end(), id) != j.after.end() &&
        (states_[i] == State::Waiting || states_[i] == State::Running))
      return false;
  }
  return true;
}

int Scheduler::next() const {
  if (policy_.jobs > 0 && running_ >= policy_.jobs) return -1;
  for (const int i : order_) {
    if (states_[i] != State::Waiting || !dependenciesDone(i)) continue;
    if (running_ == 0 || width(i) <= free_) return i;
    return -1;  // the longest waiting job comes first: a smaller one would delay it
  }
  return -1;
}

void Scheduler::started(int job) {
  states_[job] = State::Running;
  ++running_;
  free_ -= std::min(free_, width(job));
}

void Scheduler::finished(int job, bool ok) {
  if (states_[job] == State::Running) {
    --running_;
    free_ = std::min(std::max(1u, policy_.cores), free_ + width(job));
  }
  states_[job] = ok ? State::Done : State::Failed;
  if (ok) return;
  for (std::size_t i = 0; i < plan_.jobs.size(); ++i) {
    const auto& deps = plan_.jobs[i].depends_on;
    if (states_[i] == State::Waiting && std::find(deps.begin(), deps.end(), plan_.jobs[job].id) != deps.end()) {
      blocked_by_[i] = plan_.jobs[job].id;
      finished(static_cast<int>(i), false);
      states_[i] = State::Blocked;
    }
  }
}

bool Scheduler::allFinished() const {
  return std::none_of(states_.begin(), states_.end(),
                      [](State s) { return s == State::Waiting || s == State::Running; });
}

std::size_t Scheduler::count(State state) const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < states_.size(); ++i) n += todo_[i] && states_[i] == state;
  return n;
}

}  // namespace cosmo::suite
