// Cost of the thruster model per plant step with 8 ACS thrusters (scenario
// S2 layout, docs/dynamics.md §11), dt = 0.01 s, T_upd = 0.1 s.
//   BM_ThrusterEffects8     the pure §5.4 evaluation of 8 thrusters (one
//                           derivative call's worth; RK4 makes 4 per sub-step)
//   BM_VehicleStep/...      one Plant::step (RK4, event splitting, tank):
//     NoThrusters           hub + tank only: the baseline
//     Idle8                 8 FirstOrder thrusters, never commanded
//     Pulsing8FirstOrder    8 FirstOrder thrusters re-commanded every 0.1 s
//                           with on-times that close inside steps (each
//                           closing adds one RK4 sub-step)
//     Pulsing8Table         same with Table ramps (breakpoints split too)
//   Counter us_per_step: CPU microseconds per 0.01 s step (Google Benchmark
//   rate counters use CPU time), averaged over whole command periods;
//   sub_steps_per_step counts the RK4 sub-steps event splitting creates.
//   Thruster cost = Pulsing8* - NoThrusters.
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <benchmark/benchmark.h>

#include "sim/thruster.h"
#include "sim/units.h"
#include "sim/plant.h"

namespace {

using Eigen::Vector3d;

std::vector<sim::ThrusterParams> s2_acs(sim::ThrusterTransient model)
{
  const double x1 = 0.8255, y1 = 0.8803, z_hi = 1.7653, z_lo = 0.2604;
  const Vector3d pos[8] = {{x1, y1, z_hi},   {x1, y1, z_lo},   {y1, x1, z_hi},   {y1, x1, z_lo},
                           {-x1, -y1, z_hi}, {-x1, -y1, z_lo}, {-y1, -x1, z_hi}, {-y1, -x1, z_lo}};
  const Vector3d dir[8] = {-Vector3d::UnitY(), -Vector3d::UnitY(), -Vector3d::UnitX(), -Vector3d::UnitX(),
                           Vector3d::UnitY(),  Vector3d::UnitY(),  Vector3d::UnitX(),  Vector3d::UnitX()};
  std::vector<sim::ThrusterParams> out;
  for (int j = 0; j < 8; ++j) {
    sim::ThrusterParams t;
    t.r_TjB_B = pos[j];
    t.t_hat_B = dir[j];
    t.F_max = 22.0;
    t.Isp = 229.5;
    t.T_min = 0.020;
    t.transient = model;
    t.omega_on = t.omega_off = 10.0;
    t.on_ramp = {{0.0, 0.0}, {0.01, 0.3}, {0.03, 1.0}};
    t.off_ramp = {{0.0, 1.0}, {0.02, 0.2}, {0.05, 0.0}};
    t.tank = 0;
    out.push_back(t);
  }
  return out;
}

sim::SpacecraftParams s2_hub()
{
  sim::SpacecraftParams p;
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Vector3d(900.0, 800.0, 600.0).asDiagonal();
  p.mu = sim::kMuMars;
  return p;
}

sim::PropulsionParams s2_prop(int n_thr, sim::ThrusterTransient model)
{
  sim::PropulsionParams p;
  auto acs = s2_acs(model);
  p.thrusters.assign(acs.begin(), acs.begin() + n_thr);
  p.tanks.resize(1);
  p.tanks[0].r_TB_B = Vector3d(0.0, 0.0, 0.2);
  p.tanks[0].m_p0 = 400.0;
  p.command.T_upd_ns = 100'000'000;
  return p;
}

sim::InitialConditions s2_ic()
{
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(3896190.0, 0.0, 0.0);
  ic.v_CN_N = Vector3d(0.0, 5300.0, 0.0);
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  ic.omega_BN_B = Vector3d(0.001, -0.002, 0.003);
  return ic;
}

void BM_ThrusterEffects8(benchmark::State& state)
{
  const auto thr = s2_acs(sim::ThrusterTransient::FirstOrder);
  std::array<double, 8> kappa{0.1, 0.9, 0.5, 0.0, 1.0, 0.3, 0.7, 0.2};
  for (auto _ : state) {
    Vector3d F = Vector3d::Zero(), L = Vector3d::Zero();
    double mdot = 0.0;
    for (int j = 0; j < 8; ++j) {
      const sim::ThrusterEffect e = sim::thruster_effect(thr[static_cast<size_t>(j)], kappa[static_cast<size_t>(j)]);
      F += e.F_B;
      L += e.L_B;
      mdot += e.mdot;
    }
    benchmark::DoNotOptimize(F);
    benchmark::DoNotOptimize(L);
    benchmark::DoNotOptimize(mdot);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ThrusterEffects8);

enum class Case { NoThrusters, Idle8, Pulsing8FirstOrder, Pulsing8Table };

void BM_VehicleStep(benchmark::State& state, Case c)
{
  const bool any = c != Case::NoThrusters;
  const auto model = c == Case::Pulsing8Table ? sim::ThrusterTransient::Table : sim::ThrusterTransient::FirstOrder;
  sim::Plant v({s2_hub(), s2_prop(any ? 8 : 0, model)}, s2_ic());
  const bool pulse = c == Case::Pulsing8FirstOrder || c == Case::Pulsing8Table;
  // On-times 25..95 ms: every closing falls inside a 10 ms step.
  const sim::ThrusterArray cmd{0.025, 0.0437, 0.0513, 0.0621, 0.0705, 0.0788, 0.0852, 0.0949};
  constexpr int64_t dt_ns = 10'000'000;
  int64_t steps = 0;
  for (auto _ : state) {
    for (int k = 0; k < 10; ++k) {  // one command period
      if (pulse && k == 0) v.command_thrusters(cmd);
      if (v.step(dt_ns) != sim::StepStatus::Ok) state.SkipWithError("step failed");
    }
    steps += 10;
  }
  state.counters["us_per_step"] = benchmark::Counter(
      static_cast<double>(steps) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["sub_steps_per_step"] =
      static_cast<double>(steps + static_cast<int64_t>(v.counters().split_sub_steps)) / static_cast<double>(steps);
}
BENCHMARK_CAPTURE(BM_VehicleStep, NoThrusters, Case::NoThrusters);
BENCHMARK_CAPTURE(BM_VehicleStep, Idle8, Case::Idle8);
BENCHMARK_CAPTURE(BM_VehicleStep, Pulsing8FirstOrder, Case::Pulsing8FirstOrder);
BENCHMARK_CAPTURE(BM_VehicleStep, Pulsing8Table, Case::Pulsing8Table);

}  // namespace

BENCHMARK_MAIN();
