// plant_builder: Scenario -> the plant of a run, and the main-engine burn
// schedule.  The loop sees the plant only through RunPlant.
#ifndef HARNESS_PLANT_BUILDER_H
#define HARNESS_PLANT_BUILDER_H

#include <cstdint>
#include <memory>

#include <Eigen/Dense>

#include "harness/scenario.h"
#include "sim/spacecraft.h"
#include "sim/thruster.h"
#include "sim/vehicle.h"

namespace harness {

// The plant of one run: a sim::Spacecraft (hub + wheels) or, with
// thrusters, a sim::Vehicle, behind one set of calls.
class RunPlant {
 public:
  const char* kind() const { return veh_ ? "sim::Vehicle" : "sim::Spacecraft"; }
  int num_rw() const { return n_rw_; }
  int num_thr() const { return n_thr_; }
  int num_tanks() const { return veh_ ? veh_->model().num_tanks() : 0; }
  const sim::StateVector& x() const { return veh_ ? veh_->state().sc : craft_->state(); }
  sim::MassProps mass_props() const { return veh_ ? veh_->mass_props() : craft_->mass_props(); }
  sim::EnergyMomentum energy_momentum() const { return veh_ ? veh_->energy_momentum() : craft_->energy_momentum(); }
  double Omega(int i) const { return veh_ ? veh_->Omega(i) : craft_->Omega(i); }
  double u_s(int i) const { return veh_ ? u_held_[static_cast<size_t>(i)] : craft_->u_s(i); }
  double m_prop(int k) const { return veh_ ? veh_->m_prop(k) : 0.0; }
  double m_prop0(int k) const { return veh_->model().propulsion().tanks[static_cast<size_t>(k)].m_p0; }
  double thrust(int j) const { return veh_->thruster_effect(j).F_B.norm(); }
  int64_t thruster_period_ns() const { return veh_ ? veh_->model().propulsion().command.T_upd_ns : 0; }
  void latch_wheels(const sim::WheelArray& u);
  void command_thrusters(const sim::ThrusterArray& T) { veh_->command_thrusters(T); }
  sim::StepStatus step(int64_t dt_ns) { return veh_ ? veh_->step(dt_ns) : craft_->step(static_cast<double>(dt_ns) / 1e9); }

 private:
  friend RunPlant build_plant(const Scenario& sc);
  std::unique_ptr<sim::Spacecraft> craft_;
  std::unique_ptr<sim::Vehicle> veh_;
  sim::WheelArray u_held_{};  // Vehicle: latched wheel commands (it keeps them privately)
  int n_rw_ = 0, n_thr_ = 0;
};

// Builds the plant; throws ScenarioError (at the key's line) when the plant
// rejects the configuration.
RunPlant build_plant(const Scenario& sc);

// Main-engine burn: the engine opens at the first thruster command instant
// at or after burn.start and closes at start + duration.
struct BurnSchedule {
  int engine = -1;        // plant index of the engine, -1 without a burn
  int64_t on_ns = 0;      // [ns]
  int64_t off_ns = 0;     // [ns]
  int64_t T_upd_ns = 0;   // [ns] thruster command period
  // On-time [s] of the engine for the command latched at the first command
  // instant at or after now_ns (0 outside the burn).
  double on_time(int64_t now_ns) const;
};
BurnSchedule burn_schedule(const Scenario& sc, const RunPlant& plant);

// Truth thrust axis of a thruster misaligned by `delta` [rad] (see .cpp).
Eigen::Vector3d misaligned_axis(const Eigen::Vector3d& d, double delta);

}  // namespace harness

#endif  // HARNESS_PLANT_BUILDER_H
