// environment_effectors: the Earth-orbit environment models of
// docs/environment.md as force/torque effectors of sim::Plant (sim/effector.h):
// gravity-gradient torque, faceted solar radiation pressure, faceted drag,
// and the magnetic torque of a residual dipole and magnetorquer rods.
// Frames: N inertial (mean equator and equinox of date, Earth-centred),
// E Earth-fixed, B body (origin at point B).  Units: SI.
// See docs/environment.md, "In the plant".
//
// Rate and hold.  Each effector splits its model into
//   * the environment: the quantities that depend on time and on the orbit
//     position (N components: position for gravity gradient, the Sun
//     direction and flux for SRP, the air density for drag, the field for
//     magnetism), and
//   * the body part: what depends on the attitude, the rates and the mass
//     properties (rotation to B, the inertia, the facet sums, m x B).
// With period_ns = 0 (exact) both are evaluated at every RK4 stage.  With
// period_ns = T > 0:
//   * the environment is sampled from the plant state at the first segment
//     start at or after each k T and held (in N) until the next sample (the
//     sample instants do not cut the plant's steps: with a plant step
//     dt > T it is sampled once per step);
//   * the body part is evaluated at the sample too, from the held
//     environment and the state there, and the load (F_B, L_B) is held in
//     B until the next sample, or until a setter changes it (density
//     scale, a rod's dipole): then it is evaluated again at the next plant
//     (sub-)step start; a derivative evaluated between steps takes the load
//     of its own state;
//   * the gravity-gradient effector also holds the inertia about the mass
//     centre (B components) from its sample.
// A setter (density scale, rod commands, faults) acts from the next step.
//
// Torque about B.  The plant sums forces and torques about point B.  A
// load made of a force F (through the facets' centres of pressure r_i) has
// L_B = sum r_i x F_i; its torque about the mass centre C is L_C = L_B - c x F
// (c = r_CB_B).  A pure couple (gravity gradient about C, m x B) has F = 0
// and so the same moment about every point: L_B = L_C.
//
// Accumulated angular momentum.  Each effector integrates the angular
// momentum it has given the spacecraft, H_N = int [NB] L_C dt (N components,
// about the mass centre), with the plant's own RK4 weights: over a sub-step
// of length h, h/6 (L1 + 2 L2 + 2 L3 + L4) of the four stage torques it
// added (with period_ns > 0 the held load's torque about C, C taken when
// the load was evaluated, rotated by each stage's [NB]).  Summed over every
// external source this is the change of the total angular momentum about
// the mass centre to the integrator's accuracy (and to the motion of C
// within a sub-step for held loads with a force: unbalanced rotors, drawn
// propellant).
//
// Each effector keeps a reference to its plant (the plant must outlive it;
// it is owned by that plant after Plant::add_effector) and a copy of the
// EarthContext.  None allocates after construction.
#ifndef SIM_ENVIRONMENT_EFFECTORS_H
#define SIM_ENVIRONMENT_EFFECTORS_H

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "sim/capacities.h"
#include "sim/earth_context.h"
#include "sim/effector.h"
#include "sim/magnetic_field.h"
#include "sim/magnetorquer.h"
#include "sim/plant.h"
#include "sim/surface_forces.h"

namespace sim {

// Force on the body and torque about point B at one evaluation.
struct BodyLoad {
  Eigen::Vector3d F_B = Eigen::Vector3d::Zero();  // [N]   B components
  Eigen::Vector3d L_B = Eigen::Vector3d::Zero();  // [N*m] about point B, B components
};

// The sampling machinery shared by the environment effectors.
class SampledEnvironmentEffector : public ForceTorqueEffector {
 public:
  int64_t period_ns() const { return period_ns_; }  // [ns] 0: every RK4 stage
  int64_t last_sample_ns() const { return sample_ns_; }  // [ns] time of the held sample

  // Pure: the load at plant time t_s [s] and state x, with the held
  // environment when period_ns > 0 (what accumulate adds at a stage).
  virtual BodyLoad load(double t_s, const StateVector& x) const = 0;

