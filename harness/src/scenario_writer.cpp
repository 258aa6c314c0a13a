// scenario_writer.cpp: the canonical (SI, fully resolved) form of a scenario.
// Every key written here is a key the reader accepts, so a manifest loads
// back into the same Scenario.
#include "harness/scenario.h"
#include "json_util.h"

namespace harness {

namespace {
using nlohmann::json;

json v3(const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); }
json m3(const Eigen::Matrix3d& m)
{
  json out = json::array();
  for (int r = 0; r < 3; ++r) out.push_back(json::array({m(r, 0), m(r, 1), m(r, 2)}));
  return out;
}
}  // namespace

json scenario_to_json(const Scenario& sc)
{
  json j;
  j["name"] = sc.name;
  j["description"] = sc.description;
  j["seed"] = sc.seed;
  j["duration"] = sc.duration;
  j["rates"] = {{"dt", sc.rates.dt},
                {"fsw_divisor", sc.rates.fsw_divisor},
                {"fsw_offset", sc.rates.fsw_offset},
                {"record_divisor", sc.rates.record_divisor},
                {"thruster_divisor", sc.rates.thruster_divisor}};
  const SpacecraftSpec& s = sc.spacecraft;
  j["spacecraft"] = {{"mass", s.mass},
                     {"inertia", m3(s.inertia)},
                     {"com", v3(s.com)},
                     {"initial",
                      {{"sigma_BN", v3(s.initial.sigma_BN)},
                       {"omega_BN_B", v3(s.initial.omega_BN_B)},
                       {"r_CN_N", v3(s.initial.r_CN_N)},
                       {"v_CN_N", v3(s.initial.v_CN_N)}}}};
  j["environment"] = {{"mu", sc.environment.mu}, {"sun_position_N", v3(sc.environment.sun_position_N)}};
  json wheels = json::array();
  for (const WheelSpec& w : sc.wheels) {
    const sim::ReactionWheelParams& p = w.params;
    json jw = {{"name", w.name},
               {"model", wheel_model_key(p.model)},
               {"axis", v3(p.gs_hat_nom_B)},
               {"position", v3(p.r_WB_B)},
               {"J_s", p.J_s},
               {"m_w", p.m_w},
               {"U_s", p.U_s},
               {"U_d", p.U_d},
               {"Omega_0", p.Omega_0},
               {"Omega_max", p.Omega_max},
               {"u_max", p.u_max},
               {"u_min", p.u_min},
               {"P_max", p.P_max},
               {"misalignment", v3(p.delta_mis_B)},
               {"friction",
                {{"tau_c", p.friction.tau_c},
                 {"tau_st", p.friction.tau_st},
                 {"c_v", p.friction.c_v},
                 {"beta_st", p.friction.beta_st},
                 {"omega_lc", p.friction.omega_lc}}}};
    if (p.J_t) jw["J_t"] = *p.J_t;
    if (p.J_g) jw["J_g"] = *p.J_g;
    wheels.push_back(jw);
  }
  j["wheels"] = wheels;
  json thr = json::array();
  for (const ThrusterSpec& t : sc.thrusters) {
    thr.push_back({{"name", t.name},
                   {"position", v3(t.r_B)},
                   {"direction", v3(t.dir_B)},
                   {"F_max", t.F_max},
                   {"Isp", t.Isp},
                   {"T_min", t.T_min},
                   {"misalignment", t.misalignment},
                   {"transient", to_string(t.transient)},
                   {"omega_on", t.omega_on},
                   {"omega_off", t.omega_off},
                   {"acs", t.acs}});
  }
  j["thrusters"] = thr;
  if (sc.tank) j["tank"] = {{"mass", sc.tank->mass}, {"position", v3(sc.tank->r_B)}};
  if (sc.rcs_tank) j["rcs_tank"] = {{"mass", sc.rcs_tank->mass}, {"position", v3(sc.rcs_tank->r_B)}};
  if (sc.burn)
    j["burn"] = {{"thruster", sc.burn->thruster}, {"start", sc.burn->start}, {"duration", sc.burn->duration}};
  json normals = json::array();
  for (const auto& n : sc.sensors.css.normals_B) normals.push_back(v3(n));
  j["sensors"] = {{"css",
                   {{"fov", sc.sensors.css.fov},
                    {"scale", sc.sensors.css.scale},
                    {"noise_std", sc.sensors.css.noise_std},
                    {"normals", normals}}},
                  {"star_tracker",
                   {{"enabled", sc.sensors.star_tracker.enabled},
                    {"sigma_cross", sc.sensors.star_tracker.sigma_cross},
                    {"sigma_bore", sc.sensors.star_tracker.sigma_bore},
                    {"sun_exclusion", sc.sensors.star_tracker.sun_exclusion},
                    {"divisor", sc.sensors.star_tracker.divisor}}},
                  {"gyro",
                   {{"enabled", sc.sensors.gyro.enabled},
                    {"arw", sc.sensors.gyro.arw},
                    {"rrw", sc.sensors.gyro.rrw},
                    {"lsb", sc.sensors.gyro.lsb},
                    {"divisor", sc.sensors.gyro.divisor}}},
                  {"tachometer",
                   {{"enabled", sc.sensors.tachometer.enabled},
                    {"sigma", sc.sensors.tachometer.sigma},
                    {"lsb", sc.sensors.tachometer.lsb},
                    {"divisor", sc.sensors.tachometer.divisor}}},
                  {"noise", sc.sensors.noise}};
  const FswSpec& f = sc.fsw;
  json mrp = {{"K", f.mrp_fb.K},
              {"P", f.mrp_fb.P},
              {"K_i", f.mrp_fb.K_i},
              {"integral_limit", f.mrp_fb.integral_limit},
              {"control_law", f.mrp_fb.control_law}};
  if (f.mrp_fb.inertia) mrp["inertia"] = m3(*f.mrp_fb.inertia);
  json rn = {{"enabled", f.rw_null}, {"scale_to_fit", f.rw_null_scale_to_fit}};
  if (f.k_null > 0.0) rn["k_null"] = f.k_null;
  if (!f.Omega_des.empty()) rn["Omega_des"] = f.Omega_des;
  j["fsw"] = {{"mode", to_string(f.mode)},
              {"inertial", {{"sigma_R0N", v3(f.sigma_R0N)}}},
              {"sun_safe",
               {{"sun_axis_B", v3(f.sun_axis_B)},
                {"small_angle", f.sun_small_angle},
                {"omega_search_B", v3(f.omega_search_B)},
                {"lit_threshold", f.css_lit_threshold}}},
              {"mrp_fb", mrp},
              {"rw_map", {{"mode", to_string(f.rw_map)}, {"eps_P", f.eps_P}}},
              {"rw_null", rn},
              {"thr_pulse",
               {{"mode", to_string(f.thr_pulse)},
                {"t_min", f.thr_t_min},
                {"level_on", f.thr_level_on},
                {"level_off", f.thr_level_off}}},
              {"thr_map", {{"mode", to_string(f.thr_map)}}},
              {"actuation", to_string(f.actuation)}};
  j["outputs"] = {{"hdf5", sc.outputs.hdf5}, {"csv", sc.outputs.csv}, {"report_data", sc.outputs.report_data}};
  return j;
}

std::string scenario_to_json_text(const Scenario& sc, int indent) { return scenario_to_json(sc).dump(indent); }

}  // namespace harness
