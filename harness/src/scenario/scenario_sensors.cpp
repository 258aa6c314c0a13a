// scenario_sensors.cpp: `sensors` (coarse sun sensors, star tracker, gyro,
// wheel tachometers, the magnetometer (scenario_magnetics.cpp) and the noise switch).
#include "scenario/scenario_limits.h"
#include "scenario/scenario_schema.h"

#include "sim/units.h"

namespace harness::schema {

namespace {
constexpr double kRadPerArcsec = sim::kRadPerDeg / 3600.0;  // [rad / arcsec]

// Star tracker 1-sigma: [0, 1 deg] in rad, or in arcsec with _arcsec.
std::string sigma_arcsec(double x, bool arcsec)
{
  const double lim = arcsec ? kMaxStarTrackerSigmaArcsec : kMaxStarTrackerSigmaArcsec * kRadPerArcsec;
  if (x >= 0.0 && x <= lim) return "";
  return "must be in [0, " + fmt(kMaxStarTrackerSigmaArcsec) + " arcsec] = [0, " +
         fmt(kMaxStarTrackerSigmaArcsec * kRadPerArcsec) + " rad]" +
         (!arcsec && x >= 0.0 && x <= kMaxStarTrackerSigmaArcsec ? "; a value in arcsec? use the _arcsec spelling"
                                                                 : "");
}

#define KESTREL_SENSOR(member) [](auto& sc, size_t) -> auto& { return sc.sensors.member; }

// css.normals: a list of unit vectors, at most kMaxScenarioCss.
KeyDef css_normals()
{
  return custom(
      "normals",
      [](const KeyDef& k, MapReader& css, Scenario& sc, size_t) {
        YAML::Node normals = css.get(k.name);
        if (!normals.IsDefined()) return;
        const std::string kp = css.key_path(k.name);
        if (!normals.IsSequence()) {
          css.ctx().error(normals, kp, "expected a list of unit 3-vectors, got " + kind_name(normals));
          return;
        }
        if (normals.size() > kMaxScenarioCss)
          css.ctx().error(normals, kp, "at most " + std::to_string(kMaxScenarioCss) + " sensors (FSW_MAX_CSS), got " +
                                           std::to_string(normals.size()));
        for (size_t i = 0; i < normals.size() && i < kMaxScenarioCss; ++i)
          if (auto n = css.unit_of(normals[i], kp + "[" + std::to_string(i) + "]"))
            sc.sensors.css.normals_B.push_back(*n);
      },
      [](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t) {
        nlohmann::json a = nlohmann::json::array();
        for (const Eigen::Vector3d& n : sc.sensors.css.normals_B) a.push_back(nlohmann::json::array({n(0), n(1), n(2)}));
        j[k.name] = a;
      })
      .json_shape(json_list_of(json_vec3(), 0, kMaxScenarioCss))
      .unit("unit vectors in B, one per sensor");
}

}  // namespace

const Section& sensors_section()
{
  static const Section s{
      "sensors",
      {boolean("noise", KESTREL_SENSOR(noise)).unit("default true")},
      {
          Section{"css",
                  {
                      real("fov", KESTREL_SENSOR(css.fov))
                          .alt("_deg", sim::kRadPerDeg)
                          .bounds([](double x, bool deg) {
                            const double lim = deg ? 90.0 : 0.5 * sim::kPi;
                            return x > 0.0 && x <= lim ? std::string()
                                                       : std::string("half-angle must be in (0, 90 deg]");
                          })
                          .unit("rad"),
                      real("scale", KESTREL_SENSOR(css.scale)).bounds(positive("-")).unit("-"),
                      real("noise_std", KESTREL_SENSOR(css.noise_std)).bounds(non_negative("-")).unit("-"),
                      css_normals(),
                  },
                  {}},
          Section{"star_tracker",
                  {
                      boolean("enabled", KESTREL_SENSOR(star_tracker.enabled)),
                      real("sigma_cross", KESTREL_SENSOR(star_tracker.sigma_cross))
                          .alt("_arcsec", kRadPerArcsec).bounds(sigma_arcsec).unit("rad"),
                      real("sigma_bore", KESTREL_SENSOR(star_tracker.sigma_bore))
                          .alt("_arcsec", kRadPerArcsec).bounds(sigma_arcsec).unit("rad"),
                      real("sun_exclusion", KESTREL_SENSOR(star_tracker.sun_exclusion))
                          .alt("_deg", sim::kRadPerDeg)
                          .bounds(angle_below(180.0))
                          .unit("rad"),
                      integer("divisor", 1, kMaxDivisor, KESTREL_SENSOR(star_tracker.divisor)).unit("ticks"),
                  },
                  {}},
          Section{"gyro",
                  {
                      boolean("enabled", KESTREL_SENSOR(gyro.enabled)),
                      real("arw", KESTREL_SENSOR(gyro.arw)).bounds(non_negative("rad/sqrt(s)")).unit("rad/sqrt(s)"),
                      real("rrw", KESTREL_SENSOR(gyro.rrw)).bounds(non_negative("rad/s^(3/2)")).unit("rad/s^(3/2)"),
                      real("lsb", KESTREL_SENSOR(gyro.lsb)).bounds(non_negative("rad/s")).unit("rad/s"),
                      integer("divisor", 1, kMaxDivisor, KESTREL_SENSOR(gyro.divisor)).unit("ticks"),
                  },
                  {}},
          Section{"tachometer",
                  {
                      boolean("enabled", KESTREL_SENSOR(tachometer.enabled)),
                      real("sigma", KESTREL_SENSOR(tachometer.sigma))
                          .alt("_rpm", sim::kRadPerSecPerRpm).bounds(non_negative("rad/s or rpm")).unit("rad/s"),
                      real("lsb", KESTREL_SENSOR(tachometer.lsb))
                          .alt("_rpm", sim::kRadPerSecPerRpm).bounds(non_negative("rad/s or rpm")).unit("rad/s"),
                      integer("divisor", 1, kMaxDivisor, KESTREL_SENSOR(tachometer.divisor)).unit("ticks"),
                  },
                  {}},
          magnetometer_section(),
      }};
  return s;
}
#undef KESTREL_SENSOR

void read_sensors(MapReader r, Scenario& sc)
{
  const Section& def = sensors_section();
  for (const Section& c : def.children) {
    MapReader m = r.sub(c.name);
    read_keys(m, c, sc);
    if (c.name == "magnetometer") check_magnetometer(m, sc);
    m.finish();
  }
  read_keys(r, def, sc);
  r.finish();
}

}  // namespace harness::schema
