// environment_effectors: see sim/environment_effectors.h.
#include "sim/environment_effectors.h"

#include <cmath>
#include <string>

#include "sim/attitude.h"
#include "sim/environment.h"
#include "sim/gravity_gradient.h"
#include "sim/units.h"
#include "validate_util.h"

namespace sim {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

int64_t checked_period(int64_t period_ns, const char* name)
{
  if (period_ns < 0) detail::fail(std::string(name) + ".period_ns", static_cast<double>(period_ns), "must be >= 0");
  return period_ns;
}

Vector3d position_N(const StateVector& x) { return x.segment<3>(StateLayout::r_BN_N); }

Matrix3d dcm_BN(const StateVector& x) { return dcm_BN_from_sigma(x.segment<3>(StateLayout::sigma_BN)); }

}  // namespace

// ---------------------------------------------------------- sampling base

SampledEnvironmentEffector::SampledEnvironmentEffector(const Plant& plant, const EarthContext& ctx,
                                                       int64_t period_ns, const char* name)
    : plant_(plant), ctx_(ctx), period_ns_(checked_period(period_ns, name))
{
}

void SampledEnvironmentEffector::take_sample(int64_t t_ns)
{
  sample(seconds_from_ns(t_ns), plant_.state());
  sample_ns_ = t_ns;
  load_stale_ = true;  // the load of the new sample, at the step start that follows
}

void SampledEnvironmentEffector::at_instant(int64_t t_ns)
{
  // The first segment start at or after the next multiple of the period.
  if (period_ns_ == 0) return;
  const bool none = sample_ns_ == std::numeric_limits<int64_t>::min();
  if (none || t_ns / period_ns_ > sample_ns_ / period_ns_) take_sample(t_ns);
}

void SampledEnvironmentEffector::state_io(StateIO& io)
{
  io.value("environment.H_N", H_N_);
  io.value("environment.h_s", h_s_);
  io.value("environment.H_sub_N", H_sub_N_);
  io.value("environment.M_sub", M_sub_);
  io.value("environment.stage", stage_);
  io.value("environment.t0_ns", t0_ns_);
  io.value("environment.sample_ns", sample_ns_);
  io.value("environment.held_load", held_load_);
  io.value("environment.held_L_C_B", held_L_C_B_);
  io.value("environment.load_stale", load_stale_);
  io.value("environment.in_step", in_step_);
  derived_state_io(io);
}

void SampledEnvironmentEffector::prepare_now(int64_t t_ns)
{
  t0_ns_ = t_ns;
  // First use (added to the plant): a sample of now, so that a derivative
  // evaluated before the first step sees an environment.
  if (period_ns_ > 0 && sample_ns_ == std::numeric_limits<int64_t>::min()) take_sample(t_ns);
  in_step_ = false;  // a derivative between steps: the load of its own state
}

void SampledEnvironmentEffector::begin_substep(double tau, double h)
{
  h_s_ = h;
  H_sub_N_.setZero();
  M_sub_.setZero();
  stage_ = 0;
  if (period_ns_ == 0) return;
  in_step_ = true;
  if (!load_stale_) return;  // held in B since the sample
  // the plant's state is the (sub-)step's start here
  const StateVector& x = plant_.state();
  held_load_ = load(seconds_from_ns(t0_ns_) + tau, x);
  held_L_C_B_ = held_load_.L_B;
  if (!held_load_.F_B.isZero(0.0))
    held_L_C_B_ -= plant_.model().mass_centre(x, plant_.hub_with_propellant(x)).c_B.cross(held_load_.F_B);
  load_stale_ = false;
}

