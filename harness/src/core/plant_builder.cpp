// plant_builder.cpp: scenario -> sim parameters (SI throughout); the
// geometry (mass centre, wheel axes, thruster and tank positions, thrust
// axes) comes from vehicle_geometry(), the one place it is formed.
#include "core/plant_builder.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/build_error.h"
#include "sim/environment.h"
#include "sim/propellant.h"

namespace harness {

namespace {

// Hub, wheels and gravity; the hub mass centre and the wheel axes and
// origins from the vehicle's geometry.
sim::SpacecraftParams spacecraft_params(const Scenario& sc, const VehicleGeometry& g)
{
  sim::SpacecraftParams params;
  params.hub.m_h = sc.spacecraft.mass;
  params.hub.I_hBc_B = sc.spacecraft.inertia;
  params.hub.r_BcB_B = g.r_BcB_B;
  params.mu = sc.environment.mu;
  if (sc.environment.j2) {  // the reader allows it with Earth's mu only
    params.J2 = sim::kJ2Earth;
    params.R_J2 = sim::kRadiusJ2Earth;
  }
  for (size_t i = 0; i < sc.wheels.size(); ++i) {
    params.wheels.push_back(sc.wheels[i].params);
    params.wheels.back().gs_hat_nom_B = g.gs_hat_B[i];
    params.wheels.back().r_WB_B = g.r_WB_B[i];
  }
  return params;
}

sim::InitialConditions initial_conditions(const Scenario& sc)
{
  sim::InitialConditions ic;
  ic.r_CN_N = sc.spacecraft.initial.r_CN_N;
  ic.v_CN_N = sc.spacecraft.initial.v_CN_N;
  ic.sigma_BN = sc.spacecraft.initial.sigma_BN;
  ic.omega_BN_B = sc.spacecraft.initial.omega_BN_B;
  return ic;
}

// Tanks (tank, then rcs_tank) and thrusters (truth axes) with their positions
// from the vehicle's geometry.
sim::PropulsionParams propulsion_params(const Scenario& sc, const VehicleGeometry& g)
{
  sim::PropulsionParams prop;
  const std::optional<TankSpec>* tanks[] = {&sc.tank, &sc.rcs_tank};
  size_t k = 0;
  for (const std::optional<TankSpec>* t : tanks)
    if (*t) {
      sim::TankParams tk;
      tk.r_TB_B = g.r_TB_B[k++];
      tk.m_p0 = (*t)->mass;
      prop.tanks.push_back(tk);
    }
  for (size_t j = 0; j < sc.thrusters.size(); ++j) {
    const ThrusterSpec& t = sc.thrusters[j];
    sim::ThrusterParams tp;
    tp.r_TjB_B = g.thrusters[j].r_TjB_B;
    tp.t_hat_B = g.thrusters[j].t_hat_true_B;
    tp.F_max = g.thrusters[j].F_max;
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
  return prop;
}

int64_t period_ns(const EnvModelSpec& m) { return static_cast<int64_t>(std::llround(m.period * 1e9)); }

sim::FacetSet facet_set(const Scenario& sc)
{
  sim::FacetSet f;
  for (const sim::Facet& x : sc.spacecraft.facets) f.facets[static_cast<size_t>(f.count++)] = x;
  return f;
}

// The residual dipole and the rods (axes renormalised: the scenario checks
// them to 1e-6, the plant to 1e-9).
sim::MagneticParams magnetic_params(const Scenario& sc)
{
  sim::MagneticParams mp;
  mp.m_residual_B = sc.spacecraft.residual_dipole_B;
  mp.igrf_degree = sc.environment.igrf_degree;
  mp.period_ns = period_ns(sc.environment.magnetic);
  for (const MagnetorquerSpec& m : sc.magnetorquers) {
    sim::MagnetorquerParams r;
    r.axis_B = m.axis_B.normalized();
    r.m_max = m.m_max;
    r.m_remanent = m.m_remanent;
    r.power_max = m.power_max;
    mp.rods.push_back(r);
  }
  return mp;
}

// The magnetic effector and, for PWM commands, the driver that switches its
// rods (cycle: magnetorquer_drive.pwm_period, 0: the FSW period).
void add_magnetic(const Scenario& sc, sim::Plant& p, const sim::EarthContext& ctx, SettableParts& out)
{
  out.effector = &p.add_effector(std::make_unique<sim::MagneticEffector>(p, ctx, magnetic_params(sc)));
  if (sc.magnetorquers.empty() || sc.magnetorquer_drive.mode != MtqDriveMode::Pwm) return;
  const double T = sc.magnetorquer_drive.pwm_period;
  const int64_t T_ns = T > 0.0 ? static_cast<int64_t>(std::llround(T * 1e9))
                               : static_cast<int64_t>(sc.rates.fsw_divisor) * static_cast<int64_t>(sc.tick_ns());
  out.pwm = &p.add_effector(std::make_unique<MtqPwmDriver>(*out.effector, T_ns));
}

// The environment effectors the scenario enables, in EnvSource order, with
// one Earth context (the epoch of t = 0; gravity gradient alone needs no date).
EnvEffectors add_environment(const Scenario& sc, sim::Plant& p, SettableParts& mag)
{
  EnvEffectors out{};
  const EnvironmentSpec& e = sc.environment;
  const sim::EarthContext ctx = earth_context(sc).value_or(sim::EarthContext(sim::EarthContextParams{}));
  if (e.gravity_gradient.enabled) {
    sim::GravityGradientParams gp;
    gp.period_ns = period_ns(e.gravity_gradient);
    out[0] = &p.add_effector(std::make_unique<sim::GravityGradientEffector>(p, ctx, gp));
  }
  if (e.solar_pressure.enabled) {
    sim::SolarPressureParams sp;
    sp.facets = facet_set(sc);
    sp.period_ns = period_ns(e.solar_pressure);
    out[1] = &p.add_effector(std::make_unique<sim::SolarPressureEffector>(p, ctx, sp));
  }
  if (e.drag.enabled) {
    sim::DragParams dp;
    dp.facets = facet_set(sc);
    dp.atmosphere.scale = e.drag_density_scale;
    dp.period_ns = period_ns(e.drag);
    mag.drag = &p.add_effector(std::make_unique<sim::DragEffector>(p, ctx, dp));
    out[2] = mag.drag;
  }
  if (e.magnetic.enabled) {
    add_magnetic(sc, p, ctx, mag);
    out[3] = mag.effector;
  }
  return out;
}

}  // namespace

std::optional<sim::EarthContext> earth_context(const Scenario& sc)
{
  if (sc.environment.epoch.empty()) return std::nullopt;
  sim::EarthContextParams cp;
  std::string why;
  cp.epoch = parse_utc_epoch(sc.environment.epoch, &why).value_or(sim::UtcEpoch{});
  return sim::EarthContext(cp);
}

std::unique_ptr<sim::Plant> build_plant(const Scenario& sc, EnvEffectors* env, SettableParts* mag)
{
  std::unique_ptr<sim::Plant> p;  // the plant checks its own capacities (built_by_plant reports them)
  const VehicleGeometry g = vehicle_geometry(sc);
  const sim::SpacecraftParams params = spacecraft_params(sc, g);
  const sim::InitialConditions ic = initial_conditions(sc);
  if (sc.thrusters.empty()) {
    built_by_plant(sc, "spacecraft", [&] { p = std::make_unique<sim::Plant>(sim::PlantParams{params, {}}, ic); });
  } else {
    const sim::PropulsionParams prop = propulsion_params(sc, g);
    built_by_plant(sc, "thrusters", [&] { p = std::make_unique<sim::Plant>(sim::PlantParams{params, prop}, ic); });
  }
  EnvEffectors added{};
  SettableParts parts{};
  built_by_plant(sc, "environment", [&] { added = add_environment(sc, *p, parts); });
  if (env) *env = added;
  if (mag) *mag = parts;
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
