// On/off thrusters (docs/dynamics.md §5.1-§5.4, §7.3): config rejection,
// latch rule (saturation, minimum on-time, timer resolution, latch timing),
// ramp tables, force/torque/mass flow by hand, and delivered impulses against
// closed-form integrals of the Instant, FirstOrder and Table transients, with
// valve closings inside steps (step splitting) and on step boundaries.
//
// Impulse measurement: a thruster on the z axis pushing along +z through the
// mass centre (r x F = 0 exactly, attitude fixed), no tank (tank = -1, mass
// constant), gravity off.  Then m v_z(t) = F_max * integral(kappa) exactly,
// and RK4 reproduces that integral to round-off whenever kappa is constant or
// linear on every sub-step (Instant, Table).  For FirstOrder with
// omega_on = omega_off = w, I(t) = m v_z / F_max + kappa / w has dI/dt = v(t)
// (valve state); RK4 preserves linear invariants exactly, so I = T_on to
// round-off at all times after the pulse.  (Since the first-order factor is
// advanced in closed form with an RK4-exact quadrature correction, kappa and
// the impulse are each exact too; ThrusterClosedForm below checks that.)
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/attitude.h"
#include "sim/thruster.h"
#include "sim/plant.h"

namespace {
std::atomic<long> g_news{0};
}

// Counting allocator: proves Plant::step with thrusters allocates nothing (docs/dynamics.md §13).
// GCC pairs the inlined malloc in operator new with the free in operator
// delete and warns about a mismatch that is intended here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t n)
{
  g_news.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kMass = 500.0;  // [kg] hub mass of the test vehicle
constexpr int64_t kMs = 1'000'000;  // [ns]

sim::SpacecraftParams test_hub()
{
  sim::SpacecraftParams p;
  p.hub.m_h = kMass;
  p.hub.I_hBc_B = Vector3d(100.0, 120.0, 80.0).asDiagonal();
  return p;
}

// Thruster on the z axis, pushing +z through the CoM (B = C).
sim::ThrusterParams axial(sim::ThrusterTransient model)
{
  sim::ThrusterParams t;
  t.r_TjB_B = Vector3d(0.0, 0.0, -1.5);
  t.t_hat_B = Vector3d::UnitZ();
  t.F_max = 22.0;
  t.Isp = 229.5;
  t.T_min = 0.02;
  t.transient = model;
  t.tank = -1;
  t.on_ramp = {{0.0, 0.0}, {0.01, 0.3}, {0.03, 1.0}};
  t.off_ramp = {{0.0, 1.0}, {0.02, 0.2}, {0.05, 0.0}};
  return t;
}

sim::PropulsionParams one_thruster(const sim::ThrusterParams& t, int64_t T_upd_ns = 100 * kMs)
{
  sim::PropulsionParams p;
  p.thrusters = {t};
  p.command.T_upd_ns = T_upd_ns;
  return p;
}

sim::ThrusterArray req(double T)
{
  sim::ThrusterArray a{};
  a[0] = T;
  return a;
}

// Delivered impulse / F_max [s] of thruster 0 from the body's momentum.
double impulse_time(const sim::Plant& v, double F_max)
{
  return kMass * v.v_BN_N().z() / F_max;
}

// Trapezoid area of a piecewise-linear ramp from table time a to b (test-side).
double ramp_area(const std::vector<sim::RampPoint>& r, double a, double b)
{
  const auto f = [&r](double t) {
    if (t <= r.front().t) return r.front().f;
    if (t >= r.back().t) return r.back().f;
    for (size_t i = 1; i < r.size(); ++i)
      if (t <= r[i].t)
        return r[i - 1].f + (r[i].f - r[i - 1].f) * (t - r[i - 1].t) / (r[i].t - r[i - 1].t);
    return r.back().f;
  };
  std::vector<double> knots = {a};
  for (const auto& q : r)
    if (q.t > a && q.t < b) knots.push_back(q.t);
  knots.push_back(b);
  double area = 0.0;
  for (size_t i = 1; i < knots.size(); ++i)
    area += 0.5 * (f(knots[i - 1]) + f(knots[i])) * (knots[i] - knots[i - 1]);
  return area;
}

// ------------------------------------------------------------- config checks

struct BadThruster {
  const char* field;
  std::function<void(sim::ThrusterParams&)> spoil;
};

TEST(ThrusterConfig, RejectsEachBadFieldByName)
{
  const std::vector<BadThruster> rows = {
      {"t_hat_B", [](sim::ThrusterParams& t) { t.t_hat_B = Vector3d(0.0, 0.0, 1.1); }},
      {"r_TjB_B", [](sim::ThrusterParams& t) { t.r_TjB_B.x() = NAN; }},
      {"F_max", [](sim::ThrusterParams& t) { t.F_max = 0.0; }},
      {"Isp", [](sim::ThrusterParams& t) { t.Isp = -1.0; }},
      {"T_min", [](sim::ThrusterParams& t) { t.T_min = -0.01; }},
      {"omega_on", [](sim::ThrusterParams& t) { t.omega_on = 0.0; }},
      {"omega_off", [](sim::ThrusterParams& t) { t.omega_off = INFINITY; }},
      {"tank", [](sim::ThrusterParams& t) { t.tank = -2; }},
      {"dispersion", [](sim::ThrusterParams& t) { t.dispersion = -1.0; }},
      {"tau_sw", [](sim::ThrusterParams& t) { t.tau_sw = NAN; }},
      {"on_ramp[0].f", [](sim::ThrusterParams& t) {
         t.transient = sim::ThrusterTransient::Table;
         t.on_ramp[0].f = 0.1;
       }},
      {"on_ramp[2].f", [](sim::ThrusterParams& t) {
         t.transient = sim::ThrusterTransient::Table;
         t.on_ramp = {{0.0, 0.0}, {0.01, 0.5}, {0.02, 0.4}, {0.03, 1.0}};
       }},
      {"off_ramp[1].t", [](sim::ThrusterParams& t) {
         t.transient = sim::ThrusterTransient::Table;
         t.off_ramp[1].t = 0.0;
       }},
      {"off_ramp.back().f", [](sim::ThrusterParams& t) {
         t.transient = sim::ThrusterTransient::Table;
         t.off_ramp.back().f = 0.1;
       }},
  };
  for (const auto& row : rows) {
    sim::ThrusterParams t = axial(sim::ThrusterTransient::FirstOrder);
    row.spoil(t);
    try {
      sim::validate(t, "thr");
      ADD_FAILURE() << "accepted bad " << row.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("thr.") + row.field), std::string::npos)
          << e.what();
    }
  }
  // A good thruster of every model passes.
  for (auto m : {sim::ThrusterTransient::Instant, sim::ThrusterTransient::FirstOrder,
                 sim::ThrusterTransient::Table})
    EXPECT_NO_THROW(sim::validate(axial(m), "thr"));
}

