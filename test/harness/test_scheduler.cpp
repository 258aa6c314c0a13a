// Scheduler: rate-group arithmetic checked against hand-listed tick sets.
#include <gtest/gtest.h>

#include <vector>

#include "harness/core/scheduler.h"

using harness::RateGroup;
using harness::Scheduler;

TEST(RateGroup, DueTicksByHand)
{
  // divisor 4, offset 1: ticks 1, 5, 9, 13 in [0, 14)
  const RateGroup g{"g", 4, 1};
  std::vector<uint64_t> due;
  for (uint64_t k = 0; k < 14; ++k)
    if (g.due(k)) due.push_back(k);
  EXPECT_EQ(due, (std::vector<uint64_t>{1, 5, 9, 13}));
}

TEST(RateGroup, CountDueByHand)
{
  const RateGroup g{"g", 4, 1};
  EXPECT_EQ(g.count_due(0), 0u);   // []
  EXPECT_EQ(g.count_due(1), 0u);   // [0]
  EXPECT_EQ(g.count_due(2), 1u);   // [0,1]: 1
  EXPECT_EQ(g.count_due(5), 1u);   // 1
  EXPECT_EQ(g.count_due(6), 2u);   // 1, 5
  EXPECT_EQ(g.count_due(14), 4u);  // 1, 5, 9, 13
  const RateGroup every{"e", 1, 0};
  EXPECT_EQ(every.count_due(7), 7u);
  const RateGroup ten{"t", 10, 0};
  EXPECT_EQ(ten.count_due(60001), 6001u);  // S1: ticks 0..60000 at 10:1 -> t = 0, 0.1, ..., 600
}

TEST(RateGroup, CountDueMatchesEnumerationExhaustively)
{
  for (uint32_t d = 1; d <= 7; ++d)
    for (uint32_t o = 0; o < d; ++o)
      for (uint64_t n = 0; n <= 30; ++n) {
        uint64_t c = 0;
        for (uint64_t k = 0; k < n; ++k) c += (k % d == o) ? 1 : 0;
        EXPECT_EQ(RateGroup({"g", d, o}).count_due(n), c) << d << " " << o << " " << n;
      }
}

TEST(RateGroup, InvalidGroupsRejected)
{
  EXPECT_THROW(harness::validate(RateGroup{"zero", 0, 0}), std::invalid_argument);
  EXPECT_THROW(harness::validate(RateGroup{"off=div", 3, 3}), std::invalid_argument);
  EXPECT_THROW(harness::validate(RateGroup{"off>div", 3, 7}), std::invalid_argument);
  EXPECT_NO_THROW(harness::validate(RateGroup{"ok", 3, 2}));
  Scheduler s(1000);
  EXPECT_THROW(s.add_task("bad", RateGroup{"bad", 2, 2}, [](uint64_t) {}), std::invalid_argument);
  EXPECT_THROW(Scheduler(0), std::invalid_argument);
}

TEST(Scheduler, OrderWithinTickAndCounts)
{
  Scheduler s(10'000'000);  // 10 ms tick
  std::vector<std::string> log;
  s.add_task("fast", RateGroup{"1", 1, 0}, [&](uint64_t k) { log.push_back("fast" + std::to_string(k)); });
  s.add_task("slow", RateGroup{"3", 3, 0}, [&](uint64_t k) { log.push_back("slow" + std::to_string(k)); });
  s.add_task("phase", RateGroup{"3+2", 3, 2}, [&](uint64_t k) { log.push_back("phase" + std::to_string(k)); });
  for (uint64_t k = 0; k < 6; ++k) s.run_tick(k);
  const std::vector<std::string> want{"fast0", "slow0", "fast1", "fast2", "phase2", "fast3",
                                      "slow3", "fast4", "fast5", "phase5"};
  EXPECT_EQ(log, want);
  EXPECT_EQ(s.run_count(0), 6u);
  EXPECT_EQ(s.run_count(1), 2u);
  EXPECT_EQ(s.run_count(2), 2u);
  // integer clock: tick 360000 of 10 ms is exactly 3600 s
  EXPECT_EQ(s.t_ns(360000), 3'600'000'000'000ULL);
}

TEST(Scheduler, TaskOfSeveralGroupsRunsWhenAnyIsDue)
{
  // {3, 0} and {4, 1}: due at k = 0, 3, 6, 9 and 1, 5, 9 (9 once); a group
  // of divisor 1 among others makes the task due at every tick
  Scheduler s(1);
  std::vector<uint64_t> two, with_every;
  s.add_task("two", std::vector<RateGroup>{{"3", 3, 0}, {"4+1", 4, 1}}, [&](uint64_t k) { two.push_back(k); });
  s.add_task("with_every", std::vector<RateGroup>{{"5+4", 5, 4}, {"1", 1, 0}},
             [&](uint64_t k) { with_every.push_back(k); });
  for (uint64_t k = 0; k < 10; ++k) s.run_tick(k);
  EXPECT_EQ(two, (std::vector<uint64_t>{0, 1, 3, 5, 6, 9}));
  EXPECT_EQ(with_every, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(s.run_count(0), 6u);
  EXPECT_EQ(s.run_count(1), 10u);
  // a tick far from the last one (a resumed run): by the groups alone
  two.clear();
  EXPECT_EQ(s.run_tick(1'000'000'001), 2u);  // 1'000'000'001 % 4 == 1
  EXPECT_EQ(two, (std::vector<uint64_t>{1'000'000'001}));
}

TEST(Scheduler, NoDriftOverManyTicks)
{
  // 0.1 s summed 10^6 times as a double drifts; the integer clock does not.
  Scheduler s(100'000'000);
  double summed = 0.0;
  for (int i = 0; i < 1'000'000; ++i) summed += 0.1;
  EXPECT_NE(summed, 100000.0);
  EXPECT_EQ(s.t_ns(1'000'000), 100'000'000'000'000ULL);
}
