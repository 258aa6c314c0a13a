// plant: THE run class of the plant (docs/dynamics.md §1-§8, §10, §13).
// A rigid hub with reaction wheels, propellant tanks and a fixed-capacity
// list of force/torque effectors (the on/off thrusters first), integrated as
// one RK4 state on one integer nanosecond clock.  A plant with zero
// thrusters and zero tanks is the plain hub-and-wheels spacecraft.
// Frames: N inertial, B body (origin at point B), Wi wheel i.  Units: SI.
//
// Layers:
//   SpacecraftModel (sim/spacecraft.h)  pure hub + wheel physics, hub explicit
//   ThrusterSet     (sim/thruster_set.h) thruster commands, valves, kappa
//   ForceTorqueEffector (sim/effector.h) interface of every force/torque
//                                         contributor; add more with add_effector
//   Plant                                the run: state, clock, held wheel
//                                         inputs, Stribeck flags, health,
//                                         MRP switch, step protocol
//
// State: one StateVector, layout in sim/spacecraft.h (hub, Omega, theta, m_p).
// Discrete memory (§1): held wheel torques u_s and Stribeck flags, wheel and
// thruster health, thruster mailbox/schedules and first-order factors kappa.
//
// step(dt_ns), in this order (one copy of the prologue and epilogue):
//   1. Stribeck flag update per wheel at the step start (§4.6)
//   2. segments cut at effector instants (thruster latch k*T_upd while a
//      message is pending); each segment split into sub-steps at effector
//      events (valve closings, Table breakpoints, §7.3); each sub-step one
//      RK4 step with every discrete input frozen
//   3. after every sub-step: MRP shadow switch (§7.4), tank clamp at 0 (§5.6)
//   A non-finite result is not committed; the run halts with that reason.
#ifndef SIM_PLANT_H
#define SIM_PLANT_H

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "sim/capacities.h"
#include "sim/effector.h"
#include "sim/propellant.h"
#include "sim/reaction_wheel.h"
#include "sim/sensors.h"
#include "sim/spacecraft.h"
#include "sim/thruster.h"
#include "sim/thruster_set.h"

namespace sim {

struct PropulsionParams {
  std::vector<ThrusterParams> thrusters;  // (num_thr <= kMaxThrusters)
  std::vector<TankParams> tanks;          // (num_tanks <= kMaxTanks)
  ThrusterCommandParams command;
};

struct PlantParams {
  SpacecraftParams sc;    // hub, wheels (num_rw <= kMaxWheels), mu
  PropulsionParams prop;  // empty: no thrusters, no tanks
};

enum class StepStatus { Ok, NonFiniteState };

class Plant {
 public:
  // Validates everything (std::invalid_argument names the field and value);
  // the C-point initial conditions are converted with the tanks full (§1).
  Plant(PlantParams params, const InitialConditions& ic);

  // Adds a force/torque effector after the thruster set (setup only; at most
  // kMaxEffectors in all).  Returns it for the caller to command.
  template <class E>
  E& add_effector(std::unique_ptr<E> e)
  {
    E& ref = *e;
    add_effector_impl(std::move(e));
    return ref;
  }

  // ----------------------------------------------------------- inputs
  // §4.3 wheel command latch at the current wheel speeds; u_cmd[i], i < num_rw.
  // A wheel that is Off latches 0.
  void latch_wheel_commands(const WheelArray& u_cmd);
  // The same from u_cmd[0 .. num_rw()), e.g. a command message's own array.
  void latch_wheel_commands(const double* u_cmd);
  // New thruster command message: on-time requests [s] (num_thr), latched at
  // the next instant k*T_upd at or after now (§5.2).
  void command_thrusters(const ThrusterArray& T_req);
  // External test force [N] and torque about B [N*m], B components, held until changed.
  void set_external(const Eigen::Vector3d& F_ext_B, const Eigen::Vector3d& L_ext_B);

  // ----------------------------------------------------------- the step
  StepStatus step(int64_t dt_ns);

  // Pure: x_dot = f(t, x) with every discrete input frozen as it is now
  // (held torques, Stribeck flags, valve states, kappa in closed form from
  // now; t [s] after now).  RW-0 style checks compare this directly.
  // Const, but the first call after a step forms the thrusters' sub-step
  // state of now (ThrusterSet): not to be called on one Plant from two
  // threads at once (each run, and each Monte Carlo worker, owns its Plant).
  StateVector derivatives(double t, const StateVector& x, Accelerations* acc = nullptr) const;

  // ------------------------------------- device parameters between steps
  // Validated (std::invalid_argument names "wheels[i].<field>" /
  // "thrusters[j].health"); they keep the state and take effect as noted.
  void set_wheel_u_max(int i, double u_max);          // [N*m]   next latch; <= 0: unlimited
  void set_wheel_Omega_max(int i, double Omega_max);  // [rad/s] next latch; <= 0: none
  void set_wheel_friction(int i, const WheelFrictionParams& f);  // next step
  void set_wheel_health(int i, WheelHealth h);        // Off, Stuck: u_s = 0 now and at every latch
  void set_thruster_health(int j, ThrusterHealth h);  // now (see ThrusterHealth)
  void set_thruster_thrust_scale(int j, double s);    // next derivative; F, L, mdot times s >= 0

