// thruster: on/off ACS thrusters (docs/dynamics.md §5.1-§5.4, §7.3).
// Frames: B (body), Tj (thruster j: only its location r_TjB_B and axis
// t_hat_B are used).  Units: SI; the plant clock is integer nanoseconds.
//
// This header holds the pure parts, testable on their own:
//   * parameters and validate()                                     (§5.1)
//   * the latch rule: saturation, minimum on-time, timer resolution (§5.2)
//   * the thrust factor kappa(t): Instant, FirstOrder (closed-form
//     exponential, first_order_kappa), Table (piecewise linear in time,
//     evaluated from the schedule) (§5.3)
//   * force, torque about B and mass flow of one thruster          (§5.4)
// The discrete run part (command mailbox, latches, valve schedules, event
// times, closed-form first-order factor) is sim::ThrusterSet in
// sim/thruster_set.h, one force/torque effector of sim::Plant (sim/plant.h);
// tanks are in sim/propellant.h.
#ifndef SIM_THRUSTER_H
#define SIM_THRUSTER_H

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sim/capacities.h"  // kMaxThrusters, ThrusterArray

namespace sim {

constexpr double kG0 = 9.80665;  // [m/s^2] standard gravity for Isp (§0)

enum class ThrusterTransient { Instant, FirstOrder, Table };

const char* to_string(ThrusterTransient m);

// Health of a thruster, set by the Plant between steps (faults/events).
enum class ThrusterHealth {
  Nominal,    // commands latched per §5.2
  FailedOff,  // valve closed and kappa = 0 at once; requests ignored; no force, no flow
  StuckOn     // valve open from now on (kappa rises per the transient); requests ignored
};

const char* to_string(ThrusterHealth h);

struct RampPoint {
  double t = 0.0;  // [s] time since the ramp started
  double f = 0.0;  // [-] thrust factor
};

struct ThrusterParams {  // checked by validate(); fixed for a run
  Eigen::Vector3d r_TjB_B = Eigen::Vector3d::Zero();  // [m] nozzle location relative to B
  Eigen::Vector3d t_hat_B = Eigen::Vector3d::Zero();  // [-] unit thrust axis; force on the s/c is +F t_hat
  double F_max = 0.0;      // [N]   steady-state thrust, > 0
  double Isp = 0.0;        // [s]   specific impulse, > 0
  double T_min = 0.0;      // [s]   minimum on-time for an idle thruster, >= 0
  ThrusterTransient transient = ThrusterTransient::FirstOrder;
  double omega_on = 10.0;   // [rad/s] FirstOrder rise rate, > 0 (Basilisk default 10)
  double omega_off = 10.0;  // [rad/s] FirstOrder decay rate, > 0
  // Table: on-ramp starts at (0, 0), non-decreasing, ends at factor 1; off-ramp
  // starts at (0, 1), non-increasing, ends at 0; times strictly increasing.
  std::vector<RampPoint> on_ramp;   // [s, -]
  std::vector<RampPoint> off_ramp;  // [s, -]
  double tau_sw = 0.0;      // [N*m] swirl torque about t_hat at full thrust
  int tank = 0;             // [-]   index into PropulsionParams::tanks; -1: no tank (nothing depleted)
  double dispersion = 0.0;  // [-]   thrust magnitude error (truth only), > -1
};

// Per-run thruster set settings (§5.2).
struct ThrusterCommandParams {
  int64_t T_upd_ns = 100'000'000;  // [ns] command (valve driver) period; latches at k*T_upd, > 0
  std::optional<double> T_sat;     // [s]  on-time clip; default T_upd; +inf disables the clip
  double T_q = 0.0;                // [s]  valve-timer resolution; 0: off
  double kappa_idle = 1e-3;        // [-]  a closed valve with kappa <= this counts as idle (§5.2 step 2)
};

// Throws std::invalid_argument naming `name.field` and the offending value.
void validate(const ThrusterParams& p, const std::string& name = "thruster");
void validate(const ThrusterCommandParams& p, const std::string& name = "command");

// T_sat after defaulting (§5.2 step 1).
double saturation_time(const ThrusterCommandParams& p);

// ----------------------------------------------------------------- tables

// Piecewise-linear value at table time tau (clamped to the end points).
double ramp_value(const std::vector<RampPoint>& ramp, double tau);
// First table time at which the ramp reaches factor f (rising: >= f; falling:
// <= f).  Used to enter an interrupted ramp continuously (§5.3).
double ramp_entry_time(const std::vector<RampPoint>& ramp, double f, bool rising);

// ----------------------------------------------------------- valve schedule

// The running command of one thruster.  The valve is open on
// [t_latch, t_latch + T_on); "s" below is the time since t_latch [s].
struct ValveSchedule {
  int64_t t_latch_ns = 0;  // [ns] latch instant of the running command
  double T_on = 0.0;       // [s]  on-time after saturation, min-on-time and T_q
  double tau_on0 = 0.0;    // [s]  Table: on-ramp table time at s = 0
  double tau_off0 = 0.0;   // [s]  Table: off-ramp table time at s = T_on
};

// Schedule before any command: closed, kappa = 0 (Table: at the end of the off-ramp).
ValveSchedule initial_schedule(const ThrusterParams& p);

// Valve open at time s since the latch (inline: every sub-step asks it of every thruster).
inline bool valve_open(const ValveSchedule& s, double s_since_latch)
{
  return s_since_latch >= 0.0 && s_since_latch < s.T_on;
}

// Thrust factor of a Table or Instant thruster at time s since the latch.
// `open` selects the branch (the caller fixes it per sub-step, §7.3).
// Not used for FirstOrder (see first_order_kappa).
double scheduled_kappa(const ThrusterParams& p, const ValveSchedule& s, double s_since_latch,
                       bool open);

enum class LatchResult {
  Scheduled,        // the request replaced the running command
  IgnoredMinOnTime  // 0 < T < T_min on an idle thruster: no pulse (§5.2 step 2)
};

// Valve open at, or right up to, time s since the latch: a thruster whose
// running command ends exactly at the next latch instant (continuous firing)
// still counts as firing there (§5.2 step 2).
inline bool valve_firing(const ValveSchedule& s, double s_since_latch)
{
  return s.T_on > 0.0 && s_since_latch >= 0.0 && s_since_latch <= s.T_on;
}

// §5.2 steps 1-4 at latch instant t_L_ns.  kappa_now: thrust factor at t_L;
// firing: valve_firing() of the old schedule at t_L.  A thruster is idle when
// !firing and kappa_now <= kappa_idle.  A NaN or negative request is treated
// as 0 (valve closes).  On IgnoredMinOnTime, `s` is left unchanged.
LatchResult latch_thruster(const ThrusterParams& p, const ThrusterCommandParams& c, double T_req,
                           int64_t t_L_ns, double kappa_now, bool firing, ValveSchedule& s);

// FirstOrder factor (§5.3) in closed form: t [s] after a point where it was
// kappa0, with the valve state fixed over [0, t]:
//   kappa(t) = kappa_c + (kappa0 - kappa_c) e^{-w t},
// kappa_c = 1, w = omega_on when open; kappa_c = 0, w = omega_off when closed.
double first_order_kappa(const ThrusterParams& p, double kappa0, bool open, double t);
// Its exact integral over [0, t] [s]:
//   kappa_c t + (kappa0 - kappa_c) (1 - e^{-w t}) / w.
double first_order_kappa_integral(const ThrusterParams& p, double kappa0, bool open, double t);

// ------------------------------------------------------------------ effect

struct ThrusterEffect {
  Eigen::Vector3d F_B = Eigen::Vector3d::Zero();  // [N]   force on the body, B components
  Eigen::Vector3d L_B = Eigen::Vector3d::Zero();  // [N*m] torque about point B
  double mdot = 0.0;                              // [kg/s] propellant mass flow, >= 0
};

// §5.4 at thrust factor kappa (the caller passes 0 for an empty tank).
ThrusterEffect thruster_effect(const ThrusterParams& p, double kappa);

}  // namespace sim

#endif  // SIM_THRUSTER_H
