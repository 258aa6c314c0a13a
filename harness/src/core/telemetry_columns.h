// telemetry_columns: what a run records, declared once.  Each entry names a
// message, its quantities (unit, frame, components) and how they are read
// from the message; the HDF5 datasets (/<message>/<quantity>), the flat CSV
// and report columns (<column>) all follow from these declarations.
#ifndef HARNESS_TELEMETRY_COLUMNS_H
#define HARNESS_TELEMETRY_COLUMNS_H

#include <array>

#include "harness/core/loop_messages.h"
#include "harness/core/recorder.h"
#include "core/tasks.h"

namespace harness {

// The channels a run records (optional ones may be null).
struct RecordedChannels {
  const Channel<TruthMsg>* truth = nullptr;
  const Channel<MetricsMsg>* metrics = nullptr;
  const Channel<FswAcsSensorMsg>* fsw_sensors = nullptr;
  const Channel<FswAcsActuatorMsg>* fsw_actuators = nullptr;
  const Channel<FswAcsHealthMsg>* fsw_health = nullptr;
  const Channel<PlantCmdMsg>* plant_cmd = nullptr;      // thruster runs
  const Channel<SunHeadingMsg>* sun_heading = nullptr;  // sun-safe runs
};

// Declares every recorded column on `rec` (t first).  `t_now_ns` gives the
// time of the row being sampled.
void declare_telemetry(Recorder& rec, const RecordedChannels& ch, int n_rw, int n_thr, bool orbit,
                       std::function<uint64_t()> t_now_ns);

// The disturbance torque about the mass centre of each environment source
// that is on (EnvSource order): torque_<source>_x/_y/_z [N*m], B components.
// None when every source is off.
void declare_disturbances(Recorder& rec, const RecordedChannels& ch, const std::array<bool, kNumEnvSources>& on);

// The magnetorquers (`mtq_state`): mtq_dipole_<i> [A*m^2] acting dipole
// along rod i's axis, mtq_power_<i> [W] its coil power.
void declare_magnetorquers(Recorder& rec, const Channel<MtqStateMsg>& ch, int n_rods);

// The magnetometer's reading as handed on (`magnetometer`): mag_B_S_x/_y/_z
// [T] in its sensor axes (NaN during a dropout), mag_valid [-].
void declare_magnetometer(Recorder& rec, const Channel<MagnetometerMsg>& ch);

// The FSW's modes and momentum management (runs whose FSW detumbles, points
// at nadir, manages momentum or biases the wheels): fsw_mode, fsw_policy,
// fsw_detumbled, fsw_rate_est [rad/s], fsw_h_w_B_x/y/z [N*m*s] (the wheel
// momentum the FSW sees), fsw_tau_mtq_B_x/y/z [N*m], fsw_dump_phase,
// fsw_dumps, fsw_prop_used [kg].
void declare_fsw_momentum(Recorder& rec, const RecordedChannels& ch);

// Earth-orbit truth (docs/environment.md, "Recorded"): with an epoch,
// illumination [-] and eclipse [-] (1 while any of the Sun's disk is
// hidden); with the magnetic model on, field_B_x/_y/_z [T]; for each source
// that is on, H_<source>_N_x/_y/_z [N*m*s], the angular momentum it has given
// the spacecraft (N); and, with any source on and wheels, H_wheels_N_x/_y/_z
// [N*m*s].  None for a scenario without epoch and sources.
void declare_environment_truth(Recorder& rec, const RecordedChannels& ch, const std::array<bool, kNumEnvSources>& on,
                               bool has_epoch, int n_rw);

}  // namespace harness

#endif  // HARNESS_TELEMETRY_COLUMNS_H