TEST(ThrusterConfig, RejectsBadCommandSettingsAndTankIndex)
{
  const auto expect_throw = [](sim::PropulsionParams p, const std::string& field) {
    try {
      sim::Plant m({test_hub(), std::move(p)}, sim::InitialConditions{});
      ADD_FAILURE() << "accepted bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  sim::PropulsionParams p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.command.T_upd_ns = 0;
  expect_throw(p, "command.T_upd_ns");
  p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.command.T_sat = 0.0;
  expect_throw(p, "command.T_sat");
  p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.command.T_q = -1e-3;
  expect_throw(p, "command.T_q");
  p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.command.kappa_idle = 1.0;
  expect_throw(p, "command.kappa_idle");
  p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.thrusters[0].tank = 0;  // no tanks configured
  expect_throw(p, "thrusters[0].tank");
  p = one_thruster(axial(sim::ThrusterTransient::Instant));
  p.thrusters.assign(sim::kMaxThrusters + 1, axial(sim::ThrusterTransient::Instant));
  expect_throw(p, "thrusters.size()");
}

// ------------------------------------------------------------ tables, latch

TEST(ThrusterTable, ValueAndEntryTimeByHand)
{
  const auto t = axial(sim::ThrusterTransient::Table);
  EXPECT_DOUBLE_EQ(sim::ramp_value(t.on_ramp, 0.005), 0.15);
  EXPECT_DOUBLE_EQ(sim::ramp_value(t.on_ramp, 0.02), 0.65);
  EXPECT_EQ(sim::ramp_value(t.on_ramp, 1.0), 1.0);
  EXPECT_EQ(sim::ramp_value(t.off_ramp, -1.0), 1.0);
  EXPECT_DOUBLE_EQ(sim::ramp_value(t.off_ramp, 0.035), 0.1);
  // entry: on-ramp reaches 0.65 at 0.02; off-ramp falls to 0.6 at 0.01, to 0.1 at 0.035
  EXPECT_NEAR(sim::ramp_entry_time(t.on_ramp, 0.65, true), 0.02, 1e-17);
  EXPECT_NEAR(sim::ramp_entry_time(t.off_ramp, 0.6, false), 0.01, 1e-17);
  EXPECT_NEAR(sim::ramp_entry_time(t.off_ramp, 0.1, false), 0.035, 1e-17);
  EXPECT_EQ(sim::ramp_entry_time(t.on_ramp, 0.0, true), 0.0);
  EXPECT_EQ(sim::ramp_entry_time(t.off_ramp, 0.0, false), 0.05);
}

TEST(ThrusterLatch, SaturationMinOnTimeResolutionAndClose)
{
  sim::ThrusterParams p = axial(sim::ThrusterTransient::FirstOrder);  // T_min = 0.02
  sim::ThrusterCommandParams c;                                        // T_upd = 0.1 s
  sim::ValveSchedule s = sim::initial_schedule(p);

  // 1. saturation: 0.5 s clips to T_sat = T_upd
  EXPECT_EQ(sim::latch_thruster(p, c, 0.5, 0, 0.0, false, s), sim::LatchResult::Scheduled);
  EXPECT_EQ(s.T_on, 0.1);
  c.T_sat = std::numeric_limits<double>::infinity();
  sim::latch_thruster(p, c, 0.5, 0, 0.0, false, s);
  EXPECT_EQ(s.T_on, 0.5);
  c.T_sat.reset();

  // 2. minimum on-time: ignored on an idle thruster, schedule untouched ...
  s = sim::initial_schedule(p);
  EXPECT_EQ(sim::latch_thruster(p, c, 0.01, 7, 0.0, false, s), sim::LatchResult::IgnoredMinOnTime);
  EXPECT_EQ(s.T_on, 0.0);
  EXPECT_EQ(s.t_latch_ns, 0);
  // ... also while kappa is still decaying but below kappa_idle (1e-3) ...
  EXPECT_EQ(sim::latch_thruster(p, c, 0.01, 7, 0.9e-3, false, s), sim::LatchResult::IgnoredMinOnTime);
  // ... but a truncation of a firing thruster (valve open, or kappa above idle)
  EXPECT_EQ(sim::latch_thruster(p, c, 0.01, 7, 0.5, true, s), sim::LatchResult::Scheduled);
  EXPECT_EQ(s.T_on, 0.01);
  EXPECT_EQ(s.t_latch_ns, 7);
  EXPECT_EQ(sim::latch_thruster(p, c, 0.01, 9, 0.2, false, s), sim::LatchResult::Scheduled);

  // T = 0 always closes; NaN and negative requests count as 0
  EXPECT_EQ(sim::latch_thruster(p, c, 0.0, 11, 0.0, false, s), sim::LatchResult::Scheduled);
  EXPECT_EQ(s.T_on, 0.0);
  s.T_on = 0.05;
  sim::latch_thruster(p, c, NAN, 12, 1.0, true, s);
  EXPECT_EQ(s.T_on, 0.0);
  s.T_on = 0.05;
  sim::latch_thruster(p, c, -1.0, 13, 1.0, true, s);
  EXPECT_EQ(s.T_on, 0.0);

  // 4. timer resolution floors the on-time after the T_min check
  c.T_q = 0.004;
  sim::latch_thruster(p, c, 0.0537, 14, 0.0, false, s);
  EXPECT_NEAR(s.T_on, 0.052, 1e-17);
}

TEST(ThrusterEffect, ForceTorqueAboutBAndMassFlowByHand)
{
  sim::ThrusterParams p = axial(sim::ThrusterTransient::Instant);
  p.r_TjB_B = Vector3d(0.8255, 0.8803, 1.7653);
  p.t_hat_B = Vector3d(0.0, -1.0, 0.0);
  p.tau_sw = 0.3;
  p.dispersion = 0.05;
  const double kappa = 0.4;
  const sim::ThrusterEffect e = sim::thruster_effect(p, kappa);
  const double F = 22.0 * 0.4 * 1.05;  // 9.24 N
  // r x (0, -F, 0) = (-r_z*(-F), 0, r_x*(-F)) ; swirl kappa*tau_sw along t_hat
  EXPECT_NEAR((e.F_B - Vector3d(0.0, -F, 0.0)).norm(), 0.0, 1e-14);
  const Vector3d L_true(1.7653 * F, -0.4 * 0.3, -0.8255 * F);
  EXPECT_NEAR((e.L_B - L_true).norm(), 0.0, 1e-13);
  EXPECT_NEAR(e.mdot, F / (9.80665 * 229.5), 1e-18);
}

// Through the plant derivatives: hub at rest, B = C, kappa = 1 ->
// omega_dot = I^-1 (r x F + tau_sw t_hat), r_ddot = F t_hat / m.  The valve
// is opened by a StuckOn health (an Instant thruster is then at kappa = 1).
TEST(ThrusterEffect, PlantDerivativesApplyTorqueAboutB)
{
  sim::ThrusterParams p = axial(sim::ThrusterTransient::Instant);
  p.r_TjB_B = Vector3d(0.3, -0.2, 1.0);
  p.t_hat_B = Vector3d(1.0, 0.0, 0.0);
  p.tau_sw = 0.5;
  sim::Plant m({test_hub(), one_thruster(p)}, sim::InitialConditions{});
  m.set_thruster_health(0, sim::ThrusterHealth::StuckOn);
  EXPECT_EQ(m.kappa(0), 1.0);
  sim::Accelerations acc;
  m.derivatives(0.0, m.state(), &acc);
  // r x (22,0,0) = (0, 1.0*22, 0.2*22); + 0.5 x-hat
  const Vector3d L(0.5, 22.0, 4.4);
  const Vector3d wdot(L.x() / 100.0, L.y() / 120.0, L.z() / 80.0);
  EXPECT_NEAR((acc.omega_dot_BN_B - wdot).norm(), 0.0, 1e-15);
  EXPECT_NEAR((acc.r_ddot_BN_B - Vector3d(22.0 / kMass, 0.0, 0.0)).norm(), 0.0, 1e-16);
}

// A degraded thruster (Plant::set_thruster_thrust_scale, the event action
// thrust_factor): force, torque and mass flow all times s, so the derivatives
// of the test above are s times theirs; a pulse of T at s = 0.5 delivers the
// impulse of a T/2 pulse at full thrust; s = 1 restores it exactly; a
// negative or non-finite scale is refused with the field named.
TEST(ThrusterEffect, ThrustScaleScalesForceTorqueAndMassFlow)
{
  sim::ThrusterParams p = axial(sim::ThrusterTransient::Instant);
  p.r_TjB_B = Vector3d(0.3, -0.2, 1.0);
  p.t_hat_B = Vector3d(1.0, 0.0, 0.0);
  p.tau_sw = 0.5;
  sim::Plant m({test_hub(), one_thruster(p)}, sim::InitialConditions{});
  m.set_thruster_health(0, sim::ThrusterHealth::StuckOn);
  m.set_thruster_thrust_scale(0, 0.3);
  EXPECT_EQ(m.thrusters().thrust_scale(0), 0.3);
  EXPECT_EQ(m.kappa(0), 1.0);  // the valve is unchanged: the flow is reduced
  sim::Accelerations acc;
  m.derivatives(0.0, m.state(), &acc);
  const Vector3d L(0.5, 22.0, 4.4);  // as above, at full thrust
  const Vector3d wdot(L.x() / 100.0, L.y() / 120.0, L.z() / 80.0);
  EXPECT_NEAR((acc.omega_dot_BN_B - 0.3 * wdot).norm(), 0.0, 1e-15);
  EXPECT_NEAR((acc.r_ddot_BN_B - Vector3d(0.3 * 22.0 / kMass, 0.0, 0.0)).norm(), 0.0, 1e-16);
  EXPECT_NEAR(m.thruster_effect(0).mdot, 0.3 * 22.0 / (9.80665 * 229.5), 1e-18);
  m.set_thruster_thrust_scale(0, 1.0);
  m.derivatives(0.0, m.state(), &acc);
  EXPECT_NEAR((acc.omega_dot_BN_B - wdot).norm(), 0.0, 1e-15);
  for (double bad : {-0.1, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      m.set_thruster_thrust_scale(0, bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("thrusters[0].thrust_scale"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(m.thrusters().thrust_scale(0), 1.0);  // a refused value changes nothing

  // delivered impulse of a 0.0537 s pulse at half thrust
  sim::PropulsionParams pp = one_thruster(axial(sim::ThrusterTransient::Instant));
  pp.command.T_sat = std::numeric_limits<double>::infinity();
  sim::Plant v({test_hub(), pp}, sim::InitialConditions{});
  v.set_thruster_thrust_scale(0, 0.5);
  v.command_thrusters(req(0.0537));
  for (int k = 0; k < 20; ++k) EXPECT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
  EXPECT_NEAR(impulse_time(v, 22.0), 0.5 * 0.0537, 1e-12 * 0.0537);
}

// --------------------------------------------------------- delivered impulse

// Runs one pulse request of T_req at t = 0 and then `n` steps of dt.
sim::Plant run_pulse(const sim::ThrusterParams& t, double T_req, int64_t dt_ns, int n,
                       int64_t T_upd_ns = 100 * kMs)
{
  sim::PropulsionParams p = one_thruster(t, T_upd_ns);
  p.command.T_sat = std::numeric_limits<double>::infinity();
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  v.command_thrusters(req(T_req));
  for (int k = 0; k < n; ++k) EXPECT_EQ(v.step(dt_ns), sim::StepStatus::Ok);
  return v;
}

TEST(ThrusterImpulse, InstantPulseClosingInsideStepIsExact)  // THR-4 style
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  for (double T : {0.0537, 0.0213, 0.0999, 0.07}) {
    const sim::Plant v = run_pulse(t, T, 10 * kMs, 20);
    EXPECT_NEAR(impulse_time(v, t.F_max), T, 1e-12 * T) << "T_on = " << T;
    EXPECT_FALSE(v.valve_open(0));
  }
}

// Basilisk's per-stage gating adds F dt/6 when a cut-off lands on a step
// boundary (§7.3, THR-9).  Here T = 3 dt exactly: no extra impulse.
TEST(ThrusterImpulse, CutOffOnStepBoundaryHasNoStageGatingError)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  const sim::Plant v = run_pulse(t, 0.03, 10 * kMs, 10);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.03, 1e-12 * 0.03);
  // per-stage gating would have given 0.03 + 0.01/6
  EXPECT_GT(std::abs(impulse_time(v, t.F_max) - (0.03 + 0.01 / 6.0)), 1e-3);
}

TEST(ThrusterImpulse, FirstOrderEqualRatesLinearInvariantIsExact)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  const double w = 10.0;
  for (double T : {0.0537, 0.35}) {
    sim::PropulsionParams p = one_thruster(t);
    p.command.T_sat = std::numeric_limits<double>::infinity();
    sim::Plant v({test_hub(), p}, sim::InitialConditions{});
    v.command_thrusters(req(T));
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {  // 3 s; invariant = T_on from the close onward
      ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
      const double t_now = (k + 1) * 0.01;
      if (t_now > T) worst = std::max(worst, std::abs(impulse_time(v, t.F_max) + v.kappa(0) / w - T));
    }
    EXPECT_LT(worst, 1e-12 * T) << "T_on = " << T;
    // After 3 s (30 time constants, kappa ~ e^-27) the delivered impulse is F T.
    EXPECT_NEAR(impulse_time(v, t.F_max), T, 1e-11 * T);
  }
}

// kappa(t) against 1 - e^{-w t} and the off-ramp from the close value.
TEST(ThrusterImpulse, FirstOrderFactorMatchesClosedForm)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  t.omega_on = 10.0;
  t.omega_off = 25.0;
  const double T = 0.0537;  // closes inside a step
  sim::PropulsionParams p = one_thruster(t);
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  v.command_thrusters(req(T));
  const double k_close = 1.0 - std::exp(-10.0 * T);
  double worst = 0.0;
  for (int k = 1; k <= 300; ++k) {  // dt = 1 ms
    ASSERT_EQ(v.step(kMs), sim::StepStatus::Ok);
    const double tn = k * 1e-3;
    const double truth = tn < T ? 1.0 - std::exp(-10.0 * tn) : k_close * std::exp(-25.0 * (tn - T));
    worst = std::max(worst, std::abs(v.kappa(0) - truth));
  }
  EXPECT_LT(worst, 1e-14);  // closed form (project target §8 is 1e-9 absolute)
  // Delivered impulse: T - (1 - e^{-w_on T})/w_on + kappa_close/w_off (to kappa -> 0,
  // residual e^{-25*0.246} ~ 2e-3 of kappa_close counted via kappa/w_off).
  const double I_true = T - k_close / 10.0 + k_close / 25.0;
  EXPECT_NEAR(impulse_time(v, t.F_max) + v.kappa(0) / 25.0, I_true, 1e-10);
}

// The closed form of §5.3 for one FirstOrder pulse of on-time T from rest,
// at time s since the latch:
//   kappa = 1 - e^{-w_on s} (s < T),  kappa_T e^{-w_off (s - T)} (s >= T).
double first_order_pulse_kappa(double w_on, double w_off, double T, double s)
{
  const double k_T = 1.0 - std::exp(-w_on * T);
  return s < T ? -std::expm1(-w_on * s) : k_T * std::exp(-w_off * (s - T));
}

// Plant::derivatives evaluated between steps sees the thrusters as they are
// now, t seconds ahead in closed form (the state of "now" is formed only on
// such a call, not after every step): a FirstOrder thruster through the CoM
// (B = C, no tank) gives r_ddot_z = F_max kappa(t_now + t) / m with
//   kappa = 1 - e^{-w_on s} (s < T),  kappa_T e^{-w_off (s - T)} (s >= T),
// here 20 ms into a 53.7 ms pulse (at t = 0 and t = 10 ms ahead, the valve
// still open) and 80 ms in (closed, decaying), to 1e-13 relative.
TEST(ThrusterClosedForm, DerivativesBetweenStepsSeeTheThrustersNow)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  t.omega_on = 10.0;
  t.omega_off = 25.0;
  const double T = 0.0537;
  sim::Plant v({test_hub(), one_thruster(t)}, sim::InitialConditions{});
  v.command_thrusters(req(T));
  const auto kappa_true = [&](double s) { return first_order_pulse_kappa(10.0, 25.0, T, s); };
  const auto a_z = [&](double t_ahead) {
    sim::Accelerations acc;
    v.derivatives(t_ahead, v.state(), &acc);
    return acc.r_ddot_BN_B.z();
  };
  for (int k = 1; k <= 20; ++k) ASSERT_EQ(v.step(kMs), sim::StepStatus::Ok);
  for (double ahead : {0.0, 0.01}) {
    const double expect = t.F_max * kappa_true(0.02 + ahead) / kMass;
    EXPECT_NEAR(a_z(ahead), expect, 1e-13 * expect) << "ahead " << ahead;
  }
  for (int k = 21; k <= 80; ++k) ASSERT_EQ(v.step(kMs), sim::StepStatus::Ok);
  const double expect = t.F_max * kappa_true(0.08) / kMass;
  EXPECT_NEAR(a_z(0.0), expect, 1e-13 * expect);
}

