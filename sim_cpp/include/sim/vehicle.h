// vehicle: the hub-and-wheels spacecraft (sim/spacecraft.h) plus on/off
// thrusters and propellant tanks, integrated as one RK4 state
// (spec plant-dynamics §1, §5, §7.2-§7.3, §10, §13).  Frames: N, B.  Units: SI;
// the clock is an integer nanosecond counter (t_ns = sum of dt_ns).
//
// Two layers, like Spacecraft:
//   VehicleModel  validated params; const, pure physics.  derivatives() adds
//                 the thruster forces and torques about B to the held external
//                 inputs, merges the stage propellant into the hub (§5.6) and
//                 calls SpacecraftModel::derivatives with that hub.
//   Vehicle       one run: state, clock, held wheel inputs, thruster command
//                 mailbox and valve schedules; step() splits the step at every
//                 latch instant, valve closing and Table breakpoint (§7.3).
//
// State (VehicleState):
//   sc    the SpacecraftModel state (layout in sim/spacecraft.h)
//   prop  [0, n_thr)            kappa_j [-]  thrust factor; integrated for
//                               FirstOrder thrusters, unused (0) otherwise
//         [n_thr, n_thr+n_tank) m_p,k  [kg] propellant per tank
// Both parts have compile-time maximum sizes: the step never touches the heap.
#ifndef SIM_VEHICLE_H
#define SIM_VEHICLE_H

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "sim/propellant.h"
#include "sim/spacecraft.h"
#include "sim/thruster.h"

namespace sim {

constexpr int kMaxPropStates = kMaxThrusters + kMaxTanks;  // [-]

using PropStateVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxPropStates, 1>;

struct VehicleState {
  StateVector sc;        // hub, wheels
  PropStateVector prop;  // kappa_j, m_p,k
};

VehicleState operator+(const VehicleState& a, const VehicleState& b);
VehicleState operator*(double s, const VehicleState& a);

struct PropLayout {
  int num_thr = 0;
  int num_tanks = 0;
  int kappa(int j) const { return j; }
  int m_p(int k) const { return num_thr + k; }
  int size() const { return num_thr + num_tanks; }
};

struct PropulsionParams {
  std::vector<ThrusterParams> thrusters;  // (num_thr <= kMaxThrusters)
  std::vector<TankParams> tanks;          // (num_tanks <= kMaxTanks)
  ThrusterCommandParams command;
};

// Inputs held over one sub-step (valve states are fixed per sub-step, §7.3).
struct SubStepInputs {
  HeldInputs sc;                            // wheel torques, friction modes, external F/L
  std::array<bool, kMaxThrusters> open{};   // [-] (num_thr) valve state on the sub-step
  ThrusterArray s_at_t0{};                  // [s] (num_thr) time since each thruster's latch at t = 0
  std::array<ValveSchedule, kMaxThrusters> schedule{};  // (num_thr) running commands
};

class VehicleModel {
 public:
  // Validates every field (std::invalid_argument names the field and value).
  VehicleModel(SpacecraftParams sc, PropulsionParams prop);

  const SpacecraftModel& spacecraft() const { return sc_; }
  const PropulsionParams& propulsion() const { return prop_; }
  const PropLayout& prop_layout() const { return layout_; }
  int num_thr() const { return layout_.num_thr; }
  int num_tanks() const { return layout_.num_tanks; }

  // kappa = 0, m_p = m_p0, and the C-point ICs converted with the tanks full.
  VehicleState initial_state(const InitialConditions& ic) const;

  // The hub with the propellant of state x merged in (§5.6).
  HubParams hub_with_propellant(const VehicleState& x) const;
  MassProps mass_props(const VehicleState& x) const;
  EnergyMomentum energy_momentum(const VehicleState& x) const;

  // Thrust factor of thruster j at time t [s] after the sub-step origin.
  double kappa(int j, double t, const VehicleState& x, const SubStepInputs& in) const;
  // Force/torque/mass flow of thruster j at that kappa; zero if its tank is empty.
  ThrusterEffect effect(int j, double kappa, const VehicleState& x) const;

