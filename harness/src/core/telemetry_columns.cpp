// telemetry_columns.cpp: the recorded quantities, in the order of the flat
// table (CSV, report).  Dataset names are the quantity names; column names
// are the flat names kept since the first harness (scripts rely on them).
#include "core/telemetry_columns.h"
#include "core/convert.h"

#include <string>
#include <utility>
#include <vector>

#include "sim/attitude.h"
#include "sim/units.h"

namespace harness {

namespace {

constexpr double kRadToDeg = 180.0 / sim::kPi;
constexpr double kRpmPerRadS = 1.0 / sim::kRadPerSecPerRpm;

// A 3-vector quantity with columns <prefix>_x/_y/_z.
Quantity vec3(const std::string& name, const std::string& unit, const std::string& frame,
              const std::string& prefix = "")
{
  const std::string p = prefix.empty() ? name : prefix;
  return {name, unit, frame, {p + "_x", p + "_y", p + "_z"}};
}
Quantity scalar(const std::string& name, const std::string& unit, const std::string& column = "")
{
  return {name, unit, "", {column.empty() ? name : column}};
}
// One component per wheel or thruster: <prefix><i>.
Quantity indexed(const std::string& name, const std::string& unit, const std::string& prefix, int n)
{
  Quantity q{name, unit, "", {}};
  for (int i = 0; i < n; ++i) q.columns.push_back(prefix + std::to_string(i));
  return q;
}

// t, pointing error, attitude and orbit truth, and what the FSW was given.
void record_state(Recorder& rec, const RecordedChannels& ch, std::function<uint64_t()> t_now_ns)
{
  rec.add_source("", {scalar("t", "s")}, [t_now_ns](double* o) {
    o[0] = static_cast<double>(t_now_ns()) / 1e9;  // correctly rounded: 30 s is 30.0
  });
  rec.record<MetricsMsg>(*ch.metrics, {scalar("pointing_error", "deg", "pointing_error_deg")},
                         [](const MetricsMsg& x, double* o) { o[0] = x.pointing_error * kRadToDeg; });
  rec.record<TruthMsg>(*ch.truth,
                       {vec3("sigma_BN", "-", "B/N MRP"),
                        {"q_BN", "-", "B/N quaternion (scalar first)", {"q_BN_0", "q_BN_1", "q_BN_2", "q_BN_3"}},
                        vec3("omega_BN_B", "rad/s", "B"), vec3("r_BN_N", "m", "N"), vec3("v_BN_N", "m/s", "N")},
                       [](const TruthMsg& x, double* o) {
                         const Eigen::Vector4d q = sim::quaternion_from_sigma(ev(x.sigma_BN));
                         for (int i = 0; i < 3; ++i) o[i] = x.sigma_BN[i];
                         for (int i = 0; i < 4; ++i) o[3 + i] = q(i);
                         for (int i = 0; i < 3; ++i) {
                           o[7 + i] = x.omega_BN_B[i];
                           o[10 + i] = x.r_BN_N[i];
                           o[13 + i] = x.v_BN_N[i];
                         }
                       });
  // what the FSW was given (FswAcsSensorMsg): the measured values next to truth
  rec.record<FswAcsSensorMsg>(*ch.fsw_sensors,
                              {vec3("sigma_BN", "-", "B/N MRP", "meas_sigma_BN"),
                               scalar("att_valid", "-", "meas_att_valid"),
                               vec3("omega_BN_B", "rad/s", "B", "meas_omega_BN_B")},
                              [](const FswAcsSensorMsg& x, double* o) {
                                copy3(o, x.sigma_BN);
                                o[3] = x.att_valid;
                                copy3(o + 4, x.omega_BN_B);
                              });
}

// Wheel speeds (measured and truth), torques and commands.
void record_wheels(Recorder& rec, const RecordedChannels& ch, int n_rw)
{
  rec.record<FswAcsSensorMsg>(*ch.fsw_sensors, {indexed("wheel_speed", "rpm", "meas_wheel_speed_rpm_", n_rw)},
                              [n_rw](const FswAcsSensorMsg& x, double* o) {
                                for (int i = 0; i < n_rw; ++i) o[i] = static_cast<double>(x.Omega[i]) * kRpmPerRadS;
                              });
  rec.record<TruthMsg>(*ch.truth,
                       {indexed("wheel_speed", "rpm", "wheel_speed_rpm_", n_rw),
                        indexed("wheel_torque", "N*m", "wheel_torque_", n_rw)},
                       [n_rw](const TruthMsg& x, double* o) {
                         for (int i = 0; i < n_rw; ++i) o[i] = x.Omega[i] * kRpmPerRadS;
                         for (int i = 0; i < n_rw; ++i) o[n_rw + i] = x.u_s[i];
                       });
  rec.record<FswAcsActuatorMsg>(*ch.fsw_actuators, {indexed("wheel_cmd", "N*m", "wheel_cmd_", n_rw)},
                                [n_rw](const FswAcsActuatorMsg& x, double* o) {
                                  for (int i = 0; i < n_rw; ++i) o[i] = static_cast<double>(x.u_s[i]);
                                });
}

// Thruster on-times and forces, propellant, mass and the non-gravitational delta-v.
void record_thrusters(Recorder& rec, const RecordedChannels& ch, int n_thr)
{
  rec.record<PlantCmdMsg>(*ch.plant_cmd, {indexed("thruster_on_time", "s", "thruster_on_time_", n_thr)},
                          [n_thr](const PlantCmdMsg& x, double* o) {
                            for (int j = 0; j < n_thr; ++j) o[j] = x.T_on[j];
                          });
  rec.record<TruthMsg>(*ch.truth,
                       {indexed("thruster_force", "N", "thruster_force_", n_thr),
                        scalar("propellant", "kg", "propellant_kg"), scalar("mass", "kg", "mass_kg")},
                       [n_thr](const TruthMsg& x, double* o) {
                         for (int j = 0; j < n_thr; ++j) o[j] = x.F_thr[j];
                         o[n_thr] = x.m_prop;
                         o[n_thr + 1] = x.m_sc;
                       });
  rec.record<MetricsMsg>(*ch.metrics, {scalar("dv_nongrav", "m/s")},
                         [](const MetricsMsg& x, double* o) { o[0] = x.dv_ng; });
}

void record_orbit(Recorder& rec, const RecordedChannels& ch)
{
  rec.record<MetricsMsg>(*ch.metrics,
                         {scalar("orbit_e", "-"), scalar("orbit_r_p", "km", "orbit_r_p_km"),
                          scalar("orbit_energy", "J/kg")},
                         [](const MetricsMsg& x, double* o) {
                           o[0] = x.orbit_e;
                           o[1] = x.orbit_r_p * 1e-3;
                           o[2] = x.orbit_energy;
                         });
}

// The FSW: tracking error, control torque, momentum and energy, stage and
// speed-filter health, and the Sun heading in sun-safe runs.
void record_fsw(Recorder& rec, const RecordedChannels& ch, int n_rw)
{
  rec.record<FswAcsHealthMsg>(*ch.fsw_health,
                              {vec3("sigma_BR", "-", "B/R MRP"), vec3("omega_BR_B", "rad/s", "B")},
                              [](const FswAcsHealthMsg& g, double* o) {
                                copy3(o, g.sigma_BR);
                                copy3(o + 3, g.omega_BR_B);
                              });
  rec.record<FswAcsActuatorMsg>(*ch.fsw_actuators, {vec3("Lr_B", "N*m", "B")},
                                [](const FswAcsActuatorMsg& x, double* o) { copy3(o, x.Lr_B); });
  rec.record<MetricsMsg>(*ch.metrics, {vec3("H_C_N", "kg*m^2/s", "N"), scalar("E_rot", "J")},
                         [](const MetricsMsg& x, double* o) {
                           for (int i = 0; i < 3; ++i) o[i] = x.H_C_N[i];
                           o[3] = x.E_rot;
                         });
  {
    Quantity stages{"stage_status", "-", "", {}};
    for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) stages.columns.push_back(std::string("fsw_stage_") + fsw_acs_stage_name(i));
    rec.record<FswAcsHealthMsg>(*ch.fsw_health,
                                {scalar("status", "-", "fsw_status"), scalar("safe_output", "-", "fsw_safe_output"), stages},
                                [](const FswAcsHealthMsg& h, double* o) {
                                  o[0] = static_cast<double>(h.status);
                                  o[1] = h.safe_output;
                                  for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) o[2 + i] = static_cast<double>(h.stage_status[i]);
                                });
  }
  if (n_rw > 0)  // the FSW's speed-filter verdicts, 0/1 per wheel (all 0 without the filter)
    rec.record<FswAcsHealthMsg>(*ch.fsw_health,
                                {indexed("fsw_rw_failed", "-", "fsw_rw_failed_", n_rw),
                                 indexed("fsw_rw_latched", "-", "fsw_rw_latched_", n_rw)},
                                [n_rw](const FswAcsHealthMsg& h, double* o) {
                                  for (int i = 0; i < n_rw; ++i) {
                                    o[i] = static_cast<double>((h.rw_failed >> i) & 1u);
                                    o[n_rw + i] = static_cast<double>((h.rw_latched >> i) & 1u);
                                  }
                                });
  if (ch.sun_heading)
    rec.record<SunHeadingMsg>(*ch.sun_heading,
                              {vec3("sun_B", "-", "B"), scalar("valid", "-", "sun_valid"),
                               scalar("num_lit", "-", "css_num_lit")},
                              [](const SunHeadingMsg& h, double* o) {
                                for (int i = 0; i < 3; ++i) o[i] = h.sun_B[i];
                                o[3] = h.valid;
                                o[4] = h.num_lit;
                              });
}

}  // namespace