// One firing with on and off transients (omega_on != omega_off, the close
// inside a step, w dt = 0.1 and 0.25: coarse for RK4) against the closed form
// of §5.3, at every step end:
//   kappa  = 1 - e^{-w_on t}                   (t < T)
//          = kappa_T e^{-w_off (t - T)}        (t >= T)
//   I(t)   = integral of kappa: t - (1 - e^{-w_on t}) / w_on, then
//            T - kappa_T / w_on + kappa_T (1 - e^{-w_off (t - T)}) / w_off.
// kappa, the force and the delivered impulse F_max I(t) (= m v_z, no tank)
// to 1e-12 relative; with a tank the propellant used equals F_max I / (g0 Isp)
// to 1e-12 relative.  (Integrating kappa as an RK4 state, as before, erred by
// (w dt)^5/120 relative per step: ~3e-9 at w dt = 0.05, ~8e-6 at w dt = 0.25.)
TEST(ThrusterClosedForm, FirstOrderFiringKappaForceImpulseAndPropellantAreExact)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  t.F_max = 10.0;
  t.omega_on = 10.0;
  t.omega_off = 25.0;
  const double T = 0.0537;
  const double k_T = 1.0 - std::exp(-10.0 * T);
  const auto kappa_true = [&](double tn) { return first_order_pulse_kappa(10.0, 25.0, T, tn); };
  const auto integral_true = [&](double tn) {
    return tn < T ? tn + std::expm1(-10.0 * tn) / 10.0
                  : T - k_T / 10.0 - k_T * std::expm1(-25.0 * (tn - T)) / 25.0;
  };
  for (bool with_tank : {false, true}) {
    sim::PropulsionParams p = one_thruster(t);
    if (with_tank) {
      p.thrusters[0].tank = 0;
      p.tanks.resize(1);
      p.tanks[0].r_TB_B = Vector3d(0.0, 0.0, 0.3);
      // small tank (1 g; 0.23 g are used) so that m_p0 - m_p resolves the use
      // to ~1e-14 relative (with kilograms, the ulp of m_p alone is 1e-12 of it)
      p.tanks[0].m_p0 = 1e-3;
    }
    sim::Plant v({test_hub(), p}, sim::InitialConditions{});
    v.command_thrusters(req(T));
    double worst_kappa = 0.0, worst_F = 0.0, worst_I = 0.0, worst_mp = 0.0;
    for (int k = 1; k <= 100; ++k) {  // 1 s = 25 off time constants
      ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
      const double tn = k * 0.01;
      const double kt = kappa_true(tn);
      const double It = integral_true(tn);
      worst_kappa = std::max(worst_kappa, std::abs(v.kappa(0) - kt) / kt);
      worst_F = std::max(worst_F, std::abs(v.thruster_effect(0).F_B.z() - 10.0 * kt) / (10.0 * kt));
      if (!with_tank) {
        worst_I = std::max(worst_I, std::abs(kMass * v.v_BN_N().z() - 10.0 * It) / (10.0 * It));
      } else {
        const double used = 10.0 * It / (sim::kG0 * t.Isp);
        worst_mp = std::max(worst_mp, std::abs((1e-3 - v.m_prop(0)) - used) / used);
        EXPECT_NEAR(v.thruster_effect(0).mdot, 10.0 * kt / (sim::kG0 * t.Isp), 1e-12 * 10.0 * kt / (sim::kG0 * t.Isp));
      }
    }
    EXPECT_LT(worst_kappa, 1e-12) << "tank " << with_tank;
    EXPECT_LT(worst_F, 1e-12) << "tank " << with_tank;
    EXPECT_LT(worst_I, 1e-12);
    EXPECT_LT(worst_mp, 1e-12);
  }
}