  // Pure: x_dot = f(t, x, in).  t is the time since the origin of in.s_at_t0.
  VehicleState derivatives(double t, const VehicleState& x, const SubStepInputs& in,
                           Accelerations* acc = nullptr) const;

 private:
  SpacecraftModel sc_;
  PropulsionParams prop_;
  PropLayout layout_;
};

struct ThrusterCounters {
  uint64_t latches = 0;             // command messages latched
  uint64_t ignored_min_on = 0;      // per-thruster requests dropped by T_min (§5.2 step 2)
  uint64_t split_sub_steps = 0;     // extra sub-steps created by valve/table events (§7.3); latch cuts not counted
};

class Vehicle {
 public:
  Vehicle(SpacecraftParams sc, PropulsionParams prop, const InitialConditions& ic);

  const VehicleModel& model() const { return model_; }
  const VehicleState& state() const { return x_; }
  void set_state(const VehicleState& x);  // for tests and scenario restarts
  int64_t t_ns() const { return t_ns_; }

  // §4.3 wheel command latch at the current wheel speeds (as Spacecraft).
  void latch_wheel_commands(const WheelArray& u_cmd);
  // External test force/torque about B, held until changed.
  void set_external(const Eigen::Vector3d& F_ext_B, const Eigen::Vector3d& L_ext_B);
  // New thruster command message: on-time requests [s] (num_thr).  Latched at
  // the next latch instant k*T_upd at or after now; a later message before
  // that instant replaces it (§5.2).
  void command_thrusters(const ThrusterArray& T_req);

  // Advance by dt_ns: Stribeck update at the step start (§4.6); sub-steps
  // split at latch instants, valve closings and Table breakpoints, each RK4
  // with fixed valve states (§7.3); MRP switch and tank clamp after each
  // sub-step.  A non-finite result is not committed; the run halts.
  StepStatus step(int64_t dt_ns);

  // Accessors (§13).
  Eigen::Vector3d r_BN_N() const { return x_.sc.segment<3>(StateLayout::r_BN_N); }
  Eigen::Vector3d v_BN_N() const { return x_.sc.segment<3>(StateLayout::v_BN_N); }
  Eigen::Vector3d sigma_BN() const { return x_.sc.segment<3>(StateLayout::sigma_BN); }
  Eigen::Vector3d omega_BN_B() const { return x_.sc.segment<3>(StateLayout::omega_BN_B); }
  double Omega(int i) const { return x_.sc(model_.spacecraft().layout().Omega(i)); }
  double m_prop(int k) const { return x_.prop(model_.prop_layout().m_p(k)); }
  double kappa(int j) const;               // [-] thrust factor now
  bool valve_open(int j) const;            // valve state just after now
  ThrusterEffect thruster_effect(int j) const;  // F, L about B, mdot now
  const ValveSchedule& schedule(int j) const { return in_.schedule[static_cast<size_t>(j)]; }
  MassProps mass_props() const { return model_.mass_props(x_); }
  EnergyMomentum energy_momentum() const { return model_.energy_momentum(x_); }
  const ThrusterCounters& counters() const { return counters_; }
  uint64_t mrp_switch_count() const { return switches_; }
  StepStatus status() const { return status_; }

 private:
  void latch_thrusters(int64_t t_L_ns);
  bool integrate_segment(int64_t t0_ns, int64_t t1_ns);
  double s_since_latch(int j, int64_t t_ns) const;

  VehicleModel model_;
  VehicleState x_;
  int64_t t_ns_ = 0;
  SubStepInputs in_;  // held wheel inputs, valve schedules, per-sub-step valve states
  ThrusterArray T_req_{};
  bool command_pending_ = false;
  WheelArray Omega_prev_{};
  bool first_step_ = true;
  uint64_t switches_ = 0;
  ThrusterCounters counters_;
  StepStatus status_ = StepStatus::Ok;
};

}  // namespace sim

#endif  // SIM_VEHICLE_H
