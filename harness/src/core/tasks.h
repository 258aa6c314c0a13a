// tasks: the tasks of the tick protocol (docs/harness.md), one named object
// each.  A task holds the Reader/Writer of every message it uses (the
// data-flow map is built from these) and the models it drives; it runs as
// task(k) at tick k.  run.cpp registers them in the protocol's order.
#ifndef HARNESS_TASKS_H
#define HARNESS_TASKS_H

#include <array>
#include <cstdint>

#include <Eigen/Dense>

#include "core/fsw_config.h"
#include "harness/core/fsw_endpoint.h"
#include "harness/core/loop_messages.h"
#include "harness/core/messages.h"
#include "harness/core/recorder.h"
#include "harness/core/run.h"
#include "core/plant_builder.h"
#include "sim/plant.h"
#include "core/sensor_suite.h"
#include "core/sun_source.h"
#include "sim/propellant.h"

namespace harness {

// Wheel torques and thruster on-times for the plant, latched at FSW ticks.
struct PlantCmdMsg {
  double u_s[kMaxRw];    // [N*m] wheel motor torque commands (zero-order hold)
  double T_on[kMaxThr];  // [s]   on-time requests (plant thruster order; ACS from the FSW, the engine from the burn)
};

// Non-gravitational velocity change of C and the burn window (thruster runs).
struct BurnStateMsg {
  double dv_ng_N[3];  // [m/s] accumulated non-gravitational velocity change of C
  uint8_t in_burn;    // [-] 1 between burn start and burn end
};

// Plant state -> `truth` (every tick).
struct TruthTask {
  const sim::Plant* plant;
  uint64_t tick_ns;
  Writer<TruthMsg> out;
  EnvEffectors env{};  // the run's environment effectors (null: off)
  const SunSource* sun = nullptr;  // the run's Sun (illumination when dated)
  void operator()(uint64_t k) const;
  // Illumination; with an environment source on (any_env), the field, the
  // accumulated momenta and the wheel momentum (Earth orbit).
  void environment_truth(TruthMsg& t, uint64_t t_ns, double t_s, bool any_env) const;
};

// Burn monitor (thruster runs, every tick): dv += (v_C(k+1) - v_C(k)) -
// dt/2 (g(r_C(k)) + g(r_C(k+1))), and the state at the burn's start and end.
struct BurnMonitor {
  struct Snap {
    bool set = false;
    double t = 0.0, m = 0.0;
    std::array<double, sim::kMaxTanks> m_p{};
    Eigen::Vector3d dv_ng = Eigen::Vector3d::Zero(), r = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  };
  BurnMonitor(const sim::Plant* p, uint64_t tk, double dt_s, double mu_, BurnSchedule b, double F_eng,
              Reader<TruthMsg> in, Writer<BurnStateMsg> w)
      : plant(p), tick_ns(tk), dt(dt_s), mu(mu_), burn(b), engine_F_max(F_eng), truth(in), out(w)
  {
  }
  const sim::Plant* plant;
  uint64_t tick_ns;
  double dt;              // [s]
  double mu;              // [m^3/s^2]
  BurnSchedule burn;
  double engine_F_max;    // [N]
  Reader<TruthMsg> truth;
  Writer<BurnStateMsg> out;
  bool have_prev = false;
  Eigen::Vector3d r_prev = Eigen::Vector3d::Zero(), v_prev = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv_ng = Eigen::Vector3d::Zero();
  Snap start, end;
  void operator()(uint64_t k);
  void state_io(sim::StateIO& io)  // a checkpoint (sim/state_io.h)
  {
    io.value("burn.have_prev", have_prev);
    io.value("burn.r_prev", r_prev);
    io.value("burn.v_prev", v_prev);
    io.value("burn.dv_ng", dv_ng);
    io.value("burn.start", start);
    io.value("burn.end", end);
  }

