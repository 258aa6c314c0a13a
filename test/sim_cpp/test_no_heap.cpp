// No heap allocation inside the step (docs/dynamics.md §13): a counting
// global operator new proves that step(), derivatives(), latch_wheel_commands(),
// mass_props(), energy_momentum() and the accessors allocate nothing once the
// run exists.  (Thrusters and tanks: test_thruster.cpp ThrusterNoHeap.)
#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include <gtest/gtest.h>

#include "sim/earth_time.h"
#include "sim/environment_effectors.h"
#include "sim/gravity_gradient.h"
#include "sim/magnetic_field.h"
#include "sim/magnetorquer.h"
#include "sim/plant.h"
#include "sim/sensors.h"
#include "sim/sun_almanac.h"
#include "sim/surface_forces.h"
#include "sim_test_util.h"

namespace {
std::atomic<long> g_news{0};
}

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

TEST(NoHeap, CounterSeesAllocations)  // the probe itself works
{
  const long before = g_news.load();
  auto* v = new std::vector<double>(100);
  delete v;
  EXPECT_GE(g_news.load() - before, 2);
}

TEST(NoHeap, StepAndAccessorsDoNotAllocate)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(sim::WheelModel::FullyCoupled);
  p.wheels[0].model = sim::WheelModel::Balanced;
  p.wheels[1].model = sim::WheelModel::SimpleJitter;
  p.hub.I_hBc_B += 0.2 * Eigen::Matrix3d::Identity();  // room for the balanced/simple J_s
  for (auto& w : p.wheels) {
    w.friction.tau_c = 1e-3;
    w.friction.beta_st = 0.5;
    w.friction.tau_st = 2e-3;
  }
  p.mu = sim::kMuEarth;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::WheelArray cmd{0.01, -0.02, 0.03, 0.04};

  const long before = g_news.load();
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    sc.latch_wheel_commands(cmd);
    ASSERT_EQ(sc.step(simtest::ns(1e-3)), sim::StepStatus::Ok);
    const sim::StateVector xd = sc.derivatives(0.0, sc.state());
    sink += xd(0) + sc.energy_momentum().E_rot + sc.mass_props().m_sc + sc.tau_f(0) + sc.u_s(1) +
            sc.sensor_truth(Eigen::Vector3d(1.0, 0.0, 0.0)).Omega[2];
  }
  EXPECT_EQ(g_news.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

// A 0.8 m cube of six 0.5 m^2 facets.
sim::FacetSet cube_facets()
{
  sim::FacetSet facets;
  facets.count = 6;
  for (int k = 0; k < 6; ++k) {
    facets.facets[k].area = 0.5;
    facets.facets[k].n_B = (k < 3 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(k % 3);
    facets.facets[k].r_B = 0.4 * facets.facets[k].n_B;
  }
  return facets;
}

// The Earth-orbit environment models (docs/environment.md) on a per-step
// path: time and rotation, Sun, gravity gradient, SRP, drag, density, IGRF,
// magnetorquer and magnetometer.
TEST(NoHeap, EnvironmentModelsDoNotAllocate)
{
  sim::UtcEpoch epoch;
  epoch.year = 2026;
  epoch.month = 12;
  epoch.day = 5;
  const sim::FacetSet facets = cube_facets();
  const sim::Igrf14 igrf(2026.9);
  const sim::ExponentialAtmosphere atm;
  const Eigen::Matrix3d I = Eigen::Vector3d(10.0, 12.0, 8.0).asDiagonal();
  sim::MagnetometerParams mp;
  mp.sigma = 1e-7;
  mp.lsb = 1e-8;
  sim::Magnetometer mag(mp, sim::SensorContext{3, true});
  sim::Magnetorquer rod(sim::MagnetorquerParams{});
  sim::MagnetorquerArray dipoles{};

  const long before = g_news.load();
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    const sim::J2000Days d = sim::days_since_j2000(epoch, 10.0 * k);
    const Eigen::Matrix3d E = sim::dcm_EN(sim::gmst_iau1982(d));
    const Eigen::Vector3d r(6.9e6, 1.0e5 * k, 1.0e6), v(-100.0, 7500.0, 900.0);
    const Eigen::Vector3d s = sim::sun_position_almanac(d).normalized();
    sink += sim::gravity_gradient_torque(sim::kMuEarth, r, I).norm();
    sink += sim::srp_load(facets, s, 1.0).L_B.norm();
    const double rho = sim::density(atm, sim::ellipsoid_height(r));
    sink += sim::drag_load(facets, sim::wind_velocity_N(r, v), rho).F_B.norm();
    sink += igrf.field_E(E * r).norm() + sim::dipole_field_E(sim::igrf14_dipole(2026.9), E * r).norm();
    sink += sim::earth_rotation_angle(d);
    rod.command(0.01 * k - 0.5);
    dipoles[0] = rod.dipole();
    mag.update(int64_t(k) * mp.period_ns, E * r * 1e-12, dipoles);
    sink += mag.output().B_S.norm() + sim::magnetic_torque(rod.dipole_B(), mag.output().B_S).norm();
  }
  EXPECT_EQ(g_news.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

// The environment effectors in a run (docs/environment.md, "In the plant"):
// every one sampled at every stage and held, rods commanded and faulted,
// the density scale changed, between and inside steps.
TEST(NoHeap, EnvironmentEffectorsDoNotAllocate)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(sim::WheelModel::Balanced);
  p.mu = sim::kMuEarth;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  sim::EarthContextParams ep;
  ep.epoch = {2026, 12, 5, 0, 0, 0.0};
  const sim::EarthContext ctx(ep);
  const sim::FacetSet facets = cube_facets();
  sim::GravityGradientParams gp;
  sim::SolarPressureParams sp;
  sim::DragParams dp;
  sim::MagneticParams mp;
  sp.facets = dp.facets = facets;
  sp.period_ns = dp.period_ns = mp.period_ns = 0;
  mp.m_residual_B = Eigen::Vector3d(0.1, 0.2, 0.3);
  mp.rods.resize(3);
  sc.add_effector(std::make_unique<sim::GravityGradientEffector>(sc, ctx, gp));
  sc.add_effector(std::make_unique<sim::SolarPressureEffector>(sc, ctx, sp));
  auto& drag = sc.add_effector(std::make_unique<sim::DragEffector>(sc, ctx, dp));
  auto& mag = sc.add_effector(std::make_unique<sim::MagneticEffector>(sc, ctx, mp));
  gp.period_ns = sp.period_ns = dp.period_ns = mp.period_ns = simtest::ns(2e-3);
  sc.add_effector(std::make_unique<sim::GravityGradientEffector>(sc, ctx, gp));
  sc.add_effector(std::make_unique<sim::SolarPressureEffector>(sc, ctx, sp));
  sc.add_effector(std::make_unique<sim::DragEffector>(sc, ctx, dp));

  const long before = g_news.load();
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    mag.command_dipoles({0.01 * k, -0.5, 0.3});
    if (k == 50) mag.set_rod_health(1, sim::MagnetorquerHealth::Stuck);
    if (k == 60) mag.set_rod_scale(2, 0.5);
    drag.set_density_scale(1.0 + 0.01 * k);
    ASSERT_EQ(sc.step(simtest::ns(1e-3)), sim::StepStatus::Ok);
    sink += sc.derivatives(0.0, sc.state())(9) + mag.load(0.0, sc.state()).L_B.norm();
  }
  EXPECT_EQ(g_news.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
