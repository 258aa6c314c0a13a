// scenario_spacecraft.cpp: `environment` and `spacecraft` (hub mass
// properties and the initial state, optionally from an approach hyperbola).
#include "scenario/scenario_schema.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/environment.h"
#include "sim/units.h"

namespace harness::schema {

const Section& environment_section()
{
  static const Section s{
      "environment",
      {
          real("mu", [](auto& sc, size_t) -> auto& { return sc.environment.mu; })
              .bounds(non_negative("m^3/s^2")).unit("m^3/s^2"),
          vec3("sun_position_N", [](auto& sc, size_t) -> auto& { return sc.environment.sun_position_N; }).unit("m"),
      },
      {}};
  return s;
}

void read_environment(MapReader r, Scenario& sc)
{
  read_keys(r, environment_section(), sc);
  r.finish();
}

namespace {
Section hyperbola_section()
{
  Section h{"hyperbola",
            {
                input_only("periapsis_radius", Type::Real).req("periapsis radius [m]").bounds(positive("m")).unit("m"),
                input_only("v_inf", Type::Real).req("hyperbolic excess speed [m/s]").bounds(positive("m/s")).unit("m/s"),
                input_only("time_to_periapsis", Type::Real)
                    .req("time from the start to periapsis [s]").bounds(non_negative("s")).unit("s"),
            },
            {}};
  h.input_only = true;
  h.note = "resolved into r_CN_N and v_CN_N when the file is read; set those";
  return h;
}

std::string mrp_in_unit_ball(const Eigen::Vector3d& s)
{
  return s.norm() > 1.0 + 1e-12 ? "MRP must have |sigma| <= 1 (use the shadow set)" : "";
}
}  // namespace

const Section& spacecraft_section()
{
  static const Section s{
      "spacecraft",
      {
          real("mass", [](auto& sc, size_t) -> auto& { return sc.spacecraft.mass; })
              .req("hub mass [kg]").bounds(positive("kg")).unit("kg"),
          inertia("inertia", [](auto& sc, size_t) -> auto& { return sc.spacecraft.inertia; })
              .req("hub inertia about its CoM [kg*m^2]").unit("kg*m^2"),
          vec3("com", [](auto& sc, size_t) -> auto& { return sc.spacecraft.r_BcB_B; }).unit("m"),
      },
      {Section{"initial",
               {
                   vec3("sigma_BN", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.sigma_BN; })
                       .vcheck(mrp_in_unit_ball).unit("-"),
                   vec3("omega_BN_B", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.omega_BN_B; })
                       .alt("_deg_s", sim::kRadPerDeg).vcheck(rate_within(kMaxBodyRateDegS)).unit("rad/s"),
                   vec3("r_CN_N", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.r_CN_N; }).unit("m"),
                   vec3("v_CN_N", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.v_CN_N; })
                       .unit("m/s"),
               },
               {hyperbola_section()}}}};
  return s;
}

void read_spacecraft(MapReader r, Scenario& sc)
{
  const Section& def = spacecraft_section();
  read_keys(r, def, sc);
  MapReader ic = r.sub("initial");
  read_keys(ic, *def.child("initial"), sc);
  if (ic.has("hyperbola")) {
    // Approach hyperbola (sim::conic_state_from_periapsis): perifocal frame = N
    // (x toward periapsis, z along the orbit normal).  Resolved into r_CN_N,
    // v_CN_N here (needs environment.mu, read before the spacecraft).
    MapReader h = ic.sub("hyperbola");
    std::vector<std::optional<double>> v;
    for (const KeyDef& k : def.child("initial")->child("hyperbola")->keys) {
      v.push_back(h.real(k.name, [&k](double x) { return k.check(x, false); }));
      if (!v.back() && !h.has(k.name)) h.missing(k.name, k.required);
    }
    const std::optional<double>&rp = v[0], &vinf = v[1], &tp = v[2];
    h.finish();
    if (ic.has("r_CN_N") || ic.has("v_CN_N"))
      ic.error_at("hyperbola", "give either 'hyperbola' or 'r_CN_N'/'v_CN_N', not both");
    else if (!(sc.environment.mu > 0.0))
      ic.error_at("hyperbola", "needs gravity: environment.mu > 0");
    else if (rp && vinf && tp) {
      const double e = sim::hyperbolic_eccentricity(sc.environment.mu, *rp, *vinf);
      if (!(e > 1.0) || !std::isfinite(e)) {
        // e = 1 + r_p v_inf^2 / mu: a tiny r_p v_inf^2 / mu rounds e to 1
        // (found by fuzz_scenario_reader with mu = 4.28e34)
        ic.error_at("hyperbola", "not a hyperbola in double precision: e = 1 + periapsis_radius v_inf^2 / mu = " +
                                     std::to_string(e) + " (mu too large for these values?)");
      } else {
        try {
          const sim::OrbitState os = sim::conic_state_from_periapsis(sc.environment.mu, *rp, e, -*tp);
          if (!os.r_N.allFinite() || !os.v_N.allFinite())
            ic.error_at("hyperbola", "no finite state on this hyperbola (time_to_periapsis too large?)");
          sc.spacecraft.initial.r_CN_N = os.r_N;
          sc.spacecraft.initial.v_CN_N = os.v_N;
        } catch (const std::invalid_argument& ex) {  // the plant refuses the conic: say where
          ic.error_at("hyperbola", ex.what());
        }
      }
    }
  }
  ic.finish();
  r.finish();
}

}  // namespace harness::schema
