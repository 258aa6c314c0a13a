// Cost of the environment effectors of sim::Plant (sim/environment_effectors.h,
// docs/environment.md "In the plant").  Counters:
//   eval/<model>_exact   CPU time per iteration = one load() with the
//                        environment evaluated (period_ns = 0: every RK4 stage)
//   eval/<model>_held    the same with the held environment (the part done
//                        once per plant step when period_ns > 0)
//   step/<model>_dt<dt>  us_per_sim_s: extra thread-CPU microseconds per
//                           simulated second for a plant stepping at
//                           dt = 0.1 s or 0.01 s with that effector at its
//                           default rate (or held 1 s), over the same plant
//                           without it
//   eval/J2              one sim::j2_acceleration (the plant evaluates it in
//                        every derivative when SpacecraftParams::J2 is set)
//   step/J2              us_per_sim_s at dt = 0.1 s, J2 on in the plant's gravity
// Vehicle: the S1 hub in a 400 km, 51.6 deg orbit, four balanced wheels,
// 8 facets (a 1 m box and a two-sided 4 m^2 panel), IGRF degree 13, one rod.
#include <cmath>
#include <memory>

#include <benchmark/benchmark.h>

#include "sim/environment_effectors.h"
#include "sim/units.h"
#include "s1_wheel.h"
#include "thread_cpu.h"

namespace {

using Eigen::Vector3d;

std::unique_ptr<sim::Plant> make_plant(bool j2 = false)
{
  sim::SpacecraftParams p;
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Vector3d(900.0, 800.0, 600.0).asDiagonal();
  p.hub.r_BcB_B = Vector3d(0.0, 0.0, 0.1);
  p.mu = sim::kMuEarth;
  if (j2) {
    p.J2 = sim::kJ2Earth;
    p.R_J2 = sim::kRadiusJ2Earth;
  }
  for (int i = 0; i < 4; ++i) {
    sim::ReactionWheelParams w = s1_wheel(i, sim::WheelModel::Balanced);
    w.Omega_0 = sim::rad_s_from_rpm(100.0 * (i + 1));
    p.wheels.push_back(w);
  }
  sim::InitialConditions ic;
  const double R = 6778e3, inc = sim::rad_from_deg(51.6), v = std::sqrt(sim::kMuEarth / R);
  ic.r_CN_N = Vector3d(R, 0.0, 0.0);
  ic.v_CN_N = v * Vector3d(0.0, std::cos(inc), std::sin(inc));
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  ic.omega_BN_B = Vector3d(0.001, -0.01, 0.03);
  return std::make_unique<sim::Plant>(sim::PlantParams{p, {}}, ic);
}

sim::EarthContext context()
{
  sim::EarthContextParams p;
  p.epoch = {2026, 3, 20, 12, 0, 0.0};
  return sim::EarthContext(p);
}

sim::FacetSet facets()
{
  sim::FacetSet s;
  for (int a = 0; a < 3; ++a)
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      sim::Facet& f = s.facets[static_cast<size_t>(s.count++)];
      f.area = 1.0;
      f.n_B = sgn * Vector3d::Unit(a);
      f.r_B = 0.5 * f.n_B;
      f.absorbed = 0.7;
      f.specular = 0.2;
      f.diffuse = 0.1;
    }
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    sim::Facet& f = s.facets[static_cast<size_t>(s.count++)];
    f.area = 4.0;
    f.n_B = sgn * Vector3d::UnitZ();
    f.r_B = Vector3d(0.0, 2.0, 0.0);
  }
  return s;
}

enum class Model { GravityGradient, SolarPressure, Drag, Magnetic };

// The effector with its default period, or with period_ns given (>= 0).
std::unique_ptr<sim::SampledEnvironmentEffector> make(Model m, const sim::Plant& plant, int64_t period_ns)
{
  const sim::EarthContext ctx = context();
  switch (m) {
    case Model::GravityGradient: {
      sim::GravityGradientParams p;
      if (period_ns >= 0) p.period_ns = period_ns;
      return std::make_unique<sim::GravityGradientEffector>(plant, ctx, p);
    }
    case Model::SolarPressure: {
      sim::SolarPressureParams p;
      p.facets = facets();
      if (period_ns >= 0) p.period_ns = period_ns;
      return std::make_unique<sim::SolarPressureEffector>(plant, ctx, p);
    }
    case Model::Drag: {
      sim::DragParams p;
      p.facets = facets();
      if (period_ns >= 0) p.period_ns = period_ns;
      return std::make_unique<sim::DragEffector>(plant, ctx, p);
    }
    case Model::Magnetic: {
      sim::MagneticParams p;
      p.m_residual_B = Vector3d(0.1, -0.2, 0.3);
      p.rods.resize(1);
      if (period_ns >= 0) p.period_ns = period_ns;
      auto e = std::make_unique<sim::MagneticEffector>(plant, ctx, p);
      e->command_dipoles({0.5});
      return e;
    }
  }
  return nullptr;
}