  // [N*m*s] angular momentum given to the spacecraft since the effector was
  // added: int [NB] L_C dt over the plant's RK4 sub-steps (see above).
  const Eigen::Vector3d& momentum_N() const { return H_N_; }

  void accumulate(const EffectorStage& stage, EffectorSums& sums) const final;
  void at_instant(int64_t t_ns) final;
  void begin_segment(int64_t t0_ns) final { t0_ns_ = t0_ns; }
  void begin_substep(double tau, double h) final;
  void end_substep() final;
  void prepare_now(int64_t t_ns) final;
  // The sampling and momentum state, then the derived class's (derived_state_io).
  void state_io(StateIO& io) final;

 protected:
  // period_ns >= 0, else std::invalid_argument naming `name`.period_ns.
  SampledEnvironmentEffector(const Plant& plant, const EarthContext& ctx, int64_t period_ns,
                             const char* name);
  // Evaluate and store the environment at plant time t_s and state x.
  virtual void sample(double t_s, const StateVector& x) = 0;
  // The derived class's held environment and settable members (state_io).
  virtual void derived_state_io(StateIO& io) = 0;
  // A setter changed the load: evaluate it again at the next step start.
  void refresh_load() { load_stale_ = true; }

  const Plant& plant_;
  EarthContext ctx_;

 private:
  void take_sample(int64_t t_ns);
  // Adds the stage's RK4-weighted torque about C (B components) in N to the sub-step sum.
  void add_stage_momentum(const EffectorStage& stage, const Eigen::Vector3d& L_C_B) const;

  int64_t period_ns_ = 0;
  // Momentum bookkeeping (no effect on the dynamics).  stage_ counts the
  // stages of the current sub-step (-1 outside one: a derivative evaluated
  // outside Plant::step adds nothing).
  Eigen::Vector3d H_N_ = Eigen::Vector3d::Zero();               // [N*m*s]
  double h_s_ = 0.0;                                             // [s] current sub-step
  mutable Eigen::Vector3d H_sub_N_ = Eigen::Vector3d::Zero();  // [N*m] sum of w_k L_k (exact)
  mutable Eigen::Matrix3d M_sub_ = Eigen::Matrix3d::Zero();    // [-] sum of w_k [NB]_k (held)
  mutable int stage_ = -1;
  int64_t t0_ns_ = 0;  // [ns] current segment start (or now)
  int64_t sample_ns_ = std::numeric_limits<int64_t>::min();  // [ns] last sample (min: none)
  BodyLoad held_load_;  // period_ns > 0: the load acting (held in B)
  Eigen::Vector3d held_L_C_B_ = Eigen::Vector3d::Zero();  // [N*m] its torque about C when evaluated
  bool load_stale_ = true;  // evaluate held_load_ at the next step start
  bool in_step_ = false;    // inside a step (else a derivative evaluates its own stage)
};

// ------------------------------------------------------- gravity gradient

struct GravityGradientParams {
  int64_t period_ns = 0;  // [ns] >= 0; 0 (default): the position every RK4 stage
};

// L = 3 mu/|R|^5 R_B x (I_C R_B) (sim/gravity_gradient.h) with mu the
// plant's (SpacecraftParams::mu), R the position of the mass centre C and
// I_C the full inertia about C at the stage: hub, wheels (rotor positions
// of fully coupled wheels at the stage angles) and tanks with their stage
// propellant, I_C = I_sc,B - m [c~][c~]^T.  A pure couple: added to L_B as is.
// Held (period_ns > 0): R in N and I_C in B, from the sample.
class GravityGradientEffector final : public SampledEnvironmentEffector {
 public:
  GravityGradientEffector(const Plant& plant, const EarthContext& ctx,
                          const GravityGradientParams& p = {});
  const char* kind() const override { return "gravity_gradient"; }
  BodyLoad load(double t_s, const StateVector& x) const override;

