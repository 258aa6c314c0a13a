// thruster_set: the run part of the on/off ACS thrusters, one force/torque
// effector of sim::Plant (docs/dynamics.md §5.2-§5.4, §7.3).  Frames: B.
// Units: SI; times are the plant's integer nanosecond clock.
//
// Holds the command mailbox, the latch rule at k*T_upd (§5.2), the valve
// schedules, per-thruster health, and the thrust factors:
//   Instant, Table  kappa(t) evaluated from the schedule at each RK4 stage;
//   FirstOrder      kappa advanced in closed form across each sub-step
//                   (kappa(t+h) = kappa_c + (kappa - kappa_c) e^{-w h}); the
//                   RK4 stages see the closed form at their own times plus a
//                   correction linear in time (O((w h)^3)) chosen so that the
//                   RK4 quadratures of the thrust over the sub-step, its
//                   integral and its first moment, are exact: impulse,
//                   propellant and position (docs/thrusters-propellant-
//                   sensors.md "Thrust factor").
// Event splitting (§7.3): next_event() proposes valve closings and Table
// breakpoints; next_cut_ns() the latch instant while a message is pending.
#ifndef SIM_THRUSTER_SET_H
#define SIM_THRUSTER_SET_H

#include <array>
#include <cstdint>
#include <vector>

#include "sim/capacities.h"
#include "sim/effector.h"
#include "sim/thruster.h"

namespace sim {

struct ThrusterCounters {
  uint64_t latches = 0;          // command messages latched
  uint64_t ignored_min_on = 0;   // per-thruster requests dropped by T_min (§5.2 step 2)
  uint64_t split_sub_steps = 0;  // extra sub-steps created by events (§7.3), latch cuts not
                                 // counted; filled by Plant::counters()
};

class ThrusterSet final : public ForceTorqueEffector {
 public:
  ThrusterSet() { scale_.fill(1.0); }
  // Validates every thruster, the tank indices (< num_tanks or -1) and the
  // command settings (std::invalid_argument names the field).
  ThrusterSet(std::vector<ThrusterParams> thrusters, int num_tanks, ThrusterCommandParams command);

  const char* kind() const override { return "thrusters"; }
  int num_thr() const { return static_cast<int>(p_.size()); }
  const std::vector<ThrusterParams>& params() const { return p_; }
  const ThrusterCommandParams& command_params() const { return cmd_; }

  // New command message: on-time requests [s] (num_thr), latched at the next
  // latch instant k*T_upd at or after now; a later message replaces it (§5.2).
  void command(const ThrusterArray& T_req);
  bool command_pending() const { return pending_; }
  const ThrusterArray& request() const { return T_req_; }  // [s] last message

  // State now (after prepare_now(t_ns)).
  double kappa(int j) const;                      // [-] thrust factor
  bool valve_open(int j) const;                   // valve state just after now
  const ValveSchedule& schedule(int j) const { return sched_[static_cast<size_t>(j)]; }
  ThrusterHealth health(int j) const { return health_[static_cast<size_t>(j)]; }
  const ThrusterCounters& counters() const { return counters_; }
  // [s] Time thruster j's valve has been open since the start, up to now
  // (the last prepare_now): every latched pulse's open time, a pulse that a
  // later latch or a health change cut short counted up to the cut, the
  // running one up to now.  Exact: from the valve schedules, not sampled.
  double valve_open_time(int j) const;
  // F, L about B, mdot of thruster j now; zero when its tank in x is empty or it failed off.
  ThrusterEffect effect(int j, const StateVector& x, const StateLayout& L) const;

  // Takes effect at the time of the last prepare_now (see ThrusterHealth).
  void set_health(int j, ThrusterHealth h);
  // Degradation (or over-performance) of thruster j: its force, swirl torque
  // and mass flow are multiplied by s (finite, >= 0; 1 nominal), so its Isp
  // and valve behaviour are unchanged.  From the next derivative evaluation.
  void set_thrust_scale(int j, double s);
  double thrust_scale(int j) const { return scale_[static_cast<size_t>(j)]; }

