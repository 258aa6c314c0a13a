// EarthContext (sim/earth_context.h): plant time -> date, GMST, Sun.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/earth_context.h"
#include "sim/sun_almanac.h"

namespace {

sim::EarthContextParams at(int y, int mo, int d, int h, int mi, double s)
{
  sim::EarthContextParams p;
  p.epoch = {y, mo, d, h, mi, s};
  return p;
}

// J2000.0 itself: t seconds later is t/86400 days, split at whole days.
TEST(EarthContext, PlantTimeMapsToDaysFromJ2000)
{
  const sim::EarthContext c(at(2000, 1, 1, 12, 0, 0.0));
  EXPECT_EQ(c.days(0.0).whole, 0.0);
  EXPECT_EQ(c.days(0.0).frac, 0.0);
  EXPECT_EQ(c.days(1.5 * 86400.0).whole, 1.0);
  EXPECT_EQ(c.days(1.5 * 86400.0).frac, 0.5);
  EXPECT_EQ(c.days(-0.25 * 86400.0).whole, -1.0);
  EXPECT_EQ(c.days(-0.25 * 86400.0).frac, 0.75);
  // 2026-03-20 18:00 is 9575 days and 6 h after J2000.0 (26 years, 7 leap
  // days 2000..2024, 31 + 28 + 19 days into 2026): whole 9575, frac 0.25.
  const sim::EarthContext d(at(2026, 3, 20, 18, 0, 0.0));
  EXPECT_EQ(d.days(0.0).whole, 9575.0);
  EXPECT_EQ(d.days(0.0).frac, 0.25);
  // One hour later, across midnight of the day count: 9575 + 7/24.
  EXPECT_EQ(d.days(3600.0).whole, 9575.0);
  EXPECT_NEAR(d.days(3600.0).frac, 7.0 / 24.0, 1e-15);
}

// GMST advances at the Earth's rate, and dcm_EN is R3(GMST).
TEST(EarthContext, RotationAndSun)
{
  const sim::EarthContext c(at(2026, 3, 20, 12, 0, 0.0));
  const double g0 = c.gmst(0.0), g1 = c.gmst(100.0);
  EXPECT_NEAR(std::remainder(g1 - g0, 2.0 * M_PI) / 100.0, sim::kOmegaEarth, 2e-11);
  const Eigen::Matrix3d E = c.dcm_EN(100.0);
  EXPECT_NEAR(E(0, 0), std::cos(g1), 1e-15);
  EXPECT_NEAR(E(0, 1), std::sin(g1), 1e-15);
  EXPECT_EQ(E(2, 2), 1.0);
  // Near the March equinox the Sun is close to N x, at about 1 AU.
  const Eigen::Vector3d s = c.sun_position_N(0.0);
  EXPECT_NEAR(s.normalized().x(), 1.0, 1e-3);
  EXPECT_NEAR(s.norm() / sim::kAU, 0.996, 0.002);
  EXPECT_NEAR(c.decimal_year(), 2026.0 + (78.5 + 0.5) / 365.25, 0.003);
}

TEST(EarthContext, FieldsAreNamed)
{
  auto msg = [](const sim::EarthContextParams& p) {
    try {
      sim::EarthContext c(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(msg(at(2026, 2, 29, 0, 0, 0.0)).find("earth.epoch.day"), std::string::npos);
  sim::EarthContextParams p = at(2026, 1, 1, 0, 0, 0.0);
  p.shadow_radius = -1.0;
  EXPECT_NE(msg(p).find("earth.shadow_radius"), std::string::npos);
}

}  // namespace