 private:
  void sample(double t_s, const StateVector& x) override;
  void derived_state_io(StateIO& io) override;
  Eigen::Vector3d R_held_N_ = Eigen::Vector3d::Zero();  // [m] held position of C
  Eigen::Matrix3d I_held_C_B_ = Eigen::Matrix3d::Zero();  // [kg*m^2] held inertia about C, B
  // No tanks and no fully-coupled wheel: the mass properties do not change
  // during the run, so c_B and I_C are formed once (the same operations on
  // the same operands as per evaluation: the same bits).
  bool fixed_mass_ = false;
  Eigen::Vector3d c_fixed_B_ = Eigen::Vector3d::Zero();    // [m]
  Eigen::Matrix3d I_fixed_C_B_ = Eigen::Matrix3d::Zero();  // [kg*m^2]
};

// --------------------------------------------- solar radiation pressure

struct SolarPressureParams {
  FacetSet facets;                  // validated (facets[i].<field>)
  int64_t period_ns = 1000000000;   // [ns] >= 0; default 1 s
};

// srp_load of sim/surface_forces.h, torque about B (r_ref = 0), with
// s = unit(r_Sun - r_B) and flux scale (1 AU/|r_Sun - r_B|)^2 times
// illumination_factor(r_B, r_Sun, shadow_radius) (umbra and penumbra).
// Held environment: s in N and the flux scale.
class SolarPressureEffector final : public SampledEnvironmentEffector {
 public:
  SolarPressureEffector(const Plant& plant, const EarthContext& ctx, const SolarPressureParams& p);
  const char* kind() const override { return "solar_pressure"; }
  BodyLoad load(double t_s, const StateVector& x) const override;
  const FacetSet& facets() const { return facets_; }

 private:
  void sample(double t_s, const StateVector& x) override;
  void derived_state_io(StateIO& io) override;
  FacetSet facets_;
  Eigen::Vector3d s_held_N_ = Eigen::Vector3d::UnitX();  // [-] held unit vector to the Sun
  double flux_held_ = 0.0;                               // [-] held flux scale x illumination
};

// ------------------------------------------------------------- drag

struct DragParams {
  FacetSet facets;                  // validated (facets[i].<field>)
  ExponentialAtmosphere atmosphere;  // scale: initial density scale factor
  int64_t period_ns = 1000000000;   // [ns] >= 0; default 1 s
};

// drag_load of sim/surface_forces.h, torque about B (r_ref = 0), with the
// velocity of B relative to the co-rotating atmosphere (wind_velocity_N,
// every stage) rotated to B and rho = scale x density(ellipsoid_height(r_B)).
// Held environment: the nominal density (scale 1).  The scale factor
// multiplies at every stage: set_density_scale acts from the next
// derivative evaluation.
class DragEffector final : public SampledEnvironmentEffector {
 public:
  DragEffector(const Plant& plant, const EarthContext& ctx, const DragParams& p);
  const char* kind() const override { return "drag"; }
  BodyLoad load(double t_s, const StateVector& x) const override;
  // >= 0 and finite, else std::invalid_argument naming "drag.atmosphere.scale".
  void set_density_scale(double scale);
  double density_scale() const { return atm_.scale; }
  const FacetSet& facets() const { return facets_; }

