// tasks.cpp: the bodies of the tick protocol's tasks.
#include "core/tasks.h"
#include "core/convert.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "sim/attitude.h"
#include "sim/environment.h"
#include "sim/environment_effectors.h"

namespace harness {

double principal_angle(const Eigen::Vector3d& sigma_BN, const Eigen::Vector3d& sigma_RN)
{
  const Eigen::Vector4d b = sim::quaternion_from_sigma(sigma_BN), r = sim::quaternion_from_sigma(sigma_RN);
  // q_BR = q_BN (x) q_RN^-1: scalar part and vector norm
  const double q0 = b(0) * r(0) + b.tail<3>().dot(r.tail<3>());
  const Eigen::Vector3d qv = r(0) * b.tail<3>() - b(0) * r.tail<3>() - b.tail<3>().cross(r.tail<3>());
  return 2.0 * std::atan2(qv.norm(), std::fabs(q0));
}

void TruthTask::operator()(uint64_t k) const
{
  const sim::Plant& p = *plant;
  const sim::StateVector& x = p.state();
  const sim::MassCentre mp = p.mass_centre();
  // in place: every field is set below, or stays 0 (entries beyond the
  // run's wheels and thrusters, never written)
  TruthMsg& t = out.edit();
  for (int i = 0; i < 3; ++i) {
    t.r_BN_N[i] = x(sim::StateLayout::r_BN_N + i);
    t.v_BN_N[i] = x(sim::StateLayout::v_BN_N + i);
    t.sigma_BN[i] = x(sim::StateLayout::sigma_BN + i);
    t.omega_BN_B[i] = x(sim::StateLayout::omega_BN_B + i);
    t.r_CoM_B[i] = mp.c_B(i);
  }
  // mass centre: r_C = r_B + [NB] c, v_C = v_B + [NB](omega x c) (c' neglected, docs/dynamics.md §5.6)
  const Eigen::Matrix3d NB = sim::dcm_BN_from_sigma(ev(t.sigma_BN)).transpose();
  const Eigen::Vector3d rC = ev(t.r_BN_N) + NB * mp.c_B;
  const Eigen::Vector3d vC = ev(t.v_BN_N) + NB * ev(t.omega_BN_B).cross(mp.c_B);
  for (int i = 0; i < 3; ++i) {
    t.r_CN_N[i] = rC(i);
    t.v_CN_N[i] = vC(i);
  }
  t.m_sc = mp.m_sc;
  t.m_prop = 0.0;
  for (int k2 = 0; k2 < p.num_tanks(); ++k2) t.m_prop += p.m_prop(k2);
  for (int i = 0; i < p.num_rw(); ++i) {
    t.Omega[i] = p.Omega(i);
    t.u_s[i] = p.u_s(i);
  }
  for (int j = 0; j < p.num_thr(); ++j) t.F_thr[j] = p.thruster_effect(j).F_B.norm();
  static_assert(kMaxEnvSources == kNumEnvSources, "one torque per environment source");
  const double t_s = static_cast<double>(k * tick_ns) * 1e-9;
  // without environment sources the per-source fields stay 0 from the start
  // (nothing else writes them), so they are set only when a source is on
  const bool any_env = std::any_of(env.begin(), env.end(), [](const auto* e) { return e != nullptr; });
  for (int s = 0; any_env && s < kNumEnvSources; ++s) {
    Eigen::Vector3d L_C = Eigen::Vector3d::Zero();
    if (const sim::SampledEnvironmentEffector* e = env[static_cast<size_t>(s)]) {
      const sim::BodyLoad l = e->load(t_s, x);
      L_C = l.L_B - mp.c_B.cross(l.F_B);
    }
    put3(t.L_env_C_B[s], L_C);
  }
  environment_truth(t, k * tick_ns, t_s, any_env);
  out.publish(k * tick_ns);
}

void TruthTask::environment_truth(TruthMsg& t, uint64_t t_ns, double t_s, bool any_env) const
{
  const sim::Plant& p = *plant;
  const Eigen::Vector3d r_B = ev(t.r_BN_N);
  t.illumination =
      sun && sun->dated() ? sun->illumination(r_B, sun->position_N(static_cast<int64_t>(t_ns))) : 0.0;
  if (!any_env) return;  // the field and the momenta stay 0 (see operator())
  const auto* mag = static_cast<const sim::MagneticEffector*>(env[static_cast<size_t>(EnvSource::Magnetic)]);
  // index Magnetic holds a MagneticEffector
  put3(t.field_B, mag ? mag->field_B(t_s, p.state()) : Eigen::Vector3d(Eigen::Vector3d::Zero()));
  for (int s = 0; s < kNumEnvSources; ++s) {
    const sim::SampledEnvironmentEffector* e = env[static_cast<size_t>(s)];
    put3(t.H_env_N[s], e ? e->momentum_N() : Eigen::Vector3d(Eigen::Vector3d::Zero()));
  }
  Eigen::Vector3d h_B = Eigen::Vector3d::Zero();
  for (int i = 0; i < p.num_rw(); ++i) h_B += p.wheel_params(i).J_s * p.Omega(i) * p.model().wheel_derived(i).gs_hat_B;
  put3(t.H_wheels_N, sim::dcm_BN_from_sigma(ev(t.sigma_BN)).transpose() * h_B);
}

void BurnMonitor::snap(Snap& s, double t, const TruthMsg& tr) const
{
  s.set = true;
  s.t = t;
  s.m = tr.m_sc;
  for (int k = 0; k < plant->num_tanks(); ++k) s.m_p[static_cast<size_t>(k)] = plant->m_prop(k);
  s.dv_ng = dv_ng;
  s.r = ev(tr.r_CN_N);
  s.v = ev(tr.v_CN_N);
}

void BurnMonitor::operator()(uint64_t k)
{
  const TruthMsg& t = truth.read();
  const Eigen::Vector3d r = ev(t.r_CN_N), v = ev(t.v_CN_N);
  if (have_prev) {
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    if (mu > 0.0) g = 0.5 * (sim::point_mass_gravity(mu, r_prev) + sim::point_mass_gravity(mu, r));
    const sim::SpacecraftParams& sp = plant->model().params();
    if (mu > 0.0 && sp.J2 != 0.0)  // environment.j2: the plant's gravity has it too
      g += 0.5 * (sim::j2_acceleration(mu, sp.J2, sp.R_J2, r_prev) + sim::j2_acceleration(mu, sp.J2, sp.R_J2, r));
    dv_ng += (v - v_prev) - dt * g;
  }
  have_prev = true;
  r_prev = r;
  v_prev = v;
  if (burn.engine >= 0) {
    const int64_t t_ns = static_cast<int64_t>(k * tick_ns);
    const double tt = static_cast<double>(t_ns) * 1e-9;
    if (!start.set && t_ns >= burn.on_ns) snap(start, tt, t);
    // the engine is off (and its thrust decayed, 5 time constants) at burn end
    if (start.set && !end.set && t_ns >= burn.off_ns && t.F_thr[burn.engine] < 1e-3 * engine_F_max)
      snap(end, tt, t);
  }
  BurnStateMsg m{};
  for (int i = 0; i < 3; ++i) m.dv_ng_N[i] = dv_ng(i);
  m.in_burn = start.set && !end.set ? 1 : 0;
  out.write(m, k * tick_ns);
}

void SampleSensorsTask::operator()(uint64_t k) const
{
  // in place: the held outputs of the models not due stay
  if (sensors->sample(k, out.edit())) out.publish(k * tick_ns);
}

void CssTask::operator()(uint64_t k) const
{
  sensors->read_css(k, out.edit());  // in place: the readings of the run's sensors (the rest stay 0)
  out.publish(k * tick_ns);
}

void FswInputTask::operator()(uint64_t k) const
{
  static const SensorSampleMsg kNoSamples{};
  static const CssMsg kNoCss{};
  FswAcsSensorMsg& msg = out.edit();  // in place: fsw_input sets the whole message
  sensors->fsw_input(k * tick_ns, truth.read(), samples.valid() ? samples.read() : kNoSamples,
                     css.valid() ? css.read() : kNoCss, mag.valid() ? &mag.read() : nullptr, msg);
  out.publish(msg.t_ns);
}

void FswTask::operator()(uint64_t k)
{
  const uint64_t t_ns = k * tick_ns;
  if (cmd.valid() && cmd.write_count() != cmd_seen) {  // a new command: in force from this cycle
    cmd_seen = cmd.write_count();
    fsw->command(cmd.read());
  }
  // in place: the endpoint writes both messages when it delivers, and
  // throws (FswEndpointError) before writing either when it cannot
  FswAcsHealthMsg& h = health.edit();
  fsw->cycle(in.read(), act.edit(), h);
  act.publish(t_ns);
  health.publish(t_ns);
  if (has_sun) {
    // the css_sun estimate the cycle used
    SunHeadingMsg s{};
    copy3(s.sun_B, h.sun_hat_B);
    s.valid = h.sun_valid;
    s.num_lit = h.num_lit;
    sun.write(s, t_ns);
  }
}

void ActuatorTask::operator()(uint64_t k) const
{
  const FswAcsActuatorMsg& a = in.read();
  PlantCmdMsg& c = out.edit();  // in place: the run's wheels and thrusters set (entries beyond them stay 0)
  for (int i = 0; i < n_rw; ++i) c.u_s[i] = a.wheels_active ? static_cast<double>(a.u_s[i]) : 0.0;
  for (int j = 0; j < n_thr; ++j) c.T_on[j] = 0.0;
  if (a.thrusters_active)
    for (int i = 0; i < n_acs; ++i) c.T_on[acs_to_plant[static_cast<size_t>(i)]] = static_cast<double>(a.t_on[i]);
  if (burn.engine >= 0) c.T_on[burn.engine] = burn.on_time(static_cast<int64_t>(k * tick_ns));
  out.publish(k * tick_ns);
  if (n_mtq > 0) {  // the rods: the FSW's dipoles, or off
    MtqCmdMsg m{};
    if (a.mtq_active)
      for (int i = 0; i < n_mtq; ++i) m.m_cmd[i] = static_cast<double>(a.m_cmd[i]);
    mtq.write(m, k * tick_ns);
  }
}

void PlantInputTask::operator()(uint64_t) const
{
  const PlantCmdMsg& c = in.read();
  static_assert(kMaxRw == sim::kMaxWheels, "the message holds a command per plant wheel");
  plant->latch_wheel_commands(c.u_s);  // the message's own array, num_rw entries read
  if (plant->num_thr() > 0) {
    sim::ThrusterArray T{};
    for (int j = 0; j < plant->num_thr(); ++j) T[static_cast<size_t>(j)] = c.T_on[j];
    plant->command_thrusters(T);
  }
}

void MagnetometerTask::operator()(uint64_t k) const
{
  MagnetometerMsg m = out.channel().value();  // the held reading
  sensors->magnetometer(k, m);
  out.write(m, k * tick_ns);
}

void MagnetorquerTask::operator()(uint64_t k) const
{
  const MtqCmdMsg& c = in.read();
  sim::MagnetorquerArray m{};
  for (int i = 0; i < mag->num_rods(); ++i) m[static_cast<size_t>(i)] = c.m_cmd[i];
  if (pwm) pwm->command(m, static_cast<int64_t>(k * tick_ns));
  else mag->command_dipoles(m);
}

void MtqStateTask::operator()(uint64_t k) const
{
  MtqStateMsg s{};
  for (int i = 0; i < mag->num_rods(); ++i) {
    s.dipole[i] = mag->rod_dipole(i);
    s.power[i] = mag->rod(i).power();
  }
  out.write(s, k * tick_ns);
}

Eigen::Matrix3d orbit_frame_RN(OrbitFrame frame, const Eigen::Vector3d& r_N, const Eigen::Vector3d& v_N)
{
  const Eigen::Vector3d h_hat = r_N.cross(v_N).normalized();
  Eigen::Vector3d x, y, z;
  if (frame == OrbitFrame::Velocity) {
    x = v_N.normalized();
    y = -h_hat;
    z = x.cross(y);
  } else {
    z = -r_N.normalized();
    y = -h_hat;
    x = y.cross(z);
  }
  Eigen::Matrix3d RN;
  RN.row(0) = x.transpose();
  RN.row(1) = y.transpose();
  RN.row(2) = z.transpose();
  return RN;
}

PointingReference reference_of_mode(int fsw_mode, PointingReference detumble)
{
  switch (fsw_mode) {
    case FSW_ACS_MODE_SUN_SAFE: return PointingReference::SunAxis;
    case FSW_ACS_MODE_NADIR: return PointingReference::OrbitFrame;
    case FSW_ACS_MODE_DETUMBLE: return detumble;
    default: return PointingReference::Inertial;
  }
}

void MetricsTask::follow_command()
{
  if (!cmd.valid() || cmd.write_count() == cmd_seen) return;
  cmd_seen = cmd.write_count();
  const FswAcsCmdMsg& c = cmd.read();
  Eigen::Vector3d s = sigma_ref;
  if (c.set_ref) {
    s = Eigen::Vector3d(static_cast<double>(c.sigma_R0N[0]), static_cast<double>(c.sigma_R0N[1]),
                        static_cast<double>(c.sigma_R0N[2]));
    if (!std::isfinite(s.squaredNorm())) return;  // the FSW refuses the whole command
  }
  sigma_ref = s;
  ref = reference_of_mode(c.mode, ref0);  // DETUMBLE until another mode is commanded
  ref_commanded = ref_commanded || ref != ref0 || (ref == PointingReference::Inertial && sigma_ref != sigma_R0N);
}

double MetricsTask::pointing_error(uint64_t k, const TruthMsg& t) const
{
  const Eigen::Vector3d sigma = ev(t.sigma_BN);
  switch (ref) {
    case PointingReference::OrbitFrame: {
      const Eigen::Matrix3d BdN =
          sim::dcm_BN_from_sigma(sigma_BdR) * orbit_frame_RN(frame, ev(t.r_BN_N), ev(t.v_BN_N));
      const Eigen::Matrix3d E = sim::dcm_BN_from_sigma(sigma) * BdN.transpose();  // [B Bd]
      const Eigen::Vector3d s(E(1, 2) - E(2, 1), E(2, 0) - E(0, 2), E(0, 1) - E(1, 0));
      return std::atan2(0.5 * s.norm(), 0.5 * (E.trace() - 1.0));
    }
    case PointingReference::Inertial: return principal_angle(sigma, sigma_ref);
    case PointingReference::SunAxis: break;
  }
  const Eigen::Vector3d r_sun_N = sun->position_N(static_cast<int64_t>(k * tick_ns));
  const Eigen::Vector3d d_B = sim::dcm_BN_from_sigma(sigma) * (r_sun_N - ev(t.r_BN_N)).normalized();
  return std::atan2(sun_axis_B.cross(d_B).norm(), sun_axis_B.dot(d_B));
}

void MetricsTask::operator()(uint64_t k)
{
  const TruthMsg& t = truth.read();
  MetricsMsg m{};
  follow_command();
  m.pointing_error = pointing_error(k, t);
  const sim::EnergyMomentum em = plant->energy_momentum();
  for (int i = 0; i < 3; ++i) m.H_C_N[i] = em.H_C_N(i);
  m.E_rot = em.E_rot;
  if (has_burn) m.dv_ng = ev(burn.read().dv_ng_N).norm();
  if (mu > 0.0) {
    const sim::OrbitElements oe = sim::elements_from_rv(mu, ev(t.r_CN_N), ev(t.v_CN_N));
    m.orbit_e = oe.e;
    m.orbit_r_p = oe.r_p;
    m.orbit_energy = oe.energy;
  }
  if (has_burn && burn.read().in_burn) max_err_burn = std::max(max_err_burn, m.pointing_error);
  out.write(m, k * tick_ns);
}

}  // namespace harness
