// vehicle_geometry.cpp: scenario -> the vehicle's geometry (one vocabulary),
// and that geometry -> the FSW's FswAcsGeometry.
#include "harness/core/vehicle_geometry.h"

#include <cmath>
#include <cstring>

#include "core/convert.h"

namespace harness {

Eigen::Vector3d misaligned_axis(const Eigen::Vector3d& d, double delta)
{
  if (delta == 0.0) return d;
  Eigen::Vector3d a = d.cross(Eigen::Vector3d::UnitX());
  if (a.norm() < 0.42) a = d.cross(Eigen::Vector3d::UnitY());
  a.normalize();
  return (std::cos(delta) * d + std::sin(delta) * a.cross(d)).normalized();
}

VehicleGeometry vehicle_geometry(const Scenario& sc)
{
  VehicleGeometry g;
  g.r_BcB_B = sc.spacecraft.r_BcB_B;
  for (const WheelSpec& w : sc.wheels) {
    g.gs_hat_B.push_back(w.params.gs_hat_nom_B);
    g.r_WB_B.push_back(w.params.r_WB_B);
  }
  for (size_t j = 0; j < sc.thrusters.size(); ++j) {
    const ThrusterSpec& t = sc.thrusters[j];
    ThrusterGeometry tg;
    tg.r_TjB_B = t.r_TjB_B;
    tg.t_hat_B = t.t_hat_B;
    tg.t_hat_true_B = misaligned_axis(t.t_hat_B, t.misalignment);
    tg.F_max = t.F_max;
    tg.acs = t.acs;
    g.thrusters.push_back(tg);
    if (t.acs) g.acs_to_plant.push_back(static_cast<int>(j));
  }
  for (const std::optional<TankSpec>* t : {&sc.tank, &sc.rcs_tank})
    if (*t) g.r_TB_B.push_back((*t)->r_TB_B);
  return g;
}

FswAcsGeometry fsw_geometry(const Scenario& sc, const VehicleGeometry& g)
{
  FswAcsGeometry geo;
  std::memset(&geo, 0, sizeof geo);
  geo.num_rw = static_cast<int>(g.gs_hat_B.size());
  for (int i = 0; i < geo.num_rw && i < FSW_MAX_RW; ++i) {
    const sim::ReactionWheelParams& p = sc.wheels[static_cast<size_t>(i)].params;
    put3(geo.gs_hat_B[i], g.gs_hat_B[static_cast<size_t>(i)]);
    geo.J_s[i] = static_cast<fsw_real>(p.J_s);
    geo.u_max[i] = static_cast<fsw_real>(p.u_max);
  }
  geo.num_thr = static_cast<int>(g.acs_to_plant.size());
  for (int i = 0; i < geo.num_thr && i < FSW_MAX_THR; ++i) {
    const ThrusterGeometry& t = g.thrusters[static_cast<size_t>(g.acs_to_plant[static_cast<size_t>(i)])];
    put3(geo.r_thr_B[i], t.r_TjB_B);
    put3(geo.gt_hat_B[i], t.t_hat_B);  // nominal axis: the misalignment is truth only
    geo.F_max[i] = static_cast<fsw_real>(t.F_max);
  }
  // the rods, when the flight software commands them (fsw.magnetorquers)
  geo.num_mtq = sc.fsw.mtq ? static_cast<int>(sc.magnetorquers.size()) : 0;
  for (int i = 0; i < geo.num_mtq && i < FSW_MAX_MTQ; ++i) {
    const MagnetorquerSpec& m = sc.magnetorquers[static_cast<size_t>(i)];
    put3(geo.mtq_axis_B[i], m.axis_B);
    geo.mtq_m_max[i] = static_cast<fsw_real>(m.m_max);
  }
  return geo;
}

}  // namespace harness