// Two FirstOrder thrusters with four different rates fire together, closing
// at different times inside steps: open-open, open-closed and closed-closed
// sub-steps each hold two distinct rates (the set forms its exponentials
// once per distinct rate and sub-step).  Each factor against its own closed
// form and the delivered impulse F1 I1 + F2 I2 to 1e-12 relative, at every
// step end.
TEST(ThrusterClosedForm, TwoThrustersWithDistinctRatesEachFollowTheirClosedForm)
{
  struct Firing {
    double F, w_on, w_off, T;
    double kappa(double tn) const
    {
      const double k_T = -std::expm1(-w_on * T);
      return tn < T ? -std::expm1(-w_on * tn) : k_T * std::exp(-w_off * (tn - T));
    }
    double integral(double tn) const
    {
      const double k_T = -std::expm1(-w_on * T);
      return tn < T ? tn + std::expm1(-w_on * tn) / w_on
                    : T - k_T / w_on - k_T * std::expm1(-w_off * (tn - T)) / w_off;
    }
  };
  const Firing f[2] = {{10.0, 10.0, 25.0, 0.0537}, {4.0, 40.0, 5.0, 0.0871}};
  sim::PropulsionParams p;
  for (const Firing& fi : f) {
    auto t = axial(sim::ThrusterTransient::FirstOrder);
    t.F_max = fi.F;
    t.omega_on = fi.w_on;
    t.omega_off = fi.w_off;
    p.thrusters.push_back(t);
  }
  p.command.T_upd_ns = 100 * kMs;
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  sim::ThrusterArray T{};
  T[0] = f[0].T;
  T[1] = f[1].T;
  v.command_thrusters(T);
  double worst_kappa[2] = {0.0, 0.0}, worst_I = 0.0;
  for (int k = 1; k <= 100; ++k) {
    ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
    const double tn = k * 0.01;
    for (int j = 0; j < 2; ++j) {
      const double kt = f[j].kappa(tn);
      worst_kappa[j] = std::max(worst_kappa[j], std::abs(v.kappa(j) - kt) / kt);
    }
    const double I = f[0].F * f[0].integral(tn) + f[1].F * f[1].integral(tn);
    worst_I = std::max(worst_I, std::abs(kMass * v.v_BN_N().z() - I) / I);
  }
  EXPECT_LT(worst_kappa[0], 1e-12);
  EXPECT_LT(worst_kappa[1], 1e-12);
  EXPECT_LT(worst_I, 1e-12);
}