void SampledEnvironmentEffector::accumulate(const EffectorStage& stage, EffectorSums& sums) const
{
  if (period_ns_ > 0 && in_step_) {
    sums.F_B += held_load_.F_B;
    sums.L_B += held_load_.L_B;
    if (stage_ < 0 || stage_ >= 4) return;
    // RK4 weights b = 1/6, 1/3, 1/3, 1/6 (sim/rk4.h): 1, 2, 2, 1 here, h/6 at the end.
    const double w = (stage_ == 0 || stage_ == 3) ? 1.0 : 2.0;
    ++stage_;
    if (!held_L_C_B_.isZero(0.0)) M_sub_ += w * stage.dcm_NB();
    return;
  }
  const BodyLoad l = load(seconds_from_ns(t0_ns_) + stage.t, stage.x);
  sums.F_B += l.F_B;
  sums.L_B += l.L_B;
  if (stage_ < 0 || stage_ >= 4) return;
  Vector3d L_C = l.L_B;
  if (!l.F_B.isZero(0.0))
    L_C -= plant_.model().mass_centre(stage.x, plant_.hub_with_propellant(stage.x)).c_B.cross(l.F_B);
  add_stage_momentum(stage, L_C);
}

void SampledEnvironmentEffector::add_stage_momentum(const EffectorStage& stage, const Vector3d& L_C_B) const
{
  const double w = (stage_ == 0 || stage_ == 3) ? 1.0 : 2.0;
  ++stage_;
  if (L_C_B.isZero(0.0)) return;
  H_sub_N_ += w * (stage.dcm_NB() * L_C_B);
}

void SampledEnvironmentEffector::end_substep()
{
  if (stage_ == 4) H_N_ += (h_s_ / 6.0) * (period_ns_ > 0 ? Vector3d(M_sub_ * held_L_C_B_) : H_sub_N_);
  stage_ = -1;
}

// ------------------------------------------------------- gravity gradient

GravityGradientEffector::GravityGradientEffector(const Plant& plant, const EarthContext& ctx,
                                                 const GravityGradientParams& p)
    : SampledEnvironmentEffector(plant, ctx, p.period_ns, "gravity_gradient")
{
  fixed_mass_ = plant.num_tanks() == 0;
  for (const ReactionWheelParams& w : plant.model().params().wheels)
    fixed_mass_ = fixed_mass_ && w.model != WheelModel::FullyCoupled;
  if (!fixed_mass_) return;
  const MassProps mp = plant.mass_props();
  c_fixed_B_ = mp.c_B;
  I_fixed_C_B_ = mp.I_sc_B - parallel_axis(mp.m_sc, mp.c_B);
}

void GravityGradientEffector::derived_state_io(StateIO& io)
{
  io.value("gravity_gradient.R_held_N", R_held_N_);
  io.value("gravity_gradient.I_held_C_B", I_held_C_B_);
}

void GravityGradientEffector::sample(double /*t_s*/, const StateVector& x)
{
  const MassProps mp = plant_.model().mass_props(x, plant_.hub_with_propellant(x));
  I_held_C_B_ = mp.I_sc_B - parallel_axis(mp.m_sc, mp.c_B);
  R_held_N_ = position_N(x) + dcm_BN(x).transpose() * mp.c_B;
}

BodyLoad GravityGradientEffector::load(double /*t_s*/, const StateVector& x) const
{
  const Matrix3d C_BN = dcm_BN(x);
  BodyLoad l;
  if (period_ns() > 0) {
    l.L_B = gravity_gradient_torque(plant_.model().params().mu, C_BN * R_held_N_, I_held_C_B_);
    return l;
  }
  if (fixed_mass_) {
    const Vector3d R_N = position_N(x) + C_BN.transpose() * c_fixed_B_;
    l.L_B = gravity_gradient_torque(plant_.model().params().mu, C_BN * R_N, I_fixed_C_B_);
    return l;
  }
  const MassProps mp = plant_.model().mass_props(x, plant_.hub_with_propellant(x));
  const Matrix3d I_C = mp.I_sc_B - parallel_axis(mp.m_sc, mp.c_B);  // [kg*m^2] about C
  const Vector3d R_N = position_N(x) + C_BN.transpose() * mp.c_B;
  l.L_B = gravity_gradient_torque(plant_.model().params().mu, C_BN * R_N, I_C);  // a couple: about C = about B
  return l;
}

// --------------------------------------------- solar radiation pressure

SolarPressureEffector::SolarPressureEffector(const Plant& plant, const EarthContext& ctx,
                                             const SolarPressureParams& p)
    : SampledEnvironmentEffector(plant, ctx, p.period_ns, "solar_pressure"), facets_(p.facets)
{
  validate(facets_, "solar_pressure.facets");
}

