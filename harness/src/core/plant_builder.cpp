// plant_builder.cpp: scenario keys -> sim parameters (SI throughout).
#include "core/plant_builder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/build_error.h"
#include "sim/propellant.h"

namespace harness {

// The nominal axis d tilted by delta about a = unit(d x x_B) (or unit(d x y_B)
// when d is within 25 deg of x_B): d' = cos(delta) d + sin(delta) (a x d).
// For d = +z_B this tilts toward +x_B.
Eigen::Vector3d misaligned_axis(const Eigen::Vector3d& d, double delta)
{
  if (delta == 0.0) return d;
  Eigen::Vector3d a = d.cross(Eigen::Vector3d::UnitX());
  if (a.norm() < 0.42) a = d.cross(Eigen::Vector3d::UnitY());
  a.normalize();
  return (std::cos(delta) * d + std::sin(delta) * a.cross(d)).normalized();
}

std::unique_ptr<sim::Plant> build_plant(const Scenario& sc)
{
  std::unique_ptr<sim::Plant> p;  // the plant checks its own capacities (built_by_plant reports them)
  sim::SpacecraftParams params;
  params.hub.m_h = sc.spacecraft.mass;
  params.hub.I_hBc_B = sc.spacecraft.inertia;
  params.hub.r_BcB_B = sc.spacecraft.com;
  params.mu = sc.environment.mu;
  for (const WheelSpec& w : sc.wheels) params.wheels.push_back(w.params);
  sim::InitialConditions ic;
  ic.r_CN_N = sc.spacecraft.initial.r_CN_N;
  ic.v_CN_N = sc.spacecraft.initial.v_CN_N;
  ic.sigma_BN = sc.spacecraft.initial.sigma_BN;
  ic.omega_BN_B = sc.spacecraft.initial.omega_BN_B;
  if (sc.thrusters.empty()) {
    built_by_plant(sc, "spacecraft", [&] { p = std::make_unique<sim::Plant>(sim::PlantParams{params, {}}, ic); });
    return p;
  }
  sim::PropulsionParams prop;
  sim::TankParams tk;
  tk.r_TB_B = sc.tank->r_B;
  tk.m_p0 = sc.tank->mass;
  prop.tanks.push_back(tk);
  if (sc.rcs_tank) {
    sim::TankParams rt;
    rt.r_TB_B = sc.rcs_tank->r_B;
    rt.m_p0 = sc.rcs_tank->mass;
    prop.tanks.push_back(rt);
  }
  for (const ThrusterSpec& t : sc.thrusters) {
    sim::ThrusterParams tp;
    tp.r_TjB_B = t.r_B;
    tp.t_hat_B = misaligned_axis(t.dir_B, t.misalignment);
    tp.F_max = t.F_max;
    tp.Isp = t.Isp;
    tp.T_min = t.T_min;
    tp.transient = t.transient == ThrTransient::Instant ? sim::ThrusterTransient::Instant
                                                        : sim::ThrusterTransient::FirstOrder;
    tp.omega_on = t.omega_on;
    tp.omega_off = t.omega_off;
    tp.tank = (t.acs && sc.rcs_tank) ? 1 : 0;
    prop.thrusters.push_back(tp);
  }
  prop.command.T_upd_ns = static_cast<int64_t>(sc.rates.thruster_divisor) * static_cast<int64_t>(sc.tick_ns());
  built_by_plant(sc, "thrusters", [&] { p = std::make_unique<sim::Plant>(sim::PlantParams{params, prop}, ic); });
  return p;
}

BurnSchedule burn_schedule(const Scenario& sc, const sim::Plant& plant)
{
  BurnSchedule b;
  b.T_upd_ns = plant.num_thr() > 0 ? plant.thrusters().command_params().T_upd_ns : 0;
  if (!sc.burn || plant.num_thr() == 0) return b;
  for (size_t j = 0; j < sc.thrusters.size(); ++j)
    if (sc.thrusters[j].name == sc.burn->thruster) b.engine = static_cast<int>(j);
  const int64_t T = b.T_upd_ns;
  const int64_t start = static_cast<int64_t>(std::llround(sc.burn->start * 1e9));
  b.on_ns = ((start + T - 1) / T) * T;
  b.off_ns = start + static_cast<int64_t>(std::llround(sc.burn->duration * 1e9));
  if (b.off_ns <= b.on_ns) b.off_ns = b.on_ns;
  return b;
}

double BurnSchedule::on_time(int64_t now_ns) const
{
  if (engine < 0) return 0.0;
  const int64_t t_L = ((now_ns + T_upd_ns - 1) / T_upd_ns) * T_upd_ns;  // latch instant of this message
  if (t_L >= on_ns && t_L < off_ns) return static_cast<double>(std::min(T_upd_ns, off_ns - t_L)) * 1e-9;
  return 0.0;
}

}  // namespace harness