// The closed form is the exact solution whatever the step: the factor after a
// pulse does not depend on dt (the RK4-integrated factor did, at 5th order).
TEST(ThrusterClosedForm, FirstOrderFactorIndependentOfStep)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  double kappa[3], I[3];
  const int64_t dts[3] = {kMs, 10 * kMs, 50 * kMs};
  for (int r = 0; r < 3; ++r) {
    const sim::Plant v = run_pulse(t, 0.0537, dts[r], static_cast<int>(200 * kMs / dts[r]));
    kappa[r] = v.kappa(0);
    I[r] = impulse_time(v, t.F_max);
  }
  for (int r = 1; r < 3; ++r) {
    EXPECT_NEAR(kappa[r], kappa[0], 1e-13 * kappa[0]);
    EXPECT_NEAR(I[r], I[0], 1e-13 * I[0]);
  }
}

// Position of a FirstOrder thruster fired from rest: the RK4 stages see the
// thrust factor so that both the impulse and the position of every sub-step
// are exact (thruster_set.h).  A 10 N thruster through the CoM along +z,
// omega_on = 10 rad/s, the valve open from t = 0 (T_sat off, 10 s request),
// x(t) = r_z at t = 3 s, at dt = 0.01 s (w dt = 0.1) to 0.1 s (w dt = 1).
// Without a tank (mass m constant), F kappa(t) / m with kappa = 1 - e^{-w t},
// integrated twice from x = v = 0:
//   v(t) = (F/m) [t - (1 - e^{-w t}) / w]
//   x(t) = (F/m) [t^2/2 - t/w + (1 - e^{-w t}) / w^2]
// (check: x'' = (F/m)(1 - e^{-w t}), x(0) = x'(0) = 0).
// With a tank at B (point mass: the CoM stays at B) the mass falls as
//   m(t) = m0 - F K(t) / (g0 Isp),  K(t) = t - (1 - e^{-w t}) / w,
// and m dv = F kappa dt = -g0 Isp dm gives the rocket equation
//   v(t) = g0 Isp ln(m0 / m(t)),  x(t) = integral of v from 0 to t,
// the last by 3-point Gauss-Legendre on 3000 panels here (error ~ h^6, far
// below 1e-15 of x).  Measured (x(3 s) relative error, dt = 0.01 / 0.025 /
// 0.05 / 0.1 s): without a tank 7e-16 / 3e-16 / 2e-16 / 2e-16, exact to
// rounding at any w dt; with the tank 2e-16 / 3e-14 / 1e-12 / 2.6e-11, which
// is RK4's own truncation of the mass coupling F kappa / m (the stage masses
// are RK4's, not m(t)), 4th order and more in dt, bounded here by
// max(1e-13, 1e-10 (dt / 0.1 s)^4).  With one constant correction per
// sub-step (impulse exact, position not) the errors were 3.3e-10 at
// dt = 0.01 s and 3.2e-6 at dt = 0.1 s, with or without the tank.
TEST(ThrusterClosedForm, FirstOrderFiringPositionIsExact)
{
  auto t = axial(sim::ThrusterTransient::FirstOrder);
  t.F_max = 10.0;
  t.omega_on = 10.0;
  t.r_TjB_B = Vector3d(0.0, 0.0, -1.5);
  const double F = 10.0, w = 10.0, t_end = 3.0, m_p0 = 20.0;
  const double c = F / (sim::kG0 * t.Isp);  // [kg/s] mass flow at kappa = 1
  const auto K = [&](double s) { return s + std::expm1(-w * s) / w; };
  const auto v_rocket = [&](double s) { return -sim::kG0 * t.Isp * std::log1p(-c * K(s) / (kMass + m_p0)); };
  double x_rocket = 0.0;  // 3-point Gauss-Legendre, 3000 panels on [0, t_end]
  {
    const int n = 3000;
    const double h = t_end / n, g = std::sqrt(0.6);
    for (int i = 0; i < n; ++i) {
      const double mid = (i + 0.5) * h;
      x_rocket += 0.5 * h * (5.0 / 9.0 * v_rocket(mid - 0.5 * h * g) + 8.0 / 9.0 * v_rocket(mid) +
                             5.0 / 9.0 * v_rocket(mid + 0.5 * h * g));
    }
  }
  const double x_const =
      F / kMass * (0.5 * t_end * t_end - t_end / w - std::expm1(-w * t_end) / (w * w));
  for (bool with_tank : {false, true}) {
    for (int64_t dt_ns : {10 * kMs, 25 * kMs, 50 * kMs, 100 * kMs}) {
      sim::PropulsionParams p = one_thruster(t);
      p.command.T_sat = std::numeric_limits<double>::infinity();
      if (with_tank) {
        p.thrusters[0].tank = 0;
        p.tanks.resize(1);
        p.tanks[0].m_p0 = m_p0;  // at B (r_TB_B = 0), a point mass
      }
      sim::Plant v({test_hub(), p}, sim::InitialConditions{});
      v.command_thrusters(req(10.0));
      const int n = static_cast<int>(3'000 * kMs / dt_ns);
      for (int k = 0; k < n; ++k) ASSERT_EQ(v.step(dt_ns), sim::StepStatus::Ok);
      const double x_true = with_tank ? x_rocket : x_const;
      const double err = std::abs(v.r_BN_N().z() - x_true) / x_true;
      std::printf("FirstOrder position x(3 s), %s, dt = %g s: x = %.17g m, relative error %.2g\n",
                  with_tank ? "tank (rocket equation)" : "no tank", dt_ns * 1e-9, v.r_BN_N().z(), err);
      const double dt_rel = static_cast<double>(dt_ns) / (100.0 * kMs);
      const double bound = with_tank ? std::max(1e-13, 1e-10 * std::pow(dt_rel, 4)) : 1e-13;
      EXPECT_LT(err, bound) << "tank " << with_tank << " dt_ns " << dt_ns;
    }
  }
}

TEST(ThrusterImpulse, TablePulseAndInterruptedRampAreExact)
{
  const auto t = axial(sim::ThrusterTransient::Table);
  // Full pulse: on-ramp to 1 at 0.03 s, plateau, close at T, full off-ramp.
  const double T = 0.0737;
  const sim::Plant v = run_pulse(t, T, 10 * kMs, 20);
  const double I_full = ramp_area(t.on_ramp, 0.0, T) + ramp_area(t.off_ramp, 0.0, 0.05);
  EXPECT_NEAR(I_full, 0.0145 + (T - 0.03) + 0.015, 1e-15);  // trapezoids by hand
  EXPECT_NEAR(impulse_time(v, t.F_max), I_full, 1e-12 * I_full);
  EXPECT_EQ(v.kappa(0), 0.0);

  // Interrupted on-ramp (T = 0.025 s, kappa_close = 0.3 + 0.7*0.75 = 0.825): the
  // off-ramp is entered where it equals 0.825, i.e. at 0.004375 s.
  const double T2 = 0.025;
  const sim::Plant v2 = run_pulse(t, T2, 10 * kMs, 20);
  const double k_close = 0.825;
  const double tau_off = (1.0 - k_close) / 40.0;
  EXPECT_NEAR(v2.schedule(0).tau_off0, tau_off, 1e-17);
  const double I_int = ramp_area(t.on_ramp, 0.0, T2) + ramp_area(t.off_ramp, tau_off, 0.05);
  EXPECT_NEAR(impulse_time(v2, t.F_max), I_int, 1e-12 * I_int);
}

TEST(ThrusterImpulse, TableKappaIsContinuousAcrossInterruptions)
{
  auto t = axial(sim::ThrusterTransient::Table);
  t.T_min = 0.0;
  sim::PropulsionParams p = one_thruster(t, 20 * kMs);  // latch every 20 ms
  p.command.T_sat = std::numeric_limits<double>::infinity();
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  double prev = 0.0, worst_jump = 0.0;
  // alternate 12 ms on-requests and idle periods; kappa moves <= 40/s * 1 ms per step
  for (int k = 0; k < 400; ++k) {
    if (k % 20 == 0) v.command_thrusters(req(((k / 20) % 3 == 2) ? 0.0 : 0.012));
    ASSERT_EQ(v.step(kMs), sim::StepStatus::Ok);
    worst_jump = std::max(worst_jump, std::abs(v.kappa(0) - prev));
    prev = v.kappa(0);
  }
  EXPECT_LE(worst_jump, 40.0 * 1e-3 + 1e-12);  // steepest table slope (0.8/0.02 s) * dt
}

// ----------------------------------------------------------- latch behaviour

TEST(ThrusterLatch, CommandsLatchOnlyAtPeriodAndLatestWins)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  sim::PropulsionParams p = one_thruster(t);  // T_upd = 100 ms, T_sat = T_upd
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  for (int k = 0; k < 3; ++k) v.step(10 * kMs);  // t = 30 ms
  v.command_thrusters(req(0.08));
  for (int k = 0; k < 4; ++k) v.step(10 * kMs);  // t = 70 ms
  EXPECT_FALSE(v.valve_open(0));                // not latched before 100 ms
  v.command_thrusters(req(0.045));              // replaces the 0.08 request
  for (int k = 0; k < 3; ++k) v.step(10 * kMs);  // t = 100 ms: latch
  EXPECT_EQ(v.counters().latches, 0u);
  v.step(10 * kMs);
  EXPECT_EQ(v.counters().latches, 1u);
  EXPECT_EQ(v.schedule(0).t_latch_ns, 100 * kMs);
  EXPECT_EQ(v.schedule(0).T_on, 0.045);
  for (int k = 0; k < 20; ++k) v.step(10 * kMs);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.045, 1e-12 * 0.045);
  EXPECT_EQ(v.counters().latches, 1u);  // no new message, no new latch
}

