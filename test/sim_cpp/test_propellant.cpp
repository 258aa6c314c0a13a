// Propellant tanks and quasi-static depletion (docs/dynamics.md §2, §5.6):
// mass properties by hand, tank config rejection, mass bookkeeping against
// the mass-flow formula, the rocket equation through depletion (THR-8), an
// empty tank stopping its thrusters, and conservation with full tanks.
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/attitude.h"
#include "sim/propellant.h"
#include "sim/plant.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr int64_t kMs = 1'000'000;  // [ns]
constexpr double kInf = std::numeric_limits<double>::infinity();

// Scenario S2 vehicle (§11): 750 kg dry hub, one tank at (0, 0, 0.2) m with
// 400 kg, main engine on the z axis through the CoM line (445 N, 234 s).
sim::SpacecraftParams s2_hub()
{
  sim::SpacecraftParams p;
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Vector3d(900.0, 800.0, 600.0).asDiagonal();
  return p;
}

sim::PropulsionParams s2_main_engine(double m_p0 = 400.0)
{
  sim::ThrusterParams t;
  t.r_TjB_B = Vector3d(0.0, 0.0, -1.5);
  t.t_hat_B = Vector3d::UnitZ();
  t.F_max = 445.0;
  t.Isp = 234.0;
  t.transient = sim::ThrusterTransient::Instant;
  t.tank = 0;
  sim::PropulsionParams p;
  p.thrusters = {t};
  p.tanks.resize(1);
  p.tanks[0].r_TB_B = Vector3d(0.0, 0.0, 0.2);
  p.tanks[0].m_p0 = m_p0;
  p.command.T_sat = kInf;  // continuous burn from one request
  return p;
}

Matrix3d pa(double m, const Vector3d& r)  // test-side parallel-axis term
{
  return m * (r.dot(r) * Matrix3d::Identity() - r * r.transpose());
}

TEST(TankConfig, RejectsEachBadFieldByName)
{
  const auto expect_field = [](sim::TankParams t, const char* field) {
    try {
      sim::validate(t, "tank");
      ADD_FAILURE() << "accepted bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("tank.") + field), std::string::npos) << e.what();
    }
  };
  sim::TankParams t;
  t.m_p0 = -1.0;
  expect_field(t, "m_p0");
  t = {};
  t.R_T = -0.1;
  expect_field(t, "R_T");
  t = {};
  t.r_TB_B.y() = NAN;
  expect_field(t, "r_TB_B");
  EXPECT_THROW(
      {
        sim::PropulsionParams p = s2_main_engine();
        p.tanks.resize(sim::kMaxTanks + 1);
        sim::Plant m({s2_hub(), p}, sim::InitialConditions{});
      },
      std::invalid_argument);
}

// §2 sums written out for a hub with an offset CoM and two tanks (a point
// mass and a sphere), compared with Plant::mass_props().
TEST(TankMassProps, MatchHandSumsForPointAndSphereTanks)
{
  sim::SpacecraftParams sc = s2_hub();
  sc.hub.r_BcB_B = Vector3d(0.05, -0.02, 0.1);
  sim::PropulsionParams p = s2_main_engine(300.0);
  p.tanks.resize(2);
  p.tanks[1].r_TB_B = Vector3d(0.4, -0.3, 0.6);
  p.tanks[1].m_p0 = 120.0;
  p.tanks[1].R_T = 0.35;
  const sim::Plant m({sc, p}, sim::InitialConditions{});
  const sim::MassProps mp = m.mass_props();

  const double m_tot = 750.0 + 300.0 + 120.0;
  const Vector3d c = (750.0 * sc.hub.r_BcB_B + 300.0 * Vector3d(0, 0, 0.2) +
                      120.0 * Vector3d(0.4, -0.3, 0.6)) / m_tot;
  const Matrix3d I_B = sc.hub.I_hBc_B + pa(750.0, sc.hub.r_BcB_B) + pa(300.0, Vector3d(0, 0, 0.2)) +
                       0.4 * 120.0 * 0.35 * 0.35 * Matrix3d::Identity() +
                       pa(120.0, Vector3d(0.4, -0.3, 0.6));
  EXPECT_NEAR(mp.m_sc, m_tot, 1e-12);
  EXPECT_NEAR((mp.c_B - c).norm(), 0.0, 1e-15);
  EXPECT_NEAR((mp.I_sc_B - I_B).norm(), 0.0, 1e-12 * I_B.norm());
  EXPECT_EQ(mp.c_prime_B, Vector3d::Zero());  // depletion c' neglected (§5.6)

  // The C-point initial conditions include the full tanks.
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(1.0, 2.0, 3.0);
  ic.sigma_BN = Vector3d(0.1, -0.2, 0.3);
  const sim::Plant m2({sc, p}, ic);
  EXPECT_NEAR((m2.energy_momentum().r_CN_N - ic.r_CN_N).norm(), 0.0, 1e-14);

  // An empty or (stage-)negative tank contributes nothing.
  sim::TankArray m_p{};
  m_p[0] = -1e-3;
  const sim::HubParams h = sim::merge_tanks_into_hub(sc.hub, p.tanks.data(), 1, m_p);
  EXPECT_EQ(h.m_h, 750.0);
  EXPECT_NEAR((h.r_BcB_B - sc.hub.r_BcB_B).norm(), 0.0, 1e-16);
  EXPECT_NEAR((h.I_hBc_B - sc.hub.I_hBc_B).norm(), 0.0, 1e-12);
}