void declare_telemetry(Recorder& rec, const RecordedChannels& ch, int n_rw, int n_thr, bool orbit,
                       std::function<uint64_t()> t_now_ns)
{
  record_state(rec, ch, std::move(t_now_ns));
  if (n_rw > 0) record_wheels(rec, ch, n_rw);
  if (n_thr > 0) record_thrusters(rec, ch, n_thr);
  if (orbit) record_orbit(rec, ch);
  record_fsw(rec, ch, n_rw);
}

void declare_disturbances(Recorder& rec, const RecordedChannels& ch, const std::array<bool, kNumEnvSources>& on)
{
  for (int s = 0; s < kNumEnvSources; ++s) {
    if (!on[static_cast<size_t>(s)]) continue;
    const std::string name = std::string("torque_") + env_source_name(static_cast<EnvSource>(s));
    rec.record<TruthMsg>(*ch.truth, {vec3(name, "N*m", "B, about the mass centre")},
                         [s](const TruthMsg& x, double* o) { copy3(o, x.L_env_C_B[s]); });
  }
}

void declare_magnetorquers(Recorder& rec, const Channel<MtqStateMsg>& ch, int n_rods)
{
  rec.record<MtqStateMsg>(ch,
                          {indexed("mtq_dipole", "A*m^2", "mtq_dipole_", n_rods),
                           indexed("mtq_power", "W", "mtq_power_", n_rods)},
                          [n_rods](const MtqStateMsg& x, double* o) {
                            for (int i = 0; i < n_rods; ++i) {
                              o[i] = x.dipole[i];
                              o[n_rods + i] = x.power[i];
                            }
                          });
}