void SolarPressureEffector::derived_state_io(StateIO& io)
{
  io.value("solar_pressure.s_held_N", s_held_N_);
  io.value("solar_pressure.flux_held", flux_held_);
}

void SolarPressureEffector::sample(double t_s, const StateVector& x)
{
  const Vector3d r = position_N(x);
  const Vector3d r_sun = ctx_.sun_position_N(t_s);
  s_held_N_ = (r_sun - r).normalized();
  flux_held_ = solar_flux_scale(r, r_sun) * illumination_factor(r, r_sun, ctx_.params().shadow_radius);
}

BodyLoad SolarPressureEffector::load(double t_s, const StateVector& x) const
{
  Vector3d s_N = s_held_N_;
  double flux = flux_held_;
  if (period_ns() == 0) {
    const Vector3d r = position_N(x);
    const Vector3d r_sun = ctx_.sun_position_N(t_s);
    s_N = (r_sun - r).normalized();
    flux = solar_flux_scale(r, r_sun) * illumination_factor(r, r_sun, ctx_.params().shadow_radius);
  }
  BodyLoad l;
  if (flux == 0.0 || facets_.count == 0) return l;  // umbra: nothing
  const SurfaceLoad s = srp_load(facets_, dcm_BN(x) * s_N, flux);  // about B (r_ref = 0)
  l.F_B = s.F_B;
  l.L_B = s.L_B;
  return l;
}

// ------------------------------------------------------------- drag

DragEffector::DragEffector(const Plant& plant, const EarthContext& ctx, const DragParams& p)
    : SampledEnvironmentEffector(plant, ctx, p.period_ns, "drag"), facets_(p.facets)
{
  validate(facets_, "drag.facets");
  validate(p.atmosphere, "drag.atmosphere");
  atm_ = p.atmosphere;
}

void DragEffector::derived_state_io(StateIO& io)
{
  io.value("drag.density_scale", atm_.scale);  // settable (events)
  io.value("drag.rho_held", rho_held_);
}

void DragEffector::set_density_scale(double scale)
{
  // Checked here (a validate() call would form the field name on every call).
  if (!(scale >= 0.0) || !std::isfinite(scale)) detail::fail("drag.atmosphere.scale", scale, "must be finite and >= 0");
  atm_.scale = scale;
  refresh_load();
}

void DragEffector::sample(double /*t_s*/, const StateVector& x)
{
  rho_held_ = density(ExponentialAtmosphere{}, ellipsoid_height(position_N(x)));
}

BodyLoad DragEffector::load(double /*t_s*/, const StateVector& x) const
{
  BodyLoad l;
  if (facets_.count == 0) return l;
  const Vector3d r = position_N(x);
  const double rho_nominal = period_ns() > 0 ? rho_held_ : density(ExponentialAtmosphere{}, ellipsoid_height(r));
  const Vector3d v_rel_N = wind_velocity_N(r, x.segment<3>(StateLayout::v_BN_N));
  const SurfaceLoad s = drag_load(facets_, dcm_BN(x) * v_rel_N, atm_.scale * rho_nominal);  // about B
  l.F_B = s.F_B;
  l.L_B = s.L_B;
  return l;
}

// --------------------------------------------------------- magnetism

namespace {
Igrf14 make_igrf(const EarthContext& ctx, int degree)
{
  if (degree < 1 || degree > kIgrfMaxDegree) detail::fail("magnetic.igrf_degree", degree, "must be in [1, 13]");
  return Igrf14(ctx.decimal_year(), degree);
}
}  // namespace