void eval(benchmark::State& state, Model m, bool held)
{
  auto plant = make_plant();
  auto e = make(m, *plant, held ? int64_t{1000000000} : int64_t{0});
  e->prepare_now(0);  // the held sample
  const sim::StateVector x = plant->state();
  double t = 0.0, sink = 0.0;
  for (auto _ : state) {
    const sim::BodyLoad l = e->load(t, x);
    sink += l.L_B.x();
    t += 1e-3;
    benchmark::DoNotOptimize(sink);
  }
}

// Thread-CPU seconds of n steps of dt_ns, with or without the effector
// (its default period, or period_ns >= 0).
double step_cost(Model m, bool with, int n, int64_t dt_ns, int64_t period_ns)
{
  auto plant = make_plant();
  if (with) plant->add_effector(make(m, *plant, period_ns));
  const double t0 = thread_cpu_seconds();
  for (int k = 0; k < n; ++k) plant->step(dt_ns);
  return thread_cpu_seconds() - t0;
}

// 200 simulated seconds per iteration at a plant step of dt_ns.
void step(benchmark::State& state, Model m, int64_t dt_ns, int64_t period_ns)
{
  const int n = static_cast<int>(200000000000LL / dt_ns);
  double with = 0.0, without = 0.0;
  for (auto _ : state) {
    with += step_cost(m, true, n, dt_ns, period_ns);
    without += step_cost(m, false, n, dt_ns, period_ns);
  }
  const double sim_s = 1e-9 * static_cast<double>(dt_ns) * n * static_cast<double>(state.iterations());
  state.counters["us_per_sim_s"] = 1e6 * (with - without) / sim_s;
  state.counters["us_per_sim_s_plant_alone"] = 1e6 * without / sim_s;
}

void j2_eval(benchmark::State& state)
{
  Vector3d r(4.1e6, -3.3e6, 4.6e6), sink = Vector3d::Zero();
  for (auto _ : state) {
    sink += sim::j2_acceleration(sim::kMuEarth, sim::kJ2Earth, sim::kRadiusJ2Earth, r);
    r.x() += 1.0;
    benchmark::DoNotOptimize(sink);
  }
}

double j2_step_cost(bool with, int n)
{
  auto plant = make_plant(with);
  const double t0 = thread_cpu_seconds();
  for (int k = 0; k < n; ++k) plant->step(100000000);
  return thread_cpu_seconds() - t0;
}

void j2_step(benchmark::State& state)
{
  const int n = 2000;
  double with = 0.0, without = 0.0;
  for (auto _ : state) {
    with += j2_step_cost(true, n);
    without += j2_step_cost(false, n);
  }
  const double sim_s = 0.1 * n * static_cast<double>(state.iterations());
  state.counters["us_per_sim_s"] = 1e6 * (with - without) / sim_s;
  state.counters["us_per_sim_s_plant_alone"] = 1e6 * without / sim_s;
}

}  // namespace

BENCHMARK_CAPTURE(eval, GravityGradient_exact, Model::GravityGradient, false);
BENCHMARK_CAPTURE(eval, GravityGradient_held, Model::GravityGradient, true);
BENCHMARK_CAPTURE(eval, SolarPressure_exact, Model::SolarPressure, false);
BENCHMARK_CAPTURE(eval, SolarPressure_held, Model::SolarPressure, true);
BENCHMARK_CAPTURE(eval, Drag_exact, Model::Drag, false);
BENCHMARK_CAPTURE(eval, Drag_held, Model::Drag, true);
BENCHMARK_CAPTURE(eval, Magnetic_exact, Model::Magnetic, false);
BENCHMARK_CAPTURE(eval, Magnetic_held, Model::Magnetic, true);
// at the default rates (gravity gradient every RK4 stage, the others 1 s), dt = 0.1 s and 0.01 s
BENCHMARK_CAPTURE(step, GravityGradient_dt0_1, Model::GravityGradient, 100000000, -1)->Iterations(10);
BENCHMARK_CAPTURE(step, SolarPressure_dt0_1, Model::SolarPressure, 100000000, -1)->Iterations(10);
BENCHMARK_CAPTURE(step, Drag_dt0_1, Model::Drag, 100000000, -1)->Iterations(10);
BENCHMARK_CAPTURE(step, Magnetic_dt0_1, Model::Magnetic, 100000000, -1)->Iterations(10);
BENCHMARK_CAPTURE(step, GravityGradient_dt0_01, Model::GravityGradient, 10000000, -1)->Iterations(3);
BENCHMARK_CAPTURE(step, SolarPressure_dt0_01, Model::SolarPressure, 10000000, -1)->Iterations(3);
BENCHMARK_CAPTURE(step, Drag_dt0_01, Model::Drag, 10000000, -1)->Iterations(3);
BENCHMARK_CAPTURE(step, Magnetic_dt0_01, Model::Magnetic, 10000000, -1)->Iterations(3);
// gravity gradient held 1 s (position and inertia), dt = 0.01 s
BENCHMARK_CAPTURE(step, GravityGradient_held1s_dt0_01, Model::GravityGradient, 10000000, 1000000000)->Iterations(3);

BENCHMARK(j2_eval)->Name("eval/J2");
BENCHMARK(j2_step)->Name("step/J2")->Iterations(20);

BENCHMARK_MAIN();