 private:
  void sample(double t_s, const StateVector& x) override;
  void derived_state_io(StateIO& io) override;
  FacetSet facets_;
  ExponentialAtmosphere atm_;
  double rho_held_ = 0.0;  // [kg/m^3] held nominal density (scale 1)
};

// --------------------------------------------------------- magnetism

enum class MagnetorquerHealth {
  Nominal = 0,
  FailedOff = 1,  // coil dead: the remanent dipole of the last command stays, commands ignored
  Stuck = 2,      // dipole frozen at its value when stuck, commands ignored
};

struct MagneticParams {
  Eigen::Vector3d m_residual_B = Eigen::Vector3d::Zero();  // [A*m^2] residual dipole, B
  std::vector<MagnetorquerParams> rods;  // (<= kMaxMagnetorquers) validated (rods[i].<field>)
  int igrf_degree = kIgrfMaxDegree;      // [-] 1 .. 13 (1: the tilted dipole)
  int64_t period_ns = 1000000000;        // [ns] >= 0; default 1 s
};

// L = (m_residual + sum of the rods' dipoles) x B_B, a pure couple; B_B =
// [BN] [EN]^T Igrf14(epoch year, degree).field_E([EN] r_B) with the
// coefficients fixed at the epoch's decimal year (in [2020, 2030]).
// Held environment: the field in N.  Rod commands act from the next
// derivative evaluation (between steps: over the whole next step).
class MagneticEffector final : public SampledEnvironmentEffector {
 public:
  MagneticEffector(const Plant& plant, const EarthContext& ctx, const MagneticParams& p);
  const char* kind() const override { return "magnetic"; }
  BodyLoad load(double t_s, const StateVector& x) const override;
  // [T] the field in B that load(t_s, x) acts with: the held field in N
  // (period_ns > 0) or the field at the state's position, rotated to B.
  Eigen::Vector3d field_B(double t_s, const StateVector& x) const;

  int num_rods() const { return num_rods_; }
  // Dipole commands [A*m^2] (num_rods), each times its scale factor, then
  // the rod's saturation (sim/magnetorquer.h); failed and stuck rods ignore theirs.
  void command_dipoles(const std::array<double, kMaxMagnetorquers>& m_cmd);
  void set_rod_health(int i, MagnetorquerHealth h);  // validated ("rods[i].health")
  void set_rod_scale(int i, double s);               // finite, >= 0 ("rods[i].scale"); next command
  MagnetorquerHealth rod_health(int i) const { return health_[static_cast<size_t>(i)]; }
  double rod_dipole(int i) const { return dipole_[static_cast<size_t>(i)]; }  // [A*m^2] along the axis
  const Magnetorquer& rod(int i) const { return rods_[static_cast<size_t>(i)]; }
  Eigen::Vector3d dipole_B() const { return m_total_B_; }  // [A*m^2] residual + rods, B
  Eigen::Vector3d field_held_N() const { return B_held_N_; }  // [T] held field, N
  // [T] the field model evaluated (not held) at plant time t_s [s] and
  // position r_N [m], N components (what a magnetometer reads).  The last
  // evaluation is kept with its arguments: a call with equal t_s and r_N (a
  // magnetometer sample and this effector's own sample at the same instant
  // and state) returns it without evaluating the model again (a pure
  // function of its arguments: the same result, nothing to save in a
  // checkpoint).
  Eigen::Vector3d field_N(double t_s, const Eigen::Vector3d& r_N) const;

 private:
  void sample(double t_s, const StateVector& x) override;
  void derived_state_io(StateIO& io) override;
  void refresh_dipole();

  Igrf14 igrf_;
  Eigen::Vector3d m_residual_B_;
  std::vector<Magnetorquer> rods_;  // sized once by the constructor
  int num_rods_ = 0;
  std::array<MagnetorquerHealth, kMaxMagnetorquers> health_{};
  std::array<double, kMaxMagnetorquers> scale_{};   // [-] command scale factors, 1 nominal
  std::array<double, kMaxMagnetorquers> dipole_{};  // [A*m^2] each rod's acting dipole
  Eigen::Vector3d m_total_B_ = Eigen::Vector3d::Zero();  // [A*m^2]
  Eigen::Vector3d B_held_N_ = Eigen::Vector3d::Zero();   // [T]
  // the last field_N evaluation and its arguments
  mutable double last_t_s_ = 0.0;                                  // [s]
  mutable Eigen::Vector3d last_r_N_ = Eigen::Vector3d::Zero();     // [m]
  mutable Eigen::Vector3d last_B_N_ = Eigen::Vector3d::Zero();     // [T]
  mutable bool has_last_ = false;
};

}  // namespace sim

#endif  // SIM_ENVIRONMENT_EFFECTORS_H