MagneticEffector::MagneticEffector(const Plant& plant, const EarthContext& ctx, const MagneticParams& p)
    : SampledEnvironmentEffector(plant, ctx, p.period_ns, "magnetic"),
      igrf_(make_igrf(ctx, p.igrf_degree)),
      m_residual_B_(p.m_residual_B)
{
  detail::require_finite("magnetic.m_residual_B", m_residual_B_);
  if (p.rods.size() > static_cast<size_t>(kMaxMagnetorquers))
    detail::fail("magnetic.rods.size()", static_cast<double>(p.rods.size()), "must be <= sim::kMaxMagnetorquers");
  num_rods_ = static_cast<int>(p.rods.size());
  rods_.reserve(p.rods.size());
  for (size_t i = 0; i < p.rods.size(); ++i)
    rods_.emplace_back(p.rods[i], ("magnetic.rods[" + std::to_string(i) + "]").c_str());
  scale_.fill(1.0);
  refresh_dipole();
}

void MagneticEffector::refresh_dipole()
{
  Vector3d m = m_residual_B_;
  for (int i = 0; i < num_rods_; ++i) {
    const auto ui = static_cast<size_t>(i);
    dipole_[ui] = rods_[ui].dipole();
    m += rods_[ui].dipole_B();
  }
  if (m != m_total_B_) refresh_load();  // a new dipole acts from the next step start
  m_total_B_ = m;
}

void MagneticEffector::command_dipoles(const std::array<double, kMaxMagnetorquers>& m_cmd)
{
  for (int i = 0; i < num_rods_; ++i) {
    const auto ui = static_cast<size_t>(i);
    if (health_[ui] != MagnetorquerHealth::Nominal) continue;
    rods_[ui].command(scale_[ui] * m_cmd[ui]);
  }
  refresh_dipole();
}

void MagneticEffector::set_rod_health(int i, MagnetorquerHealth h)
{
  if (i < 0 || i >= num_rods_) detail::fail("magnetorquer index", i, "must be in [0, num_rods)");
  const int hv = static_cast<int>(h);
  if (hv < 0 || hv > 2)
    detail::fail("magnetic.rods[" + std::to_string(i) + "].health", hv, "must be Nominal, FailedOff or Stuck");
  const auto ui = static_cast<size_t>(i);
  health_[ui] = h;
  if (h == MagnetorquerHealth::FailedOff) rods_[ui].command(0.0);  // coil off: remanence only
  refresh_dipole();
}

void MagneticEffector::set_rod_scale(int i, double s)
{
  if (i < 0 || i >= num_rods_) detail::fail("magnetorquer index", i, "must be in [0, num_rods)");
  if (!(s >= 0.0) || !std::isfinite(s))
    detail::fail("magnetic.rods[" + std::to_string(i) + "].scale", s, "must be finite and >= 0");
  scale_[static_cast<size_t>(i)] = s;
}

Vector3d MagneticEffector::field_N(double t_s, const Vector3d& r_N) const
{
  // bitwise equality of the arguments (a NaN never matches: evaluated again)
  if (has_last_ && t_s == last_t_s_ && r_N == last_r_N_) return last_B_N_;
  const Matrix3d C_EN = ctx_.dcm_EN(t_s);
  last_B_N_ = C_EN.transpose() * igrf_.field_E(C_EN * r_N);
  last_t_s_ = t_s;
  last_r_N_ = r_N;
  has_last_ = true;
  return last_B_N_;
}

void MagneticEffector::derived_state_io(StateIO& io)
{
  for (Magnetorquer& r : rods_) r.state_io(io);
  io.value("magnetic.health", health_);
  io.value("magnetic.scale", scale_);
  io.value("magnetic.dipole", dipole_);
  io.value("magnetic.m_total_B", m_total_B_);
  io.value("magnetic.B_held_N", B_held_N_);
}

void MagneticEffector::sample(double t_s, const StateVector& x) { B_held_N_ = field_N(t_s, position_N(x)); }

Vector3d MagneticEffector::field_B(double t_s, const StateVector& x) const
{
  const Vector3d B_N = period_ns() > 0 ? B_held_N_ : field_N(t_s, position_N(x));
  return dcm_BN(x) * B_N;
}

BodyLoad MagneticEffector::load(double t_s, const StateVector& x) const
{
  BodyLoad l;
  if (m_total_B_.isZero(0.0)) return l;
  l.L_B = magnetic_torque(m_total_B_, field_B(t_s, x));  // a couple: about C = about B
  return l;
}

}  // namespace sim