  // ---------------------------------------------------- accessors (§13)
  const SpacecraftModel& model() const { return model_; }
  const StateLayout& layout() const { return model_.layout(); }
  int num_rw() const { return model_.num_rw(); }
  int num_thr() const { return thr_.num_thr(); }
  int num_tanks() const { return static_cast<int>(tanks_.size()); }
  const ReactionWheelParams& wheel_params(int i) const;
  const ThrusterSet& thrusters() const { return thr_; }
  const std::vector<TankParams>& tanks() const { return tanks_; }
  int num_effectors() const { return 1 + static_cast<int>(extra_.size()); }

  const StateVector& state() const { return x_; }
  void set_state(const StateVector& x);  // for tests and scenario restarts
  // The whole run state for a checkpoint (sim/state_io.h, docs/checkpoint.md):
  // the state vector and clock, held inputs, wheel health, the settable
  // wheel parameters, the step counters and every effector's state.
  // Restored into a Plant built from the same parameters.
  void state_io(StateIO& io);
  int64_t t_ns() const { return t_ns_; }

  Eigen::Vector3d r_BN_N() const { return x_.segment<3>(StateLayout::r_BN_N); }
  Eigen::Vector3d v_BN_N() const { return x_.segment<3>(StateLayout::v_BN_N); }
  Eigen::Vector3d sigma_BN() const { return x_.segment<3>(StateLayout::sigma_BN); }
  Eigen::Vector3d omega_BN_B() const { return x_.segment<3>(StateLayout::omega_BN_B); }

  // wheels
  double Omega(int i) const { return x_(layout().Omega(i)); }  // [rad/s]
  double theta(int i) const { return x_(layout().theta(i)); }  // [rad] unwrapped
  double u_s(int i) const { return held_.wheels.u_s[static_cast<size_t>(i)]; }  // [N*m] held motor torque
  double tau_f(int i) const;                                             // [N*m] friction now
  bool stribeck_mode(int i) const { return held_.wheels.stribeck[static_cast<size_t>(i)]; }
  WheelHealth wheel_health(int i) const { return wheel_health_[static_cast<size_t>(i)]; }

  // thrusters and tanks
  double kappa(int j) const { return thr_.kappa(j); }          // [-] thrust factor now
  bool valve_open(int j) const { return thr_.valve_open(j); }  // just after now
  ThrusterEffect thruster_effect(int j) const { return thr_.effect(j, x_, layout()); }
  const ValveSchedule& schedule(int j) const { return thr_.schedule(j); }
  ThrusterHealth thruster_health(int j) const { return thr_.health(j); }
  ThrusterCounters counters() const;
  double m_prop(int k) const { return x_(layout().m_p(k)); }  // [kg]

  // whole vehicle
  HubParams hub_with_propellant(const StateVector& x) const;  // §5.6 (params hub without tanks)
  MassProps mass_props() const { return model_.mass_props(x_, hub_with_propellant(x_)); }
  // m_sc and c_B of mass_props() without the inertias (the per-tick truth).
  MassCentre mass_centre() const { return model_.mass_centre(x_, hub_with_propellant(x_), rotor_sin_cos_now()); }
  EnergyMomentum energy_momentum() const { return model_.energy_momentum(x_, hub_with_propellant(x_)); }
  const HeldInputs& held_inputs() const { return held_; }
  uint64_t mrp_switch_count() const { return switches_; }
  uint64_t steps_taken() const { return steps_; }
  StepStatus status() const { return status_; }

  // The sensors' truth from the plant state now (§7.2 step 1): t_ns,
  // sigma_BN, omega_BN_B, r_BN_N, Omega[num_rw]; the Sun position and the
  // illumination factor come from the caller's environment.
  SensorTruth sensor_truth(const Eigen::Vector3d& r_SunN_N, double f_illum = 1.0) const;
  void fill_sensor_truth(SensorTruth& out, const Eigen::Vector3d& r_SunN_N, double f_illum = 1.0) const;

 private:
  void add_effector_impl(std::unique_ptr<ForceTorqueEffector> e);
  void check_wheel_index(int i) const;
  bool integrate_segment(int64_t t0_ns, int64_t t1_ns);
  void prepare_effectors_now();
  // cos and sin of the rotor angles of x_ (null when no wheel jitters),
  // formed once for the angles they are of: the per-tick truth's mass
  // centre and the first derivative of the next step read the same ones.
  const RotorSinCos* rotor_sin_cos_now() const;
  template <class F>
  void for_each_effector(F&& f)
  {
    f(static_cast<ForceTorqueEffector&>(thr_));
    for (auto& e : extra_) f(*e);
  }

  SpacecraftModel model_;
  std::vector<TankParams> tanks_;
  TankMerger merger_;  // the hub with the tanks' propellant, per derivative
  ThrusterSet thr_;
  std::vector<std::unique_ptr<ForceTorqueEffector>> extra_;  // reserved to kMaxEffectors - 1
  StateVector x_;
  int64_t t_ns_ = 0;
  HeldInputs held_;
  std::array<WheelHealth, kMaxWheels> wheel_health_{};
  WheelArray Omega_prev_{};  // [rad/s] wheel speeds at the previous step start (§4.6)
  bool first_step_ = true;
  uint64_t switches_ = 0;
  uint64_t steps_ = 0;
  uint64_t split_sub_steps_ = 0;
  StepStatus status_ = StepStatus::Ok;
  // rotor_sin_cos_now()'s values and the bits of the angles they are of
  // (a cache: not part of the plant's state)
  mutable RotorSinCos rotor_now_{};
  mutable std::array<uint64_t, kMaxWheels> rotor_now_theta_{};
  mutable bool rotor_now_set_ = false;
};

}  // namespace sim

#endif  // SIM_PLANT_H