// Mass used by a pulse = F_max (1 + disp) T / (g0 Isp) per thruster, charged
// to the right tank; thrusters with tank -1 deplete nothing.
// The per-derivative merge with its constant parts formed once equals the
// term-by-term merge (whose hand sums the test above checks) to rounding,
// for empty, negative (counted as 0), small and large propellant masses.
TEST(TankMassProps, MergerEqualsTheTermByTermMerge)
{
  sim::HubParams hub;
  hub.m_h = 750.0;
  hub.r_BcB_B = Vector3d(0.02, -0.01, 0.15);
  hub.I_hBc_B << 900.0, 12.0, -7.0, 12.0, 800.0, 5.0, -7.0, 5.0, 600.0;
  std::array<sim::TankParams, 3> tanks;
  tanks[0].r_TB_B = Vector3d(0.0, 0.0, -0.4);
  tanks[0].R_T = 0.55;
  tanks[1].r_TB_B = Vector3d(0.8, 0.3, 0.1);
  tanks[2].r_TB_B = Vector3d(-0.6, 0.7, -0.2);
  tanks[2].R_T = 0.2;
  const sim::TankMerger none(hub, tanks.data(), 0);
  const sim::HubParams h0 = none.merge(sim::TankArray{});
  EXPECT_EQ(h0.m_h, hub.m_h);
  EXPECT_EQ(h0.r_BcB_B, hub.r_BcB_B);
  EXPECT_EQ(h0.I_hBc_B, hub.I_hBc_B);
  const sim::TankMerger merger(hub, tanks.data(), 3);
  const double masses[] = {0.0, -1.0, 1e-9, 0.37, 12.5, 480.0, 2500.0};
  for (const double a : masses)
    for (const double b : masses)
      for (const double c : {0.0, 35.0}) {
        sim::TankArray m_p{};
        m_p[0] = a;
        m_p[1] = b;
        m_p[2] = c;
        const sim::HubParams ref = sim::merge_tanks_into_hub(hub, tanks.data(), 3, m_p);
        const sim::HubParams got = merger.merge(m_p);
        EXPECT_NEAR(got.m_h, ref.m_h, 1e-15 * ref.m_h);
        EXPECT_LE((got.r_BcB_B - ref.r_BcB_B).norm(), 1e-15) << a << " " << b << " " << c;
        EXPECT_LE((got.I_hBc_B - ref.I_hBc_B).cwiseAbs().maxCoeff(), 2e-15 * ref.I_hBc_B.cwiseAbs().maxCoeff())
            << a << " " << b << " " << c;
      }
}

TEST(TankDepletion, MassUsedMatchesMassFlowPerTank)
{
  sim::PropulsionParams p = s2_main_engine(50.0);
  p.tanks.push_back(p.tanks[0]);
  p.tanks[1].m_p0 = 20.0;
  sim::ThrusterParams acs = p.thrusters[0];
  acs.F_max = 22.0;
  acs.Isp = 229.5;
  acs.dispersion = 0.03;
  acs.tank = 1;
  p.thrusters.push_back(acs);
  acs.tank = -1;
  p.thrusters.push_back(acs);
  sim::Plant v({s2_hub(), p}, sim::InitialConditions{});
  v.command_thrusters({0.0537, 0.0713, 0.09});
  for (int k = 0; k < 20; ++k) ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
  const double used0 = 445.0 * 0.0537 / (9.80665 * 234.0);
  const double used1 = 22.0 * 1.03 * 0.0713 / (9.80665 * 229.5);
  EXPECT_NEAR(v.m_prop(0), 50.0 - used0, 1e-13 * 50.0);
  EXPECT_NEAR(v.m_prop(1), 20.0 - used1, 1e-13 * 20.0);
  EXPECT_NEAR(v.mass_props().m_sc, 750.0 + 70.0 - used0 - used1, 1e-12 * 820.0);
}

