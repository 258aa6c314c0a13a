// scenario_check.cpp: the checks a run makes on a loaded scenario before its
// first step, without the run (see check_run_configuration in scenario.h).
#include <memory>
#include <stdexcept>

#include "core/build_error.h"
#include "core/fsw_config.h"
#include "harness/core/fsw_endpoint.h"
#include "harness/scenario/scenario.h"
#include "core/plant_builder.h"
#include "core/sensor_suite.h"

namespace harness {

void check_run_configuration(const Scenario& sc)
{
  // The same builders Run uses, in the same order (run.cpp: Impl, wire).
  SettableParts mag{};
  const std::unique_ptr<sim::Plant> plant = build_plant(sc, nullptr, &mag);
  const FswSetup fsw = make_fsw_setup(sc, plant->mass_props());
  try {
    const InProcessFsw init(fsw.cfg);  // fsw_acs_init
  } catch (const std::invalid_argument& e) {
    throw config_error(sc, "fsw", e.what());
  }
  const SunSource sun(sc);
  const SensorSuite sensors(sc, fsw, *plant, sun, mag.effector);
  (void)burn_schedule(sc, *plant);
}

}  // namespace harness
