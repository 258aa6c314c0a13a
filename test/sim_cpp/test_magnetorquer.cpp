// Magnetorquer (docs/environment.md): saturation, remanence after switch-off,
// resistive coil power, and the torque m x B against a hand calculation.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/magnetorquer.h"
#include "field_check.h"

namespace {

using Eigen::Vector3d;

sim::MagnetorquerParams rod()
{
  sim::MagnetorquerParams p;
  p.axis_B = Vector3d(0.0, 0.6, 0.8);
  p.m_max = 10.0;       // [A m^2]
  p.m_remanent = 0.05;  // [A m^2]
  p.power_max = 1.2;    // [W]
  return p;
}

TEST(Magnetorquer, SaturationRemanenceAndPower)
{
  sim::Magnetorquer m(rod());
  EXPECT_EQ(m.dipole(), 0.0);  // never commanded: no remanence yet
  m.command(4.0);
  EXPECT_EQ(m.dipole(), 4.0);
  EXPECT_FALSE(m.saturated());
  EXPECT_NEAR(m.power(), 1.2 * 0.16, 1e-15);  // (4/10)^2 of full power
  EXPECT_LT((m.dipole_B() - Vector3d(0.0, 2.4, 3.2)).norm(), 1e-15);
  m.command(25.0);
  EXPECT_EQ(m.dipole(), 10.0);
  EXPECT_TRUE(m.saturated());
  EXPECT_NEAR(m.power(), 1.2, 1e-15);
  m.command(0.0);  // switched off after a positive command: +remanence, no power
  EXPECT_EQ(m.dipole(), 0.05);
  EXPECT_EQ(m.power(), 0.0);
  EXPECT_FALSE(m.saturated());
  m.command(-12.0);
  EXPECT_EQ(m.dipole(), -10.0);
  EXPECT_TRUE(m.saturated());
  m.command(NAN);  // taken as off: remanence keeps the last sign
  EXPECT_EQ(m.dipole(), -0.05);
  m.command(-5.0);
  EXPECT_NEAR(m.power(), 0.3, 1e-15);
}

// m = 10 A m^2 along x, B = 30,000 nT along y: L = m B z = 3e-4 N m along z;
// a general pair against the cross product written out.
TEST(Magnetorquer, TorqueIsDipoleCrossField)
{
  const Vector3d L = sim::magnetic_torque(Vector3d(10.0, 0.0, 0.0), Vector3d(0.0, 30000e-9, 0.0));
  EXPECT_NEAR(L.z(), 3e-4, 1e-18);
  EXPECT_EQ(L.x(), 0.0);
  EXPECT_EQ(L.y(), 0.0);
  const Vector3d m(1.5, -2.0, 0.5), B(2e-5, 1e-5, -3e-5);
  const Vector3d want(m.y() * B.z() - m.z() * B.y(), m.z() * B.x() - m.x() * B.z(),
                      m.x() * B.y() - m.y() * B.x());
  EXPECT_LT((sim::magnetic_torque(m, B) - want).norm(), 1e-20);
  EXPECT_NEAR(sim::magnetic_torque(m, B).dot(B), 0.0, 1e-20);  // never along the field
}

TEST(Magnetorquer, RejectedFieldsAreNamed)
{
  const auto expect_field = [](const sim::MagnetorquerParams& p, const char* field) {
    simtest::expect_rejects_field([&] { sim::validate(p, "mtq"); }, field);
  };
  EXPECT_NO_THROW(sim::validate(rod()));
  sim::MagnetorquerParams p = rod();
  p.axis_B = Vector3d(1.0, 1.0, 0.0);
  expect_field(p, "mtq.axis_B");
  p = rod();
  p.m_max = 0.0;
  expect_field(p, "mtq.m_max");
  p = rod();
  p.m_remanent = 10.0;
  expect_field(p, "mtq.m_remanent");
  p = rod();
  p.power_max = -1.0;
  expect_field(p, "mtq.power_max");
  EXPECT_THROW(sim::Magnetorquer(p, "mtq"), std::invalid_argument);
}

}  // namespace