TEST(ThrusterLatch, LatchInstantInsideAStepSplitsTheStep)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  sim::PropulsionParams p = one_thruster(t, 25 * kMs);  // latch grid not a multiple of dt
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  v.step(10 * kMs);  // t = 10 ms: message arrives, next latch at 25 ms
  v.command_thrusters(req(0.02));
  for (int k = 0; k < 10; ++k) v.step(10 * kMs);
  EXPECT_EQ(v.schedule(0).t_latch_ns, 25 * kMs);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.02, 1e-12 * 0.02);
}

// A step longer than T_upd: the pending message is latched at the first
// latch instant inside the step, and only there.
TEST(ThrusterLatch, StepLongerThanCommandPeriod)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  sim::PropulsionParams p = one_thruster(t, 30 * kMs);
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  v.step(100 * kMs);
  v.command_thrusters(req(0.025));  // t = 100 ms; next latch instant 120 ms
  for (int k = 0; k < 3; ++k) v.step(100 * kMs);
  EXPECT_EQ(v.schedule(0).t_latch_ns, 120 * kMs);
  EXPECT_EQ(v.counters().latches, 1u);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.025, 1e-12 * 0.025);
  EXPECT_EQ(v.counters().split_sub_steps, 1u);  // the closing (latch cuts are not counted)
}

