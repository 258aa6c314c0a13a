// Cost of one sim::Plant step without thrusters or tanks (one RK4 step,
// 4 derivative evaluations, §7.1).  Counters:
//   us_per_step   thread-CPU microseconds per step (us_per_step_wall: wall clock)
//   RTF_dt0.01    simulated seconds per wall second at dt = 0.01 s
//   RTF_dt0.1     same at dt = 0.1 s
// The step cost does not depend on dt (fixed-step RK4), so the real-time
// factor is dt / (time per step).  Issue 6 target: <= 5 us per step for the
// hub with 4 fully-coupled wheels; issue 20 goal: <= 1.5 us.
//   BM_Derivative_*: one derivative evaluation (us_per_derivative).
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "sim/plant.h"
#include "sim/units.h"
#include "s1_wheel.h"

namespace {

double thread_cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

sim::SpacecraftParams vehicle(int num_rw, sim::WheelModel model)
{
  sim::SpacecraftParams p;  // scenario S1 hub and pyramid, LEO gravity on
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Eigen::Vector3d(900.0, 800.0, 600.0).asDiagonal();
  p.hub.r_BcB_B = Eigen::Vector3d(0.0, 0.0, 0.1);
  p.mu = sim::kMuEarth;
  for (int i = 0; i < num_rw; ++i) {
    sim::ReactionWheelParams w = s1_wheel(i, model);
    w.Omega_0 = sim::rad_s_from_rpm(100.0 * (i + 1));
    w.friction.tau_c = 5e-4;
    p.wheels.push_back(w);
  }
  return p;
}

// The vehicle in LEO with wheel torques latched.
std::unique_ptr<sim::Plant> make_plant(int num_rw, sim::WheelModel model)
{
  sim::InitialConditions ic;
  ic.r_CN_N = Eigen::Vector3d(-4020338.690396649, 7490566.741852513, 5248299.211589362);
  ic.v_CN_N = Eigen::Vector3d(-5199.77710904224, -3436.681645356935, 1041.576797498721);
  ic.sigma_BN = Eigen::Vector3d(0.1, 0.2, -0.3);
  ic.omega_BN_B = Eigen::Vector3d(0.001, -0.01, 0.03);
  auto sc = std::make_unique<sim::Plant>(sim::PlantParams{vehicle(num_rw, model), {}}, ic);
  sc->latch_wheel_commands(sim::WheelArray{0.01, -0.01, 0.005, -0.005});
  return sc;
}

void run(benchmark::State& state, int num_rw, sim::WheelModel model)
{
  const auto plant = make_plant(num_rw, model);
  sim::Plant& sc = *plant;
  const double cpu0 = thread_cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    sc.step(1'000'000);  // 1 ms; the cost per step is independent of dt
    benchmark::DoNotOptimize(sc.state().data());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = thread_cpu_seconds() - cpu0;
  const double n = static_cast<double>(state.iterations());
  // Thread CPU time is the figure to quote on a shared machine; wall time
  // also counts time lost to other processes.
  const double t_step = cpu / n;  // [s]
  state.counters["us_per_step"] = t_step * 1e6;
  state.counters["us_per_step_wall"] = wall / n * 1e6;
  state.counters["RTF_dt_0.01s"] = 0.01 / t_step;
  state.counters["RTF_dt_0.1s"] = 0.1 / t_step;
}

// One derivative evaluation (the step makes four, plus the RK4 sums and the
// per-step device work), at the state after 1 s of steps: rotor angles of
// tens of radians, as in a run (at theta = 0 sin and cos return at once).
void derivative(benchmark::State& state, int num_rw, sim::WheelModel model)
{
  const auto plant = make_plant(num_rw, model);
  sim::Plant& sc = *plant;
  for (int k = 0; k < 1000; ++k) sc.step(1'000'000);  // rotor angles away from 0 (sin/cos's fast path)
  sim::StateVector x = sc.state();
  const double cpu0 = thread_cpu_seconds();
  for (auto _ : state) {
    const sim::StateVector xd = sc.derivatives(0.0, x);
    benchmark::DoNotOptimize(xd.data());
    x(sim::StateLayout::omega_BN_B) += 1e-12 * xd(sim::StateLayout::omega_BN_B);  // a new state each time
  }
  state.counters["us_per_derivative"] = (thread_cpu_seconds() - cpu0) / static_cast<double>(state.iterations()) * 1e6;
}

void BM_Derivative_Hub4FullyCoupled(benchmark::State& s) { derivative(s, 4, sim::WheelModel::FullyCoupled); }
void BM_Derivative_Hub4SimpleJitter(benchmark::State& s) { derivative(s, 4, sim::WheelModel::SimpleJitter); }
void BM_Derivative_Hub4Balanced(benchmark::State& s) { derivative(s, 4, sim::WheelModel::Balanced); }
void BM_Derivative_HubOnly(benchmark::State& s) { derivative(s, 0, sim::WheelModel::Balanced); }

void BM_Rk4Step_Hub4FullyCoupled(benchmark::State& s) { run(s, 4, sim::WheelModel::FullyCoupled); }
void BM_Rk4Step_Hub4SimpleJitter(benchmark::State& s) { run(s, 4, sim::WheelModel::SimpleJitter); }
void BM_Rk4Step_Hub4Balanced(benchmark::State& s) { run(s, 4, sim::WheelModel::Balanced); }
void BM_Rk4Step_HubOnly(benchmark::State& s) { run(s, 0, sim::WheelModel::Balanced); }

}  // namespace

BENCHMARK(BM_Rk4Step_Hub4FullyCoupled);
BENCHMARK(BM_Rk4Step_Hub4SimpleJitter);
BENCHMARK(BM_Rk4Step_Hub4Balanced);
BENCHMARK(BM_Rk4Step_HubOnly);
BENCHMARK(BM_Derivative_Hub4FullyCoupled);
BENCHMARK(BM_Derivative_Hub4SimpleJitter);
BENCHMARK(BM_Derivative_Hub4Balanced);
BENCHMARK(BM_Derivative_HubOnly);
BENCHMARK_MAIN();
