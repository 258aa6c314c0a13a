// Plant capacities (sim/capacities.h) against the flight software's
// (fsw_config.h, css_sun.h): any configuration the FSW accepts must fit in
// the plant.  Compile-time checks; the test body only reports the values.
#include <gtest/gtest.h>

#include "fsw/css_sun.h"     // FSW_MAX_CSS
#include "fsw/fsw_config.h"  // FSW_MAX_RW, FSW_MAX_THR
#include "sim/capacities.h"

static_assert(sim::kMaxWheels >= FSW_MAX_RW, "plant wheel capacity below FSW_MAX_RW");
static_assert(sim::kMaxThrusters >= FSW_MAX_THR, "plant thruster capacity below FSW_MAX_THR");
static_assert(sim::kMaxCss >= FSW_MAX_CSS, "plant CSS capacity below FSW_MAX_CSS");
static_assert(sim::kMaxEffectors >= 1, "the thruster set is an effector");
static_assert(sim::kMaxStateDim == 12 + 2 * sim::kMaxWheels + sim::kMaxTanks, "state layout");

TEST(Capacities, PlantCoversTheFlightSoftware)
{
  EXPECT_GE(sim::kMaxWheels, FSW_MAX_RW);
  EXPECT_GE(sim::kMaxThrusters, FSW_MAX_THR);
  EXPECT_GE(sim::kMaxCss, FSW_MAX_CSS);
}
