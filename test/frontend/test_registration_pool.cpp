// RegistrationPool and the thread-safe FeatureCache: a job's result is the inline result bit for bit, whatever
// thread runs it; a scan's features are computed once even when several threads ask at once; errors reach the
// caller.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cosmo/frontend/feature_cache.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/frontend/registration_pool.hpp"
#include "../support/synthetic_team.hpp"

using namespace cosmo;
using namespace cosmo::frontend;
using namespace cosmo::sequence;

namespace {

const std::vector<test::SyntheticTrial>& team() { return test::sharedSyntheticTeam(2, 12); }

std::shared_ptr<const KeptScan> scanOf(char robot, std::size_t i) {
  return std::make_shared<const KeptScan>(std::make_shared<const Scan>(team()[robot == 'a' ? 0 : 1].scans[i]), nullptr);
}

}  // namespace

TEST(FeatureCache, ComputesAScanOnceWhenManyThreadsAskAtOnce) {
  FeatureCache cache;
  const registration::GlobalRegistration registration(FrontendParams::loadDir(defaultConfigDir()).registration);
  const auto scan = scanOf('a', 0);
  std::atomic<int> computed{0};
  std::vector<const registration::FeatureCloud*> got(4, nullptr);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] {
      got[i] = cache
                   .get(scan,
                        [&](const Scan& s) {
                          ++computed;
                          return registration.prepare(s);
                        })
                   .get();
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(computed.load(), 1);
  EXPECT_EQ(cache.size(), 1u);
  for (const registration::FeatureCloud* f : got) EXPECT_EQ(f, got.front());  // the one entry
  // a failing computation is reported to every caller of that scan, and does not poison other scans
  const auto bad = scanOf('a', 1);
  const auto fail = [](const Scan&) -> registration::FeatureCloud { throw std::runtime_error("no features"); };
  EXPECT_THROW(cache.get(bad, fail), std::runtime_error);
  EXPECT_THROW(cache.get(bad, fail), std::runtime_error);
  EXPECT_EQ(cache.get(scan, fail).get(), got.front());  // cached: not recomputed
}

TEST(RegistrationPool, ResultsAreTheInlineResultsBitForBitAndErrorsReachTheCaller) {
  const registration::GlobalRegistration registration(FrontendParams::loadDir(defaultConfigDir()).registration);
  // pairs of scans of the two robots at their shared start (some register, some not)
  std::vector<std::pair<std::shared_ptr<const KeptScan>, std::shared_ptr<const KeptScan>>> pairs;
  for (std::size_t i = 0; i < 4; ++i) pairs.emplace_back(scanOf('a', i), scanOf('b', 3 - i));
  std::vector<registration::RegistrationResult> inline_results;
  for (const auto& [s, t] : pairs) inline_results.push_back(registration.align(*s->get(), *t->get()));
  for (unsigned threads : {0u, 1u, 2u, 3u}) {  // 0: inline in submit()
    auto cache = std::make_shared<FeatureCache>();
    RegistrationPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    std::vector<std::shared_future<registration::RegistrationResult>> futures;
    for (const auto& [s, t] : pairs)
      futures.push_back(pool.submit([&registration, cache, s = s, t = t] {
        const auto prepare = [&](const Scan& x) { return registration.prepare(x); };
        const auto target = cache->get(t, prepare);
        const auto source = cache->get(s, prepare);
        return registration.align(*source, *target);
      }));
    auto failing = pool.submit([]() -> registration::RegistrationResult { throw std::runtime_error("job failed"); });
    for (std::size_t i = 0; i < futures.size(); ++i) {
      const registration::RegistrationResult& r = futures[i].get();
      EXPECT_TRUE(r.T_target_source.matrix() == inline_results[i].T_target_source.matrix()) << i;
      EXPECT_EQ(r.valid, inline_results[i].valid);
      EXPECT_EQ(r.final_inliers, inline_results[i].final_inliers);
      EXPECT_EQ(r.reason, inline_results[i].reason);
    }
    EXPECT_THROW(failing.get(), std::runtime_error);
    EXPECT_EQ(cache->size(), 8u);                  // every scan's features once
    EXPECT_EQ(pool.jobsDone(), pairs.size() + 1);  // counted before its result arrives
  }
}

TEST(RegistrationPool, StopsWithJobsStillQueued) {
  std::shared_future<registration::RegistrationResult> never;
  {
    RegistrationPool pool(1);
    std::promise<void> release;
    std::shared_future<void> gate = release.get_future().share();
    pool.submit([gate] {
      gate.wait();
      return registration::RegistrationResult{};
    });
    never = pool.submit([] { return registration::RegistrationResult{}; });
    release.set_value();
  }  // the destructor joins after the running job; the queued one may be abandoned
  if (never.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      never.get();
    } catch (const std::future_error& e) { EXPECT_EQ(e.code(), std::future_errc::broken_promise); }
  }
}
