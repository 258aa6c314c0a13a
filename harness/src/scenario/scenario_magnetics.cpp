// scenario_magnetics.cpp: `magnetorquers` (sim::MagnetorquerParams each),
// `magnetorquer_drive` (dipole or PWM commands) and `sensors.magnetometer`
// (sim::MagnetometerParams).  All need environment.magnetic; all are off
// (absent) by default and then not written.  docs/environment.md, "In a scenario".
#include "scenario/scenario_schema.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "sim/capacities.h"

namespace harness::schema {

namespace {

constexpr double kAxisTol = 1e-6;   // [-] | |axis| - 1 | of a magnetorquer axis as written
constexpr double kOrthoTol = 1e-6;  // [-] max |R R^T - I| of the magnetometer's dcm_SB as written

int64_t to_ns(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }

std::string scale_errors_above_minus_one(const Eigen::Vector3d& e)
{
  return e.minCoeff() > -1.0 ? "" : "each component must be > -1 (the output is times 1 + e)";
}

// A list of `rows` lists of `cols` finite numbers (cols < 0: any, the same
// for every row) at node v; nullopt after reporting at kp.
std::optional<Eigen::MatrixXd> matrix_of(MapReader& r, const YAML::Node& v, const std::string& kp, int rows, int cols)
{
  if (!v.IsSequence() || static_cast<int>(v.size()) != rows) {
    r.ctx().error(v, kp, "expected a list of " + std::to_string(rows) + " rows (lists of numbers), got " +
                             (v.IsSequence() ? "a list of " + std::to_string(v.size()) : kind_name(v)));
    return std::nullopt;
  }
  Eigen::MatrixXd m;
  for (int i = 0; i < rows; ++i) {
    const YAML::Node row = v[static_cast<size_t>(i)];
    const std::string rp = kp + "[" + std::to_string(i) + "]";
    if (!row.IsSequence()) {
      r.ctx().error(row, rp, "expected a list of numbers, got " + kind_name(row));
      return std::nullopt;
    }
    const int n = static_cast<int>(row.size());
    if (i == 0) m.resize(rows, cols >= 0 ? cols : n);
    if (n != m.cols()) {
      r.ctx().error(row, rp, "expected " + std::to_string(m.cols()) + " numbers, got " + std::to_string(n));
      return std::nullopt;
    }
    for (int j = 0; j < n; ++j) {
      double x = 0.0;
      if (!decode_double(row[static_cast<size_t>(j)], x) || !std::isfinite(x)) {
        r.ctx().error(row[static_cast<size_t>(j)], rp + "[" + std::to_string(j) + "]",
                      "expected a finite number, got " + kind_name(row[static_cast<size_t>(j)]));
        return std::nullopt;
      }
      m(i, j) = x;
    }
  }
  return m;
}

nlohmann::json rows_json(const Eigen::MatrixXd& m)
{
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    a.push_back(row);
  }
  return a;
}

#define KESTREL_MAG(member) [](auto& sc, size_t) -> auto& { return sc.sensors.magnetometer.member; }

// sensors.magnetometer.dcm_SB: 3 rows (the sensor axes in B), orthonormal
// within kOrthoTol and right-handed.
KeyDef dcm_key()
{
  return custom(
      "dcm_SB",
      [](const KeyDef& k, MapReader& r, Scenario& sc, size_t) {
        const YAML::Node v = r.get(k.name);
        if (!v.IsDefined()) return;
        const std::optional<Eigen::MatrixXd> m = matrix_of(r, v, r.key_path(k.name), 3, 3);
        if (!m) return;
        const Eigen::Matrix3d R = *m;
        const double err = (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (!(err <= kOrthoTol))
          r.error_at(k.name, "must be orthonormal (rows: the sensor axes in B; max |R R^T - I| <= " + fmt(kOrthoTol) +
                                 "), got " + fmt(err));
        else if (!(R.determinant() > 0.0))
          r.error_at(k.name, "must be a rotation (right-handed: det > 0), got det " + fmt(R.determinant()));
        else
          sc.sensors.magnetometer.dcm_SB = R;
      },
      [](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t) {
        j[k.name] = rows_json(sc.sensors.magnetometer.dcm_SB);
      })
      .json_shape(json_list_of(json_vec3(), 3, 3))
      .unit("3 rows: the sensor axes in B, orthonormal, right-handed");
}

// sensors.magnetometer.interference: 3 rows of one number per magnetorquer
// [T/(A*m^2)] (the magnetorquers are read before the sensors).
KeyDef interference_key()
{
  return custom(
      "interference",
      [](const KeyDef& k, MapReader& r, Scenario& sc, size_t) {
        const YAML::Node v = r.get(k.name);
        if (!v.IsDefined()) return;
        const std::optional<Eigen::MatrixXd> m = matrix_of(r, v, r.key_path(k.name), 3, -1);
        if (!m) return;
        if (m->cols() != static_cast<Eigen::Index>(sc.magnetorquers.size()))
          r.error_at(k.name, "needs one column per magnetorquer (" + std::to_string(sc.magnetorquers.size()) +
                                 "), got " + std::to_string(m->cols()));
        else
          sc.sensors.magnetometer.interference = *m;
      },
      [](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t) {
        if (sc.sensors.magnetometer.interference.cols() > 0)
          j[k.name] = rows_json(sc.sensors.magnetometer.interference);
      })
      .json_shape(json_list_of(json_list_of({{"type", "number"}}), 3, 3))
      .unit("T/(A*m^2), 3 rows of one number per magnetorquer");
}

}  // namespace

const Section& magnetorquers_section()
{
#define KESTREL_MTQ(member) [](auto& sc, size_t i) -> auto& { return sc.magnetorquers[i].member; }
  static const Section s = [] {
    Section t{"magnetorquers",
              {
                  string("name", KESTREL_MTQ(name)).unit("default mtq<i+1>, unique"),
                  vec3("axis", KESTREL_MTQ(axis_B), true).req("unit dipole axis in B"),
                  real("m_max", KESTREL_MTQ(m_max)).req("saturation dipole [A*m^2]").bounds(positive("A*m^2")).unit("A*m^2"),
                  real("m_remanent", KESTREL_MTQ(m_remanent)).bounds(non_negative("A*m^2")).unit("A*m^2, < m_max"),
                  real("power_max", KESTREL_MTQ(power_max)).bounds(non_negative("W")).unit("W"),
              },
              {}};
    t.list = true;
    t.capacity = static_cast<size_t>(sim::kMaxMagnetorquers);
    t.count = [](const Scenario& sc) { return sc.magnetorquers.size(); };
    t.present = [](const Scenario& sc) { return !sc.magnetorquers.empty(); };
    return t;
  }();
#undef KESTREL_MTQ
  return s;
}

const Section& magnetorquer_drive_section()
{
  static const Section s = [] {
    Section d{"magnetorquer_drive",
              {
                  choice<MtqDriveMode>("mode", {{"dipole", MtqDriveMode::Dipole}, {"pwm", MtqDriveMode::Pwm}},
                                       [](auto& sc, size_t) -> auto& { return sc.magnetorquer_drive.mode; }),
                  real("pwm_period", [](auto& sc, size_t) -> auto& { return sc.magnetorquer_drive.pwm_period; })
                      .bounds(non_negative("s")).unit("s, 0: the FSW period"),
              },
              {}};
    d.present = [](const Scenario& sc) { return !sc.magnetorquers.empty(); };
    return d;
  }();
  return s;
}

Section magnetometer_section()
{
  Section m{"magnetometer",
            {
                boolean("enabled", KESTREL_MAG(enabled)).unit("default false"),
                dcm_key(),
                real("period", KESTREL_MAG(period)).bounds(non_negative("s")).unit("s, 0: the FSW period"),
                real("field_period", KESTREL_MAG(field_period))
                    .bounds(non_negative("s"))
                    .unit("s, 0: the field model at every sample"),
                real("sigma", KESTREL_MAG(sigma)).bounds(non_negative("T")).unit("T"),
                vec3("bias", KESTREL_MAG(bias)).unit("T"),
                vec3("scale_error", KESTREL_MAG(scale_error)).vcheck(scale_errors_above_minus_one).unit("-"),
                real("lsb", KESTREL_MAG(lsb)).bounds(non_negative("T")).unit("T"),
                real("range", KESTREL_MAG(range)).bounds(non_negative("T")).unit("T"),
                interference_key(),
            },
            {}};
  m.present = [](const Scenario& sc) { return sc.sensors.magnetometer.enabled; };
  return m;
}
#undef KESTREL_MAG

namespace {
// One rod: its keys, the axis as written (within kAxisTol of unit length)
// and the remanence below saturation.
void read_rod(MapReader& top, const YAML::Node& node, Scenario& sc, size_t i)
{
  MapReader r(top.ctx(), node, "magnetorquers[" + std::to_string(i) + "]");
  sc.magnetorquers.emplace_back();
  sc.magnetorquers.back().name = "mtq" + std::to_string(i + 1);
  read_keys(r, magnetorquers_section(), sc, i);
  const MagnetorquerSpec& m = sc.magnetorquers[i];
  if (r.has("axis") && node["axis"].IsSequence() && node["axis"].size() == 3) {
    Eigen::Vector3d a;
    bool ok = true;
    for (size_t c = 0; c < 3; ++c) ok = ok && decode_double(node["axis"][c], a(static_cast<int>(c)));
    if (ok && !(std::fabs(a.norm() - 1.0) <= kAxisTol))
      r.error_at("axis", "must be a unit vector within " + fmt(kAxisTol) + " (a rod's axis sets its dipole), |axis| = " +
                             fmt(a.norm()));
  }
  if (r.has("m_remanent") && m.m_max > 0.0 && !(m.m_remanent < m.m_max))
    r.error_at("m_remanent", "must be < m_max (" + fmt(m.m_max) + " A*m^2), got " + fmt(m.m_remanent));
  r.finish();
  for (size_t j = 0; j < i; ++j)
    if (sc.magnetorquers[j].name == m.name) r.error_at("name", "duplicate magnetorquer name '" + m.name + "'");
  for (const WheelSpec& w : sc.wheels)
    if (w.name == m.name) r.error_at("name", "'" + m.name + "' already names a wheel (event devices are named)");
  for (const ThrusterSpec& t : sc.thrusters)
    if (t.name == m.name) r.error_at("name", "'" + m.name + "' already names a thruster (event devices are named)");
  for (const char* reserved : {"gyro", "star_tracker", "fsw", "magnetometer"})
    if (m.name == reserved) r.error_at("name", "'" + m.name + "' names another device");
}
}  // namespace

void read_magnetorquers(MapReader& top, Scenario& sc)
{
  const YAML::Node list = top.get("magnetorquers");
  MapReader drive = top.sub("magnetorquer_drive");
  if (list.IsDefined() && !list.IsNull()) {
    if (!list.IsSequence()) {
      top.ctx().error(list, "magnetorquers", "expected a list of magnetorquers, got " + kind_name(list));
    } else if (list.size() > static_cast<size_t>(sim::kMaxMagnetorquers)) {
      top.ctx().error(list, "magnetorquers", "at most " + std::to_string(sim::kMaxMagnetorquers) +
                                                 " magnetorquers, got " + std::to_string(list.size()));
    } else {
      for (size_t i = 0; i < list.size(); ++i) read_rod(top, list[i], sc, i);
    }
  }
  read_keys(drive, magnetorquer_drive_section(), sc);
  if (!sc.magnetorquers.empty() && !sc.environment.magnetic.enabled)
    top.error_at_key("magnetorquers", "need the geomagnetic field: environment.magnetic.enabled: true");
  if (top.has("magnetorquer_drive") && sc.magnetorquers.empty())
    top.error_at_key("magnetorquer_drive", "given but there are no magnetorquers");
  // PWM cycles start at the control instants: the FSW period must hold a whole number of them.
  const int64_t fsw_ns = static_cast<int64_t>(sc.rates.fsw_divisor) * to_ns(sc.rates.dt);
  const int64_t pwm_ns = to_ns(sc.magnetorquer_drive.pwm_period);
  if (sc.magnetorquer_drive.pwm_period > 0.0 && fsw_ns > 0 && (pwm_ns <= 0 || fsw_ns % pwm_ns != 0))
    drive.error_at("pwm_period", "the FSW period (" + fmt(static_cast<double>(fsw_ns) * 1e-9) +
                                     " s) must be a whole number of PWM periods, got " +
                                     fmt(sc.magnetorquer_drive.pwm_period) + " s");
  drive.finish();
}

// The magnetometer's rules across sections (after its keys are read).
void check_magnetometer(MapReader& m, const Scenario& sc)
{
  const MagnetometerSpec& g = sc.sensors.magnetometer;
  if (!g.enabled) return;
  if (!sc.environment.magnetic.enabled)
    m.error_at("enabled", "needs the geomagnetic field: environment.magnetic.enabled: true");
  const int64_t tick = to_ns(sc.rates.dt), p = to_ns(g.period);
  if (g.period > 0.0 && tick > 0 && (p < tick || p % tick != 0))
    m.error_at("period", "must be a whole number of steps dt = " + fmt(sc.rates.dt) + " s, got " + fmt(g.period) + " s");
  if (g.range > 0.0 && g.lsb > g.range) m.error_at("lsb", "must not exceed range (" + fmt(g.range) + " T)");
  // the field's samples are magnetometer samples: a whole number of its period
  const int64_t sample = g.period > 0.0 ? p : tick * static_cast<int64_t>(sc.rates.fsw_divisor);
  const int64_t f = to_ns(g.field_period);
  if (g.field_period > 0.0 && sample > 0 && (f < sample || f % sample != 0))
    m.error_at("field_period", "must be a whole number of the magnetometer's sample period (" +
                                   fmt(1e-9 * static_cast<double>(sample)) + " s), got " + fmt(g.field_period) + " s");
}

}  // namespace harness::schema
