// The loop does not allocate: a counting global operator new shows that a
// whole closed-loop run (scheduler, messages, FSW chain, plant, recorder)
// performs zero heap allocations after setup.  (Eigen's fixed-size and
// bounded-size types used by the plant never call malloc either.)
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "harness/core/recorder.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace {
std::atomic<unsigned long> g_news{0};
std::atomic<bool> g_counting{false};
}  // namespace

void* operator new(std::size_t n)
{
  if (g_counting.load()) ++g_news;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n)
{
  if (g_counting.load()) ++g_news;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {
unsigned long count_during(const std::function<void()>& f)
{
  g_news = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_news.load();
}
}  // namespace

TEST(NoAlloc, CounterWorks)
{
  // the counter itself must see an allocation, or the next test proves nothing
  const unsigned long n = count_during([] {
    auto* v = new std::vector<double>(100);
    delete v;
  });
  EXPECT_GE(n, 2u);
}

TEST(NoAlloc, RecorderSampleDoesNotAllocate)
{
  harness::Recorder rec("r");
  rec.add_source({{"a", "-"}, {"b", "-"}}, [](double* o) {
    o[0] = 1.0;
    o[1] = 2.0;
  });
  rec.allocate(1000, 64);
  harness::MemorySink mem;
  rec.add_sink(mem);
  const double* storage = mem.storage_address();
  const unsigned long n = count_during([&rec] {
    for (int i = 0; i < 1000; ++i) rec.sample();
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(rec.rows(), 1000u);
  EXPECT_EQ(mem.rows(), 960u);  // 15 full chunks handed over
  EXPECT_EQ(mem.storage_address(), storage);
}

TEST(NoAlloc, ClosedLoopRunDoesNotAllocate)
{
  for (const char* model : {"balanced", "fully_coupled"}) {
    const harness::Scenario sc = harness::load_scenario(
        KESTREL_SOURCE_DIR "/scenarios/s1_sun_pointing.yaml",
        {{"duration", "20"}, {"rates.dt", "0.05"}, {"rates.fsw_divisor", "2"}, {"rates.record_divisor", "2"},
         {"wheel_defaults.model", model}, {"fsw.rw_null.enabled", "true"}});
    harness::Run run(sc);  // setup allocates
    const double* storage = run.memory().storage_address();
    const unsigned long n = count_during([&run] { run.step_ticks(run.total_ticks()); });
    EXPECT_TRUE(run.done());
    EXPECT_EQ(run.failure(), "");
    EXPECT_EQ(n, 0u) << model;
    EXPECT_EQ(run.memory().storage_address(), storage);
    EXPECT_EQ(run.recorder().rows(), run.recorder().capacity());  // exact preallocation
    EXPECT_EQ(run.recorder().overflow(), 0u);
    EXPECT_EQ(run.memory().rows(), 201u);  // 20 s at 10 Hz, t = 0 and t = 20 included
  }
}

// S2: sim::Plant with thrusters, tanks and gravity,, the 8-thruster fsw_acs chain
// and the burn, over ignition (burn.start moved to 10 s): no allocation either.
TEST(NoAlloc, S2ThrusterRunDoesNotAllocate)
{
  const harness::Scenario sc = harness::load_scenario(KESTREL_SOURCE_DIR "/scenarios/s2_mars_orbit_insertion.yaml",
                                                      {{"duration", "30"}, {"burn.start", "10"}, {"burn.duration", "10"}});
  harness::Run run(sc);
  const unsigned long n = count_during([&run] { run.step_ticks(run.total_ticks()); });
  EXPECT_TRUE(run.done());
  EXPECT_EQ(run.failure(), "");
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(run.recorder().overflow(), 0u);
}

// S3: every Earth-orbit disturbance effector (held environments resampled
// inside the counted steps), their accumulated momenta, illumination, the
// field and the wheels' momentum recorded: no allocation either.
TEST(NoAlloc, S3EarthOrbitRunDoesNotAllocate)
{
  const harness::Scenario sc = harness::load_scenario(KESTREL_SOURCE_DIR "/scenarios/s3_leo_smallsat.yaml",
                                                      {{"duration", "30"}, {"outputs.hdf5", "false"}});
  harness::Run run(sc);
  const unsigned long n = count_during([&run] { run.step_ticks(run.total_ticks()); });
  EXPECT_TRUE(run.done());
  EXPECT_EQ(run.failure(), "");
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(run.recorder().overflow(), 0u);
}

// Scenario events applied during the loop (docs/events.md): a wheel fails
// at 5 s and is flagged unavailable 0.1 s later, both inside the counted
// steps; the log entries are built at setup and moved in.
TEST(NoAlloc, RunWithEventsDoesNotAllocate)
{
  const harness::Scenario sc = harness::load_scenario(
      KESTREL_SOURCE_DIR "/scenarios/s1_wheel_failure.yaml",
      {{"duration", "20"}, {"events.0.t", "5"}, {"rates.dt", "0.1"}, {"rates.fsw_divisor", "1"},
       {"rates.record_divisor", "1"}, {"wheel_defaults.model", "balanced"}});
  harness::Run run(sc);
  const unsigned long n = count_during([&run] { run.step_ticks(run.total_ticks()); });
  EXPECT_TRUE(run.done());
  EXPECT_EQ(run.failure(), "");
  ASSERT_EQ(run.events_applied().size(), 2u);  // both applied inside the counted loop
  EXPECT_EQ(n, 0u);
}

// Magnetorquers driven by PWM (the driver cuts the plant's steps), rod
// faults and a magnetometer with its faults, all applied inside the counted
// loop (test/harness/data/leo_magnetics.yaml, docs/environment.md).
TEST(NoAlloc, MagnetorquersAndMagnetometerDoNotAllocate)
{
  const harness::Scenario sc = harness::load_scenario(
      KESTREL_SOURCE_DIR "/test/harness/data/leo_magnetics.yaml",
      {{"magnetorquer_drive", "{mode: pwm, pwm_period: 0.05}"},
       {"sensors.magnetometer.sigma", "1e-7"},
       {"events", "[{t: 0.2, actions: [{device: mtq_a, action: dipole, value: 3.3}, "
                  "{device: mtq_z, action: dipole, value: -1.2}]}, "
                  "{t: 0.6, actions: [{device: mtq_z, action: stuck}, {device: magnetometer, action: dropout, value: 0.3}]}, "
                  "{t: 1.2, actions: [{device: mtq_a, action: scale, value: 0.5}, {device: magnetometer, action: frozen}]}, "
                  "{t: 1.5, actions: [{device: mtq_a, action: fail_off}, {device: magnetometer, action: restore}]}]"}});
  harness::Run run(sc);
  const unsigned long n = count_during([&run] { run.step_ticks(run.total_ticks()); });
  EXPECT_TRUE(run.done());
  EXPECT_EQ(run.failure(), "");
  ASSERT_EQ(run.events_applied().size(), 4u);
  EXPECT_EQ(n, 0u);
}