 private:
  void snap(Snap& s, double t, const TruthMsg& tr) const;
};

// Gyro, star tracker, tachometers (every tick; each samples the plant's
// sensor truth when its own period is due, its output held in between)
// -> `sensor_samples`.
struct SampleSensorsTask {
  SensorSuite* sensors;  // samples the plant's sensor truth
  uint64_t tick_ns;
  Writer<SensorSampleMsg> out;
  void operator()(uint64_t k) const;
};

// Coarse sun sensors (FSW ticks) -> `css_readings`.
struct CssTask {
  SensorSuite* sensors;  // samples the plant's sensor truth
  uint64_t tick_ns;
  Writer<CssMsg> out;
  void operator()(uint64_t k) const;
};

// FSW input (FSW ticks) -> `fsw_sensors`.
struct FswInputTask {
  const SensorSuite* sensors;
  uint64_t tick_ns;
  Reader<TruthMsg> truth;
  Reader<SensorSampleMsg> samples;  // unset without sampled models
  Reader<CssMsg> css;               // unset without CSS models
  Reader<MagnetometerMsg> mag;      // unset unless the FSW reads the magnetometer
  Writer<FswAcsSensorMsg> out;
  void operator()(uint64_t k) const;
};

// The FSW (FSW ticks): `fsw_sensors` -> endpoint -> `fsw_actuators`,
// `fsw_health` (and `sun_heading` in sun-safe runs).  A command written to
// `fsw_cmd` since the last cycle (runs that take FSW commands) is handed to
// the endpoint first, for this cycle (FswEndpoint::command).
struct FswTask {
  FswEndpoint* fsw;
  uint64_t tick_ns;
  Reader<FswAcsSensorMsg> in;
  Writer<FswAcsActuatorMsg> act;
  Writer<FswAcsHealthMsg> health;
  Writer<SunHeadingMsg> sun;  // unset outside sun-safe runs
  bool has_sun = false;
  Reader<FswAcsCmdMsg> cmd;   // unset in runs that take no FSW commands
  uint64_t cmd_seen = 0;      // write count of `fsw_cmd` handed on so far
  void operator()(uint64_t k);
  void state_io(sim::StateIO& io) { io.value("fsw_task.cmd_seen", cmd_seen); }  // a checkpoint
};

// FSW actuator message -> plant commands (FSW ticks): wheel torques
// (zero when the FSW's wheels are inactive), ACS on-times in plant order,
// the engine's on-time from the burn schedule.
struct ActuatorTask {
  uint64_t tick_ns;
  int n_rw, n_thr, n_acs;
  std::array<int, FSW_MAX_THR> acs_to_plant;
  BurnSchedule burn;
  Reader<FswAcsActuatorMsg> in;
  Writer<PlantCmdMsg> out;
  int n_mtq = 0;           // rods commanded by the FSW (fsw.magnetorquers), else 0
  Writer<MtqCmdMsg> mtq;   // `mtq_cmd`, set when n_mtq > 0
  void operator()(uint64_t k) const;
};

// The plant takes `plant_cmd` (FSW ticks): wheel torques latched (docs/dynamics.md §4.3),
// thruster requests latched at its next command instant (docs/dynamics.md §5.2).
struct PlantInputTask {
  sim::Plant* plant;
  Reader<PlantCmdMsg> in;
  void operator()(uint64_t k) const;
};

// Magnetometer (every tick, with sensors.magnetometer): samples when its
// period is due; the reading handed on, faults applied -> `magnetometer`.
struct MagnetometerTask {
  SensorSuite* sensors;
  uint64_t tick_ns;
  Writer<MagnetometerMsg> out;
  void operator()(uint64_t k) const;
};

// The rods take `mtq_cmd` (FSW ticks, the control instants): dipole mode
// commands the effector (held until the next); PWM mode starts the driver's
// cycles there.
struct MagnetorquerTask {
  sim::MagneticEffector* mag;
  MtqPwmDriver* pwm;  // null: dipole mode
  uint64_t tick_ns;
  Reader<MtqCmdMsg> in;
  void operator()(uint64_t k) const;
};

// The rods' acting dipoles and coil power (record ticks) -> `mtq_state`.
struct MtqStateTask {
  const sim::MagneticEffector* mag;
  uint64_t tick_ns;
  Writer<MtqStateMsg> out;
  void operator()(uint64_t k) const;
};

// Figures of merit (record ticks) -> `metrics`.  The pointing error is the
// truth attitude against the reference in force (PointingReference, run.h):
// the configuration's, then the mode and reference of each FSW command in
// `fsw_cmd` (the message the FSW is handed), from the tick it is written, so
// it checks the FSW independently of the FSW's own error output.
struct MetricsTask {
  MetricsTask(const sim::Plant* p, uint64_t tk, PointingReference ref_, const Eigen::Vector3d& sigma_R0N_,
              const Eigen::Vector3d& sun_axis_B_, const SunSource* sun_, double mu_, Reader<TruthMsg> t,
              Reader<BurnStateMsg> b, bool has_b, Writer<MetricsMsg> w)
      : plant(p), tick_ns(tk), ref0(ref_), ref(ref_), sigma_R0N(sigma_R0N_), sigma_ref(sigma_R0N_),
        sun_axis_B(sun_axis_B_), sun(sun_), mu(mu_), truth(t), burn(b), has_burn(has_b), out(w)
  {
  }
  const sim::Plant* plant;
  uint64_t tick_ns;
  PointingReference ref0;            // the configuration's (fsw.mode; DETUMBLE: its exit's)
  PointingReference ref;             // in force
  Eigen::Vector3d sigma_R0N;         // the configuration's inertial reference
  Eigen::Vector3d sigma_ref;         // the inertial reference in force
  bool ref_commanded = false;        // a command changed the reference in force
  Eigen::Vector3d sun_axis_B;
  const SunSource* sun;  // the run's Sun (of the pointing error)
  double mu;
  Reader<TruthMsg> truth;
  Reader<BurnStateMsg> burn;  // unset without thrusters
  bool has_burn = false;
  Writer<MetricsMsg> out;
  Reader<FswAcsCmdMsg> cmd;   // unset in runs that take no FSW commands
  uint64_t cmd_seen = 0;      // write count of `fsw_cmd` taken so far
  double max_err_burn = 0.0;  // [rad] largest pointing error between burn start and end
  // the orbit frame (NADIR): formed here from the truth position and
  // velocity, independently of the FSW
  OrbitFrame frame = OrbitFrame::Nadir;
  Eigen::Vector3d sigma_BdR = Eigen::Vector3d::Zero();
  void operator()(uint64_t k);
  void state_io(sim::StateIO& io)  // a checkpoint (sim/state_io.h)
  {
    io.value("metrics.ref", ref);
    io.value("metrics.sigma_ref", sigma_ref);
    io.value("metrics.ref_commanded", ref_commanded);
    io.value("metrics.cmd_seen", cmd_seen);
    io.value("metrics.max_err_burn", max_err_burn);
    io.value("metrics.frame", frame);
    io.value("metrics.sigma_BdR", sigma_BdR);
  }
  // Takes a new command of `fsw_cmd`: its mode's reference, its inertial
  // reference when it sets one (a set command the FSW refuses, |sigma|^2
  // not finite, changes nothing, as in the FSW).
  void follow_command();
  double pointing_error(uint64_t k, const TruthMsg& t) const;  // [rad]
};

// The reference an FSW mode (FswAcsMode) points by; DETUMBLE: `detumble`.
PointingReference reference_of_mode(int fsw_mode, PointingReference detumble);

// [RN] of the orbit frame from position and velocity (N): NADIR: z to nadir,
// y along the negative orbit normal; VELOCITY: x along the velocity.
Eigen::Matrix3d orbit_frame_RN(OrbitFrame frame, const Eigen::Vector3d& r_N, const Eigen::Vector3d& v_N);

// Principal angle [rad] of B relative to R from two MRPs.
double principal_angle(const Eigen::Vector3d& sigma_BN, const Eigen::Vector3d& sigma_RN);

}  // namespace harness

#endif  // HARNESS_TASKS_H
