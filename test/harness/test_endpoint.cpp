// The FSW seam: a Run takes any FswEndpoint.  A wrapper around the
// in-process application sees every cycle's three messages and changes
// nothing (bit-identical rows); an endpoint whose link fails stops the run
// at that tick with its message, the rows recorded so far kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "harness/core/fsw_endpoint.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

harness::Scenario short_s1()
{
  return harness::load_scenario(kS1, {{"duration", "20"},
                                      {"rates.dt", "0.05"},
                                      {"rates.fsw_divisor", "2"},
                                      {"rates.record_divisor", "2"},
                                      {"wheel_defaults.model", "balanced"}});
}

// Forwards to an in-process FSW and keeps what crossed the seam.
class Spy : public harness::FswEndpoint {
 public:
  explicit Spy(const FswAcsConfig& cfg) : inner_(cfg) {}
  std::string describe() const override { return "spy around " + inner_.describe(); }
  void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& h) override
  {
    if (cycles > 0 && in.t_ns <= last_t_ns) ++non_increasing;
    last_t_ns = in.t_ns;
    inner_.cycle(in, out, h);
    ++cycles;
  }
  uint64_t cycles = 0, non_increasing = 0, last_t_ns = 0;

 private:
  harness::InProcessFsw inner_;
};

// Delivers n cycles, then the link is down.
class Flaky : public harness::FswEndpoint {
 public:
  Flaky(const FswAcsConfig& cfg, int n) : inner_(cfg), left_(n) {}
  std::string describe() const override { return "flaky link"; }
  void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& h) override
  {
    if (left_-- <= 0) throw harness::FswEndpointError("no answer from the flight computer");
    inner_.cycle(in, out, h);
  }

 private:
  harness::InProcessFsw inner_;
  int left_;
};

}  // namespace

TEST(Endpoint, AnyEndpointPlugsInWithoutChangingTheLoop)
{
  const harness::Scenario sc = short_s1();
  harness::Run plain(sc);
  ASSERT_TRUE(plain.step_ticks(plain.total_ticks())) << plain.failure();

  auto spy = std::make_unique<Spy>(harness::fsw_acs_config_of(sc));
  Spy* s = spy.get();
  harness::RunConfig cfg;
  cfg.fsw = std::move(spy);
  harness::Run wrapped(sc, std::move(cfg));
  ASSERT_TRUE(wrapped.step_ticks(wrapped.total_ticks())) << wrapped.failure();
  EXPECT_EQ(s->cycles, 201u);  // 20 s at 10 Hz, t = 0 and t = 20 included
  EXPECT_EQ(s->non_increasing, 0u);
  EXPECT_EQ(s->last_t_ns, 20'000'000'000u);
  const harness::MemorySink& a = plain.memory();
  const harness::MemorySink& b = wrapped.memory();
  ASSERT_EQ(a.rows(), b.rows());
  for (uint64_t r = 0; r < a.rows(); ++r)
    for (size_t c = 0; c < a.num_columns(); ++c) ASSERT_EQ(a.at(r, c), b.at(r, c)) << r << " " << a.columns()[c].name;
  EXPECT_NE(wrapped.dataflow().to_dot().find("spy around"), std::string::npos);
}

TEST(Endpoint, ALinkFailureStopsTheRunAndKeepsItsRows)
{
  const harness::Scenario sc = short_s1();
  harness::RunConfig cfg;
  cfg.fsw = std::make_unique<Flaky>(harness::fsw_acs_config_of(sc), 50);  // 50 cycles: t = 0 .. 4.9 s
  harness::Run run(sc, std::move(cfg));
  EXPECT_FALSE(run.step_ticks(run.total_ticks()));
  EXPECT_TRUE(run.done());
  EXPECT_NE(run.failure().find("no answer from the flight computer"), std::string::npos) << run.failure();
  EXPECT_NE(run.failure().find("t = 5"), std::string::npos) << run.failure();
  // rows of t = 0 .. 4.9 s recorded (10 Hz), handed to the sink at the failure
  EXPECT_EQ(run.memory().rows(), 50u);
  EXPECT_FALSE(run.memory().complete());
}

// Device parameters change between steps without rebuilding the run: a wheel
// switched off mid-run holds zero torque from then on, the others go on.
TEST(Endpoint, ThePlantsDevicesChangeBetweenSteps)
{
  harness::Run run(short_s1());
  ASSERT_TRUE(run.step_ticks(100));  // 5 s
  run.plant().set_wheel_health(2, sim::WheelHealth::Off);
  ASSERT_TRUE(run.step_ticks(run.total_ticks()));
  const auto t = run.memory().column("t");
  const auto u2 = run.memory().column("wheel_torque_2");
  const auto u0 = run.memory().column("wheel_torque_0");
  double before = 0.0, after = 0.0, other = 0.0;
  for (size_t r = 0; r < t.size(); ++r) {
    if (t[r] < 5.0) before = std::max(before, std::fabs(u2[r]));
    if (t[r] >= 5.0) after = std::max(after, std::fabs(u2[r]));
    if (t[r] >= 5.0) other = std::max(other, std::fabs(u0[r]));
  }
  EXPECT_GT(before, 1e-4);  // the wheel was working (S1 acquires from a tumble)
  EXPECT_EQ(after, 0.0);
  EXPECT_GT(other, 1e-4);
}