TEST(ThrusterLatch, ContinuousFiringAcrossPeriodsAndTruncation)
{
  auto t = axial(sim::ThrusterTransient::Instant);
  sim::Plant v({test_hub(), one_thruster(t)}, sim::InitialConditions{});
  // FSW asks 1.1 T_upd every period: T_sat = T_upd turns it into continuous firing.
  for (int k = 0; k < 100; ++k) {  // 1 s
    if (k % 10 == 0) v.command_thrusters(req(0.11));
    ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
    EXPECT_TRUE(v.valve_open(0) || k % 10 == 9);
  }
  EXPECT_NEAR(impulse_time(v, t.F_max), 1.0, 1e-12);
  // A short request (< T_min) on a firing thruster is a truncation, not ignored.
  v.command_thrusters(req(0.011));
  for (int k = 0; k < 10; ++k) v.step(10 * kMs);
  EXPECT_NEAR(impulse_time(v, t.F_max), 1.011, 1e-12);
  EXPECT_EQ(v.counters().ignored_min_on, 0u);
  // Now idle: the same short request is dropped (no pulse).
  v.command_thrusters(req(0.011));
  for (int k = 0; k < 10; ++k) v.step(10 * kMs);
  EXPECT_NEAR(impulse_time(v, t.F_max), 1.011, 1e-12);
  EXPECT_EQ(v.counters().ignored_min_on, 1u);
}

