// magnetorquer_drive: how a run's magnetorquer rods follow their dipole
// commands (scenario `magnetorquer_drive`, docs/environment.md).
//
// Dipole mode: the harness commands the rods (sim::MagneticEffector::
// command_dipoles) at each control instant; they hold the dipole until the next.
// PWM mode: MtqPwmDriver, a force/torque effector of the plant with no load
// of its own, drives each rod at sign(c) m_max for duty x T from each cycle
// start (duty = min(|c| / m_max, 1), on-time rounded to whole ns) and off
// (remanence) for the rest of the cycle; cycles of T start at the command
// instant and repeat until the next command.  The switch instants cut the
// plant's steps (next_cut_ns), so they are exact, not quantised to the step.
#ifndef HARNESS_SRC_MAGNETORQUER_DRIVE_H
#define HARNESS_SRC_MAGNETORQUER_DRIVE_H

#include <array>
#include <cstdint>

#include "sim/capacities.h"
#include "sim/effector.h"
#include "sim/environment_effectors.h"

namespace harness {

class MtqPwmDriver final : public sim::ForceTorqueEffector {
 public:
  // `mag` (owned by the same plant, added before this) carries the rods;
  // period_ns > 0.
  MtqPwmDriver(sim::MagneticEffector& mag, int64_t period_ns);
  const char* kind() const override { return "magnetorquer_pwm"; }
  void accumulate(const sim::EffectorStage&, sim::EffectorSums&) const override {}

  // Dipole commands [A*m^2] given at t_ns (between steps): a cycle starts there.
  void command(const sim::MagnetorquerArray& m_cmd, int64_t t_ns);
  int64_t period_ns() const { return period_ns_; }
  int64_t on_ns(int i) const { return on_ns_[static_cast<size_t>(i)]; }  // [ns] on-time per cycle

  void at_instant(int64_t t_ns) override;               // the rods' levels for the segment from t_ns
  int64_t next_cut_ns(int64_t t_ns) const override;     // the next switch instant after t_ns
  void state_io(sim::StateIO& io) override
  {
    io.value("mtq_pwm.start_ns", start_ns_);
    io.value("mtq_pwm.on_ns", on_ns_);
    io.value("mtq_pwm.level", level_);
    io.value("mtq_pwm.out", out_);
  }

 private:
  sim::MagneticEffector& mag_;
  int64_t period_ns_;
  int64_t start_ns_ = -1;  // [ns] first cycle start; -1: no command yet
  std::array<int64_t, sim::kMaxMagnetorquers> on_ns_{};  // [ns] on-time per cycle
  sim::MagnetorquerArray level_{};                                     // [A*m^2] +-m_max while on
  sim::MagnetorquerArray out_{};                                       // [A*m^2] what the rods are commanded now
};

}  // namespace harness

#endif  // HARNESS_SRC_MAGNETORQUER_DRIVE_H
