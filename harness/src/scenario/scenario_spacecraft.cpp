// scenario_spacecraft.cpp: `environment` and `spacecraft` (hub mass
// properties and the initial state, optionally from an approach hyperbola).
#include "scenario/scenario_schema.h"

#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "sim/environment.h"
#include "sim/magnetic_field.h"
#include "sim/units.h"

namespace harness::schema {

namespace {

// A key written to the manifest only when `given` (an absent optional key
// leaves the manifests of older scenarios unchanged).
KeyDef written_if(KeyDef k, std::function<bool(const Scenario&)> given)
{
  WriteFn w = std::move(k.write);
  k.write = [w, given](const KeyDef& d, nlohmann::json& j, const Scenario& sc, size_t i) {
    if (given(sc)) w(d, j, sc, i);
  };
  return k;
}

std::string utc_epoch_text(const std::string& s)
{
  std::string why;
  return parse_utc_epoch(s, &why) ? "" : why;
}

// A disturbance model's map: `enabled` and `period` (plus `extra` keys);
// written when enabled.
template <class M>
Section env_model_section(const std::string& name, M model, std::vector<KeyDef> extra = {})
{
  std::vector<KeyDef> keys{
      boolean("enabled", [model](auto& sc, size_t) -> auto& { return model(sc).enabled; }).unit("default false"),
      real("period", [model](auto& sc, size_t) -> auto& { return model(sc).period; })
          .bounds([](double x, bool) {
            return x >= 0.0 && x <= 86400.0 ? std::string() : "must be in [0, 86400] s (0: every integration stage)";
          })
          .unit("s, rounded to ns"),
  };
  for (KeyDef& k : extra) keys.push_back(std::move(k));
  Section s{name, std::move(keys), {}};
  s.present = [model](const Scenario& sc) { return model(sc).enabled; };
  return s;
}

}  // namespace

const Section& environment_section()
{
#define KESTREL_ENV(member) [](auto& sc) -> auto& { return sc.environment.member; }
  static const Section s{
      "environment",
      {
          real("mu", [](auto& sc, size_t) -> auto& { return sc.environment.mu; })
              .bounds(non_negative("m^3/s^2")).unit("m^3/s^2"),
          written_if(vec3("sun_position_N", [](auto& sc, size_t) -> auto& { return sc.environment.sun_position_N; })
                         .unit("m"),
                     [](const Scenario& sc) { return sc.environment.epoch.empty(); }),
          written_if(string("epoch", [](auto& sc, size_t) -> auto& { return sc.environment.epoch; })
                         .scheck(utc_epoch_text).unit("UTC YYYY-MM-DDThh:mm:ssZ"),
                     [](const Scenario& sc) { return !sc.environment.epoch.empty(); }),
          written_if(boolean("j2", [](auto& sc, size_t) -> auto& { return sc.environment.j2; })
                         .unit("default false: Earth's J2 in the gravity"),
                     [](const Scenario& sc) { return sc.environment.j2; }),
      },
      {
          env_model_section("gravity_gradient", KESTREL_ENV(gravity_gradient)),
          env_model_section("solar_pressure", KESTREL_ENV(solar_pressure)),
          env_model_section("drag", KESTREL_ENV(drag),
                            {real("density_scale", [](auto& sc, size_t) -> auto& {
                               return sc.environment.drag_density_scale;
                             }).bounds(non_negative("-")).unit("-")}),
          env_model_section("magnetic", KESTREL_ENV(magnetic),
                            {integer("igrf_degree", 1, sim::kIgrfMaxDegree, [](auto& sc, size_t) -> auto& {
                               return sc.environment.igrf_degree;
                             }).unit("-")}),
      }};
#undef KESTREL_ENV
  return s;
}

namespace {
// Models that need an Earth orbit: J2, a dated Sun, the atmosphere or the
// field (not gravity gradient, which needs only mu > 0).
void check_env_models(MapReader& r, const Scenario& sc)
{
  const EnvironmentSpec& e = sc.environment;
  if (e.gravity_gradient.enabled && !(e.mu > 0.0))
    r.error_at("gravity_gradient", "needs gravity: environment.mu > 0");
  const bool earth = std::fabs(e.mu - sim::kMuEarth) <= 1e-3 * sim::kMuEarth;
  if (e.j2 && !earth)
    r.error_at("j2", "Earth's J2 needs an Earth orbit: environment.mu = " + fmt(sim::kMuEarth) +
                         " m^3/s^2 (within 0.1%), got " + fmt(e.mu));
  for (EnvSource src : {EnvSource::SolarPressure, EnvSource::Drag, EnvSource::Magnetic}) {
    if (!env_model(e, src).enabled) continue;
    const std::string name = env_source_name(src);
    if (e.epoch.empty()) r.error_at(name, "needs environment.epoch (the UTC date of t = 0)");
    if (!earth)
      r.error_at(name, "needs an Earth orbit: environment.mu = " + fmt(sim::kMuEarth) + " m^3/s^2 (within 0.1%), got " +
                           fmt(e.mu));
  }
  if (!e.epoch.empty()) {
    // a dated run is an Earth orbit: its Sun is the almanac's (sun_source.h)
    if (!earth)
      r.error_at("epoch", "a dated run is an Earth orbit: needs environment.mu = " + fmt(sim::kMuEarth) +
                              " m^3/s^2 (within 0.1%), got " + fmt(e.mu));
    if (r.has("sun_position_N"))
      r.error_at("sun_position_N", "with environment.epoch the Sun comes from the date (almanac); remove this key");
  }
  std::string why;
  const std::optional<sim::UtcEpoch> ep = e.epoch.empty() ? std::nullopt : parse_utc_epoch(e.epoch, &why);
  if (e.magnetic.enabled && ep) {
    const double year = sim::decimal_year(sim::days_since_j2000(*ep));
    if (year < 2020.0 || year > 2030.0)
      r.error_at("epoch", "the magnetic model (IGRF-14) is valid from 2020 to 2030, got " + e.epoch);
  }
}
}  // namespace

void read_environment(MapReader r, Scenario& sc)
{
  const Section& def = environment_section();
  read_keys(r, def, sc);
  for (const Section& m : def.children) {
    MapReader sub = r.sub(m.name);
    read_keys(sub, m, sc);
    sub.finish();
  }
  check_env_models(r, sc);
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

Check unit_interval()
{
  return [](double x, bool) { return x >= 0.0 && x <= 1.0 ? std::string() : "must be in [0, 1]"; };
}

// spacecraft.facets: the surfaces solar pressure and drag act on (sim::Facet).
Section facet_section()
{
#define KESTREL_FACET(member) [](auto& sc, size_t i) -> auto& { return sc.spacecraft.facets[i].member; }
  Section f{"facets",
            {
                real("area", KESTREL_FACET(area)).req("facet area [m^2]").bounds(positive("m^2")).unit("m^2"),
                vec3("normal", KESTREL_FACET(n_B), true).req("outward unit normal in B"),
                vec3("centre_of_pressure", KESTREL_FACET(r_B)).req("centre of pressure from B [m]").unit("m"),
                real("absorbed", KESTREL_FACET(absorbed)).bounds(unit_interval()).unit("-, default 1"),
                real("specular", KESTREL_FACET(specular)).bounds(unit_interval()).unit("-, default 0"),
                real("diffuse", KESTREL_FACET(diffuse)).bounds(unit_interval()).unit("-, default 0"),
                real("C_D", KESTREL_FACET(C_D)).bounds(non_negative("-")).unit("-, default 2.2"),
            },
            {}};
#undef KESTREL_FACET
  f.list = true;
  f.capacity = static_cast<size_t>(sim::kMaxFacets);
  f.count = [](const Scenario& sc) { return sc.spacecraft.facets.size(); };
  f.present = [](const Scenario& sc) { return !sc.spacecraft.facets.empty(); };
  return f;
}

void read_facets(MapReader& r, Scenario& sc)
{
  const YAML::Node list = r.get("facets");
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) {
    r.ctx().error(list, "spacecraft.facets", "expected a list of facets, got " + kind_name(list));
    return;
  }
  if (list.size() > static_cast<size_t>(sim::kMaxFacets)) {
    r.ctx().error(list, "spacecraft.facets", "at most " + std::to_string(sim::kMaxFacets) + " facets, got " +
                                                 std::to_string(list.size()));
    return;
  }
  const Section& def = *spacecraft_section().child("facets");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "spacecraft.facets[" + std::to_string(i) + "]";
    sc.spacecraft.facets.emplace_back();
    if (!list[i].IsMap()) {
      r.ctx().error(list[i], path, "expected a map of facet keys, got " + kind_name(list[i]));
      continue;
    }
    MapReader f(r.ctx(), list[i], path);
    read_keys(f, def, sc, i);
    const sim::Facet& x = sc.spacecraft.facets[i];
    const double sum = x.absorbed + x.specular + x.diffuse;
    if (std::fabs(sum - 1.0) > 1e-9)
      f.error_at(f.has("diffuse") ? "diffuse" : f.has("specular") ? "specular" : "absorbed",
                 "absorbed + specular + diffuse must be 1 (within 1e-9), got " + fmt(sum));
    f.finish();
  }
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
          written_if(vec3("residual_dipole", [](auto& sc, size_t) -> auto& { return sc.spacecraft.residual_dipole_B; })
                         .unit("A*m^2"),
                     [](const Scenario& sc) {  // with the field on, also when zero (Monte Carlo disperses it)
                       return sc.environment.magnetic.enabled || !sc.spacecraft.residual_dipole_B.isZero(0.0);
                     }),
      },
      {Section{"initial",
               {
                   attitude_key(vec3("sigma_BN", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.sigma_BN; })
                                    .vcheck(mrp_in_unit_ball).unit("-")),
                   vec3("omega_BN_B", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.omega_BN_B; })
                       .alt("_deg_s", sim::kRadPerDeg).vcheck(rate_within(kMaxBodyRateDegS)).unit("rad/s"),
                   vec3("r_CN_N", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.r_CN_N; }).unit("m"),
                   vec3("v_CN_N", [](auto& sc, size_t) -> auto& { return sc.spacecraft.initial.v_CN_N; })
                       .unit("m/s"),
               },
               {hyperbola_section()}},
       facet_section()}};
  return s;
}

void read_spacecraft(MapReader r, Scenario& sc)
{
  const Section& def = spacecraft_section();
  read_keys(r, def, sc);
  read_facets(r, sc);
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