// The valve-open time the plant keeps (ThrusterSet::valve_open_time) by
// hand: a pulse a later latch cuts short counts to the cut, a stuck-open
// valve for as long as it is stuck, a valve failed off mid-pulse to the
// failure; with Instant thrust it equals the delivered impulse / F_max.
TEST(ThrusterLatch, ValveOpenTimeCountsCutStuckAndFailedPulses)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  sim::PropulsionParams p = one_thruster(t);  // T_upd = 100 ms
  p.command.T_sat = std::numeric_limits<double>::infinity();
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  auto steps = [&](int n) {
    for (int k = 0; k < n; ++k) ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
  };
  v.command_thrusters(req(0.25));  // latched at 0, open 0.25 s unless cut
  steps(5);                        // t = 50 ms
  EXPECT_NEAR(v.thrusters().valve_open_time(0), 0.05, 1e-15);
  v.command_thrusters(req(0.03));  // latched at 100 ms: the first pulse ends there
  steps(45);                       // t = 500 ms
  EXPECT_NEAR(v.thrusters().valve_open_time(0), 0.13, 1e-12);
  v.set_thruster_health(0, sim::ThrusterHealth::StuckOn);
  steps(20);                       // t = 700 ms
  v.set_thruster_health(0, sim::ThrusterHealth::Nominal);
  EXPECT_NEAR(v.thrusters().valve_open_time(0), 0.33, 1e-12);
  steps(5);                        // t = 750 ms
  v.command_thrusters(req(0.08));  // latched at 800 ms
  steps(8);                        // t = 830 ms
  v.set_thruster_health(0, sim::ThrusterHealth::FailedOff);
  v.command_thrusters(req(0.08));  // ignored by a failed valve
  steps(30);
  EXPECT_NEAR(v.thrusters().valve_open_time(0), 0.36, 1e-12);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.36, 1e-12);
}

TEST(ThrusterLatch, ValveTimerResolutionFloorsOnTime)
{
  const auto t = axial(sim::ThrusterTransient::Instant);
  sim::PropulsionParams p = one_thruster(t);
  p.command.T_q = 1e-3;
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  v.command_thrusters(req(0.0537));
  for (int k = 0; k < 10; ++k) v.step(10 * kMs);
  EXPECT_NEAR(impulse_time(v, t.F_max), 0.053, 1e-12 * 0.053);
}

// Halving dt leaves the delivered impulse unchanged (event splitting makes it
// independent of the grid) while attitude converges at 4th order.
TEST(ThrusterImpulse, OffAxisPulseImpulseIndependentOfStep)
{
  auto t = axial(sim::ThrusterTransient::Instant);
  t.r_TjB_B = Vector3d(0.0, 0.8, 0.0);  // torque about x
  t.t_hat_B = Vector3d::UnitZ();
  double H_x[2];
  for (int r = 0; r < 2; ++r) {
    const int64_t dt = r == 0 ? 10 * kMs : 5 * kMs;
    const sim::Plant v = run_pulse(t, 0.0537, dt, static_cast<int>(200 * kMs / dt));
    // About C (= B), torque-free after the pulse: H_C,N is constant and equals
    // the angular impulse.
    H_x[r] = v.energy_momentum().H_C_N.x();
  }
  // The rotation is about x only (diagonal inertia, torque along x), so the
  // torque stays along N's x axis and H_x = 0.8 F T exactly.
  const double H_true = 0.8 * 22.0 * 0.0537;
  EXPECT_NEAR(H_x[0], H_true, 1e-12 * H_true);
  EXPECT_NEAR(H_x[1], H_true, 1e-12 * H_true);
}

// --------------------------------------------------------------- no heap

TEST(ThrusterNoHeap, PlantStepWithThrustersDoesNotAllocate)
{
  sim::PropulsionParams p;
  for (auto m : {sim::ThrusterTransient::Instant, sim::ThrusterTransient::FirstOrder,
                 sim::ThrusterTransient::Table}) {
    auto t = axial(m);
    t.tank = 0;
    p.thrusters.push_back(t);
  }
  p.tanks.resize(1);
  p.tanks[0].m_p0 = 50.0;
  p.tanks[0].r_TB_B = Vector3d(0.0, 0.0, 0.2);
  sim::Plant v({test_hub(), p}, sim::InitialConditions{});
  sim::ThrusterArray cmd{0.0537, 0.03, 0.071};
  const long before = g_news.load();
  double sink = 0.0;
  for (int k = 0; k < 50; ++k) {
    if (k % 10 == 0) v.command_thrusters(cmd);
    ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
    sink += v.kappa(1) + v.thruster_effect(2).mdot + v.mass_props().m_sc;
  }
  EXPECT_EQ(g_news.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
  EXPECT_GT(v.counters().split_sub_steps, 0u);
}

}  // namespace