// THR-8: a burn through the CoM line from m0 to m1 gives
// dv = g0 Isp ln(m0/m1).  v_B' = F / m(t) with m linear in t; RK4 integrates
// it with error ~ dt^4 (mdot/m)^4, negligible here (mdot/m ~ 2e-4 /s).
TEST(TankDepletion, RocketEquationDuringBurn)
{
  sim::Plant v({s2_hub(), s2_main_engine()}, sim::InitialConditions{});
  v.command_thrusters({kInf});
  const double mdot = 445.0 / (9.80665 * 234.0);
  for (int k = 0; k < 300; ++k) ASSERT_EQ(v.step(1000 * kMs), sim::StepStatus::Ok);  // 300 s
  const double m0 = 1150.0, m1 = m0 - mdot * 300.0;
  EXPECT_NEAR(v.mass_props().m_sc, m1, 1e-12 * m0);
  const double dv = sim::rocket_delta_v(234.0, m0, m1);
  EXPECT_NEAR(v.v_BN_N().z(), dv, 1e-11 * dv);
  EXPECT_NEAR(v.v_BN_N().head<2>().norm(), 0.0, 1e-15);
  EXPECT_EQ(v.omega_BN_B(), Vector3d::Zero());
  EXPECT_NEAR(dv, 9.80665 * 234.0 * std::log(1150.0 / m1), 1e-12 * dv);  // helper = formula
}

// Burn to depletion: the tank clamps at 0 and the engine stops.  The step in
// which the tank empties is integrated with the thrust on at the RK stages
// that still see propellant, so dv is exact to about one step of thrust:
// |error| <= F dt / m_dry.
TEST(TankDepletion, RocketEquationToEmptyTankAndEngineStops)
{
  const double m_p0 = 10.0;  // ~51.6 s of burn
  sim::Plant v({s2_hub(), s2_main_engine(m_p0)}, sim::InitialConditions{});
  v.command_thrusters({kInf});
  const double dt = 0.1;
  for (int k = 0; k < 600; ++k) ASSERT_EQ(v.step(100 * kMs), sim::StepStatus::Ok);  // 60 s
  EXPECT_EQ(v.m_prop(0), 0.0);
  EXPECT_EQ(v.mass_props().m_sc, 750.0);
  EXPECT_EQ(v.thruster_effect(0).F_B, Vector3d::Zero());
  const double dv = sim::rocket_delta_v(234.0, 750.0 + m_p0, 750.0);
  EXPECT_NEAR(v.v_BN_N().z(), dv, 445.0 * dt / 750.0);
  const double vz = v.v_BN_N().z();
  for (int k = 0; k < 10; ++k) v.step(100 * kMs);
  EXPECT_EQ(v.v_BN_N().z(), vz);  // no thrust from an empty tank
}

// With full tanks and no firing, tanks are rigid parts of the body: H_C and
// E_rot (§8, tank terms) and the orbital quantities are conserved.
TEST(TankConservation, RigidTanksConserveMomentumAndEnergy)
{
  sim::SpacecraftParams sc = s2_hub();
  sc.hub.r_BcB_B = Vector3d(0.05, -0.02, 0.1);
  sc.mu = 4.2828314e13;
  sim::PropulsionParams p = s2_main_engine(300.0);
  p.tanks.resize(2);
  p.tanks[1].r_TB_B = Vector3d(0.4, -0.3, 0.6);
  p.tanks[1].m_p0 = 120.0;
  p.tanks[1].R_T = 0.35;
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(3896190.0, 0.0, 0.0);
  ic.v_CN_N = Vector3d(0.0, 3500.0, 300.0);
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  ic.omega_BN_B = Vector3d(0.05, -0.03, 0.08);
  sim::Plant v({sc, p}, ic);
  const sim::EnergyMomentum e0 = v.energy_momentum();
  for (int k = 0; k < 500; ++k) ASSERT_EQ(v.step(10 * kMs), sim::StepStatus::Ok);
  const sim::EnergyMomentum e1 = v.energy_momentum();
  EXPECT_LT((e1.H_C_N - e0.H_C_N).norm(), 1e-12 * e0.H_C_N.norm());
  EXPECT_LT(std::abs(e1.E_rot - e0.E_rot), 1e-12 * std::abs(e0.E_rot));
  EXPECT_LT((e1.H_orb_N - e0.H_orb_N).norm(), 1e-12 * e0.H_orb_N.norm());
  EXPECT_LT(std::abs(e1.E_orb - e0.E_orb), 1e-12 * std::abs(e0.E_orb));
  // Same numbers as an equivalent single rigid hub (independent of the merge):
  // H_C = I_C omega with I_C from the hand sums of the previous test.
  const double m_tot = 1170.0;
  const Vector3d c = (750.0 * sc.hub.r_BcB_B + 300.0 * Vector3d(0, 0, 0.2) +
                      120.0 * Vector3d(0.4, -0.3, 0.6)) / m_tot;
  const Matrix3d I_B = sc.hub.I_hBc_B + pa(750.0, sc.hub.r_BcB_B) + pa(300.0, Vector3d(0, 0, 0.2)) +
                       0.4 * 120.0 * 0.35 * 0.35 * Matrix3d::Identity() +
                       pa(120.0, Vector3d(0.4, -0.3, 0.6));
  const Matrix3d I_C = I_B - pa(m_tot, c);
  EXPECT_LT((e0.H_C_B - I_C * ic.omega_BN_B).norm(), 1e-12 * e0.H_C_B.norm());
}

}  // namespace