  // ForceTorqueEffector
  void accumulate(const EffectorStage& stage, EffectorSums& sums) const override;
  void at_instant(int64_t t_ns) override;
  int64_t next_cut_ns(int64_t t_ns) const override;
  void begin_segment(int64_t t0_ns) override;
  double next_event(double tau, double H, double snap) const override;
  void begin_substep(double tau, double tau_end) override;
  void end_substep() override;
  void prepare_now(int64_t t_ns) override;
  void state_io(StateIO& io) override;  // every member after cmd_ (below)

 private:
  // FirstOrder closed form over the current sub-step: stage times (as RK4
  // forms them), factors at those times plus the quadrature correction, and
  // the factor at the sub-step end.
  struct FirstOrderStage {
    double kappa[3] = {0.0, 0.0, 0.0};  // [-] stage values (with the correction) at stage_t_
    double kappa_c = 0.0, d0 = 0.0, w = 0.0;
    double delta = 0.0;  // [-]   stage correction at the sub-step start
    double slope = 0.0;  // [1/s] its rate: delta + slope (t - tau) at time t
    double kappa_end = 0.0;             // [-] closed form at tau + h
  };

  void refresh_unit(size_t j);  // unit_[j] from the parameters and the thrust scale
  double s_since_latch(int j, int64_t t_ns) const;
  // FirstOrder thruster j's factor at time t of the current sub-step in
  // closed form (without the stage correction at RK4 stage times).
  double first_order_closed_form(size_t j, double t) const;
  void latch(int64_t t_L_ns);
  // begin_substep's work; const so that accumulate can form the state of
  // "now" (tau = tau_end = 0) on first use after prepare_now (below).
  void form_substep(double tau, double tau_end) const;

  // ---- run state from here on (state_io saves each member below)
  std::vector<ThrusterParams> p_;  // fixed for a run
  ThrusterCommandParams cmd_;      // fixed for a run
  ThrusterArray T_req_{};
  bool pending_ = false;
  std::array<ValveSchedule, kMaxThrusters> sched_{};
  std::array<ThrusterHealth, kMaxThrusters> health_{};
  ThrusterArray scale_{};     // [-] thrust scale (set_thrust_scale), 1 nominal
  // The effect at kappa = 1 with the thrust scale: §5.4 is linear in kappa
  // (F, the torque r x F + kappa tau_sw t and mdot = F / (g0 Isp)), so a
  // thruster's effect is kappa times it; formed once per configuration
  // instead of in every derivative evaluation.
  std::array<ThrusterEffect, kMaxThrusters> unit_{};
  ThrusterArray kappa_fo_{};  // [-] FirstOrder kappa at the current sub-step start / now
  int64_t t0_ns_ = 0;         // [ns] current segment start (or now)
  ThrusterArray s_at_t0_{};   // [s] time since each thruster's latch at t0_ns_
  // The sub-step state, formed by begin_substep.  prepare_now (after every
  // step) only marks it stale: the next step's begin_substep replaces it,
  // and only a derivative evaluated between steps (Plant::derivatives from
  // outside) needs the state of "now", which accumulate then forms.  Mutable
  // for that lazy formation alone; a ThrusterSet is not shared across threads.
  mutable bool substep_formed_ = false;
  mutable std::array<bool, kMaxThrusters> open_{};  // valve state over the current sub-step
  mutable std::array<FirstOrderStage, kMaxThrusters> fo_{};
  mutable double stage_t_[3] = {0.0, 0.0, 0.0};  // [s] the sub-step's RK4 stage times: tau, tau + h/2, tau + h
  // Thrusters that may act over the current sub-step (accumulate's loop):
  // not failed off, and not a FirstOrder factor at rest at 0; with what
  // that loop reads of their parameters.
  struct ActiveThruster {
    int j = 0;                 // thruster index
    int tank = -1;             // its tank, or -1
    bool first_order = false;  // FirstOrder transient (else Instant or Table)
  };
  mutable std::array<ActiveThruster, kMaxThrusters> active_{};
  mutable int num_active_ = 0;
  ThrusterCounters counters_;
  ThrusterArray open_done_{};  // [s] valve-open time of the replaced schedules (valve_open_time)
};

}  // namespace sim

#endif  // SIM_THRUSTER_SET_H
