// effector: the interface of a force/torque effector of sim::Plant
// (docs/dynamics.md §3 F_ext,B / L_ext,B, §5.4, §7.3).  Frames: B.  Units: SI.
//
// A force/torque effector adds a force and a torque about point B to the hub
// equations and may draw propellant from tanks; it has no integrated state of
// its own and no mass-property contribution.  The thruster set
// (sim/thruster_set.h) is one; a magnetorquer, a solar-pressure or a test
// load is another, added with Plant::add_effector without touching the rest.
// The Plant sums every effector's contribution onto the held external
// force/torque at each derivative evaluation, in list order (the thruster
// set first), as the old VehicleModel::derivatives summed its thrusters.
//
// Step protocol (Plant::step, all times of the plant clock, integer ns):
//   for each segment [t0, t1) of the step:
//     at_instant(t0)          discrete actions due at t0 (e.g. a command latch)
//     t1 = min over effectors of next_cut_ns(t0), and the step end
//     begin_segment(t0)
//     for each sub-step [tau, tau + h) of the segment (tau in s from t0):
//       next_event(tau, H, snap) proposes a split point inside (tau, H)
//       begin_substep(tau, h)  freeze discrete inputs over the sub-step
//       RK4: accumulate(stage) at every stage (pure, const)
//       end_substep()          advance discrete states to tau + h
//   after the step (and after any setter): prepare_now(t_ns), so that a
//   derivative evaluated outside a step sees the state "just after now".
// Only accumulate() runs inside RK4; none of the hooks may allocate.
#ifndef SIM_EFFECTOR_H
#define SIM_EFFECTOR_H

#include <cstdint>
#include <limits>

#include <Eigen/Dense>

#include "sim/capacities.h"
#include "sim/spacecraft.h"  // StateVector, StateLayout
#include "sim/state_io.h"

namespace sim {

// What an effector sees at one derivative evaluation.
struct EffectorStage {
  double t;                    // [s] time since the current segment start (the RK4 time)
  const StateVector& x;        // stage state
  const StateLayout& layout;   // named indices into x (m_p(k) for tanks)
  // [NB] of the stage's attitude, formed at the first call and shared by
  // every effector of this stage (stage-local cache, no allocation).
  const Eigen::Matrix3d& dcm_NB() const;

  mutable bool dcm_ready = false;                                  // cache state
  mutable Eigen::Matrix3d dcm_NB_cache = Eigen::Matrix3d::Zero();  // cache
};

// Running sums an effector adds to (initialised with the held external
// force/torque and zero flows).
struct EffectorSums {
  Eigen::Vector3d F_B;   // [N]    force on the body, B components
  Eigen::Vector3d L_B;   // [N*m]  torque about point B, B components
  TankArray m_p_dot{};   // [kg/s] (num_tanks) tank mass rates (a draw is negative)
};

class ForceTorqueEffector {
 public:
  virtual ~ForceTorqueEffector() = default;

  virtual const char* kind() const = 0;

  // Pure: add this effector's force, torque about B and tank mass rates at
  // the stage.  Must not allocate or change the effector.
  virtual void accumulate(const EffectorStage& stage, EffectorSums& sums) const = 0;

  // Step protocol hooks (see the header comment).  Defaults: an effector
  // whose inputs are held constant between steps.
  virtual void at_instant(int64_t /*t_ns*/) {}
  virtual int64_t next_cut_ns(int64_t /*t_ns*/) const { return std::numeric_limits<int64_t>::max(); }
  virtual void begin_segment(int64_t /*t0_ns*/) {}
  virtual double next_event(double /*tau*/, double H, double /*snap*/) const { return H; }
  virtual void begin_substep(double /*tau*/, double /*h*/) {}
  virtual void end_substep() {}
  virtual void prepare_now(int64_t /*t_ns*/) {}

  // Its run state for a checkpoint (sim/state_io.h): every member that
  // changes during a run.  Pure, so that a new effector cannot be added
  // without saying what it saves.
  virtual void state_io(StateIO& io) = 0;
};

}  // namespace sim

#endif  // SIM_EFFECTOR_H