void declare_fsw_momentum(Recorder& rec, const RecordedChannels& ch)
{
  rec.record<FswAcsHealthMsg>(*ch.fsw_health,
                              {scalar("mode", "-", "fsw_mode"), scalar("policy", "-", "fsw_policy"),
                               scalar("detumbled", "-", "fsw_detumbled"), scalar("rate_est", "rad/s", "fsw_rate_est"),
                               vec3("h_w_B", "N*m*s", "B", "fsw_h_w_B"), vec3("tau_mtq_B", "N*m", "B", "fsw_tau_mtq_B"),
                               scalar("dump_phase", "-", "fsw_dump_phase"), scalar("dumps", "-", "fsw_dumps"),
                               scalar("prop_used", "kg", "fsw_prop_used")},
                              [](const FswAcsHealthMsg& h, double* o) {
                                o[0] = h.mode;
                                o[1] = h.policy;
                                o[2] = h.detumbled;
                                o[3] = static_cast<double>(h.rate_est);
                                copy3(o + 4, h.h_w_B);
                                copy3(o + 7, h.tau_mtq_B);
                                o[10] = h.dump_phase;
                                o[11] = h.dumps;
                                o[12] = static_cast<double>(h.prop_used);
                              });
}

void declare_magnetometer(Recorder& rec, const Channel<MagnetometerMsg>& ch)
{
  rec.record<MagnetometerMsg>(ch, {vec3("B_S", "T", "S (magnetometer axes)", "mag_B_S"), scalar("valid", "-", "mag_valid")},
                              [](const MagnetometerMsg& x, double* o) {
                                copy3(o, x.B_S);
                                o[3] = x.valid;
                              });
}

void declare_environment_truth(Recorder& rec, const RecordedChannels& ch, const std::array<bool, kNumEnvSources>& on,
                               bool has_epoch, int n_rw)
{
  if (has_epoch)
    rec.record<TruthMsg>(*ch.truth, {scalar("illumination", "-"), scalar("eclipse", "-")},
                         [](const TruthMsg& x, double* o) {
                           o[0] = x.illumination;
                           o[1] = x.illumination < 1.0 ? 1.0 : 0.0;
                         });
  if (on[static_cast<size_t>(EnvSource::Magnetic)])
    rec.record<TruthMsg>(*ch.truth, {vec3("field_B", "T", "B")},
                         [](const TruthMsg& x, double* o) { copy3(o, x.field_B); });
  bool any = false;
  for (int s = 0; s < kNumEnvSources; ++s) {
    if (!on[static_cast<size_t>(s)]) continue;
    any = true;
    const std::string name = std::string("H_") + env_source_name(static_cast<EnvSource>(s)) + "_N";
    rec.record<TruthMsg>(*ch.truth, {vec3(name, "N*m*s", "N, about the mass centre")},
                         [s](const TruthMsg& x, double* o) { copy3(o, x.H_env_N[s]); });
  }
  if (any && n_rw > 0)
    rec.record<TruthMsg>(*ch.truth, {vec3("H_wheels_N", "N*m*s", "N, wheels' spin momentum relative to B")},
                         [](const TruthMsg& x, double* o) { copy3(o, x.H_wheels_N); });
}

}  // namespace harness
