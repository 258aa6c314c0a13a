// mc_draw.cpp: see mc_draw.h.
#include "scenario/mc_draw.h"

#include <cmath>

#include "scenario/overrides.h"
#include "scenario/scenario_schema.h"
#include "sim/attitude.h"

namespace harness {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

uint64_t mix(uint64_t z)  // SplitMix64's finaliser
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

double as_double(const ParameterValue& p)
{
  if (std::holds_alternative<double>(p.value)) return std::get<double>(p.value);
  if (std::holds_alternative<long long>(p.value)) return static_cast<double>(std::get<long long>(p.value));
  if (std::holds_alternative<uint64_t>(p.value)) return static_cast<double>(std::get<uint64_t>(p.value));
  return std::nan("");
}

// A number drawn for a key of type Integer/Unsigned is rounded to the
// nearest whole number (documented).
ParameterValue number_for(const ParameterValue& nominal, double x)
{
  if (std::holds_alternative<long long>(nominal.value)) return ParameterValue(static_cast<long long>(std::llround(x)));
  if (std::holds_alternative<uint64_t>(nominal.value))
    return ParameterValue(static_cast<uint64_t>(x <= 0.0 ? 0 : std::llround(x)));
  return ParameterValue(x);
}

// Two unit vectors completing n to a right-handed orthonormal basis.
void perpendiculars(const Eigen::Vector3d& n, Eigen::Vector3d& e1, Eigen::Vector3d& e2)
{
  Eigen::Index k = 0;
  n.cwiseAbs().minCoeff(&k);
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  a(k) = 1.0;
  e1 = n.cross(a).normalized();
  e2 = n.cross(e1);
}

// A rotation vector: isotropic normal (angle_std per axis) or a uniformly
// random axis with an angle uniform in [0, angle_max].
Eigen::Vector3d rotation_vector(McStream& r, const DispersionSpec& s)
{
  if (s.angle_std) return *s.angle_std * Eigen::Vector3d(r.normal(), r.normal(), r.normal());
  Eigen::Vector3d axis;
  do {
    axis = Eigen::Vector3d(r.normal(), r.normal(), r.normal());
  } while (!(axis.norm() > 1e-12));
  return axis.normalized() * (*s.angle_max * r.uniform());
}

std::string unit_of(const schema::KeyDef& k, bool suffixed)
{
  if (!suffixed) return k.doc.size() <= 12 ? k.doc : "";
  std::string u = k.suffix.substr(1);
  const size_t us = u.find('_');
  if (us != std::string::npos) u[us] = '/';
  return u;
}

}  // namespace

McStream::McStream(uint64_t master, uint64_t run, const std::string& key)
{
  uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a of the key path
  for (unsigned char c : key) h = (h ^ c) * 0x100000001b3ULL;
  uint64_t s = mix(master ^ 0x6b65737472656c4dULL);  // "kestrelM"
  s = mix(s ^ mix(run + kGolden));
  s_ = mix(s ^ mix(h));
}

uint64_t McStream::next()
{
  s_ += kGolden;
  return mix(s_);
}

double McStream::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double McStream::normal()
{
  const double u1 = 1.0 - uniform();  // (0, 1]: the log is finite
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

uint64_t mc_run_seed(uint64_t master, uint64_t run)
{
  return mix(mix(master ^ 0x73656e736f727321ULL) ^ mix(run + kGolden)) & ((1ULL << 53) - 1);
}

namespace {

// A choice's value (as written) as a value of key k: "" or why it is not one.
std::string decode_choice(const schema::KeyDef& k, const std::string& value, ParameterValue& out)
{
  switch (k.type) {
    case schema::Type::Real: {
      double x = 0.0;
      if (!decode_double(YAML::Node(value), x)) return "not a number";
      out = ParameterValue(x);
      return "";
    }
    case schema::Type::Integer:
    case schema::Type::Unsigned: {
      long long x = 0;
      if (!decode_int(YAML::Node(value), x)) return "not a whole number";
      if (k.type == schema::Type::Integer) out = ParameterValue(x);
      else if (x < 0) return "must be >= 0";
      else out = ParameterValue(static_cast<uint64_t>(x));
      return "";
    }
    case schema::Type::Bool:
      if (value != "true" && value != "false") return "expected true or false";
      out = ParameterValue(value == "true");
      return "";
    default: out = ParameterValue(value); return "";
  }
}

McTarget bind_target(const Scenario& nominal, const DispersionSpec& s, size_t i, const std::string& path)
{
  McTarget t;
  t.dispersion = i;
  t.path = path;
  const std::vector<std::string> parts = split_path(path);
  t.name = normalise_path(parts);
  const KeyTarget k = resolve_path(parts, list_sizes(nominal));
  t.key = k.key;
  t.suffixed = k.suffixed;
  t.index = k.index;
  try {
    t.nominal = get_parameter(nominal, path);  // a settable key: t.key is set
  } catch (const ScenarioError& e) {
    t.error = e.issues().front().message;
    return t;
  } catch (const std::exception& e) {
    t.error = e.what();
    return t;
  }
  if (s.dist != DistKind::Choice) return t;
  for (const std::string& v : s.values) {
    t.choices.emplace_back(0.0);
    t.choice_errors.push_back(decode_choice(*t.key, v, t.choices.back()));
  }
  return t;
}

void add_columns(const McTarget& t, const DispersionSpec& s, std::vector<McColumn>& out)
{
  const std::string& name = t.name;
  const std::string unit = t.key ? unit_of(*t.key, t.suffixed) : "";
  switch (s.dist) {
    case DistKind::Normal:
    case DistKind::TruncatedNormal:
    case DistKind::Uniform: out.push_back({name, unit}); break;
    case DistKind::Choice: out.push_back({name + ".choice", "index"}); break;
    case DistKind::NormalVector:
      for (const char* c : {"_x", "_y", "_z"}) out.push_back({name + c, unit});
      break;
    case DistKind::UnitVector:
    case DistKind::Attitude: out.push_back({name + ".angle_deg", "deg"}); break;
    case DistKind::Inertia:
      out.push_back({name + ".angle_deg", "deg"});
      if (s.principal_std_rel > 0.0)
        for (const char* c : {".scale_1", ".scale_2", ".scale_3"}) out.push_back({name + c, "-"});
      break;
  }
}

}  // namespace

McBinding bind_dispersions(const Scenario& nominal)
{
  McBinding b;
  if (!nominal.monte_carlo) return b;
  b.specs = nominal.monte_carlo->dispersions;
  for (size_t i = 0; i < b.specs.size(); ++i) {
    std::string why;
    for (const std::string& k : expand_dispersion_key(nominal, b.specs[i].key, why)) {
      b.targets.push_back(bind_target(nominal, b.specs[i], i, k));
      add_columns(b.targets.back(), b.specs[i], b.columns);
    }
    b.spec_errors.push_back(why);
  }
  return b;
}

// ---- the draws of one bound key ---------------------------------------------
// Each returns "" or why the draw is invalid; the values drawn go to d.drawn
// (not those of a draw the key refuses, except inertia's).

namespace {

std::string set_value(const McTarget& t, Scenario& sc, const ParameterValue& v)
{
  return t.key->set(*t.key, sc, t.index, v, t.suffixed);
}

std::string set_number(const McTarget& t, McDraw& d, double x)
{
  const std::string bad = set_value(t, d.sc, number_for(t.nominal, x));
  if (bad.empty()) d.drawn.push_back(x);
  return bad;
}

std::string draw_truncated_normal(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const double m = s.mean.value_or(as_double(t.nominal));
  for (int tries = 0; tries < 10000; ++tries) {  // acceptance >= 1 % (checked when read)
    const double c = m + s.std * r.normal();
    if (c >= *s.min && c <= *s.max) return set_number(t, d, c);
  }
  return "truncated_normal: no value in bounds after 10000 draws";
}

std::string draw_uniform(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const double lo = s.half_width ? as_double(t.nominal) - *s.half_width : *s.min;
  const double hi = s.half_width ? as_double(t.nominal) + *s.half_width : *s.max;
  return set_number(t, d, lo + (hi - lo) * r.uniform());
}

std::string draw_choice(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  std::vector<double> w = s.weights;
  if (w.empty()) w.assign(s.values.size(), 1.0);
  double total = 0.0;
  for (double x : w) total += x;
  const double u = r.uniform() * total;
  size_t pick = 0;
  double acc = 0.0;
  for (pick = 0; pick + 1 < w.size(); ++pick) {
    acc += w[pick];
    if (u < acc) break;
  }
  while (w[pick] == 0.0 && pick > 0) --pick;  // u at a boundary of zero-weight values
  const std::string bad = t.choice_errors[pick].empty() ? set_value(t, d.sc, t.choices[pick]) : t.choice_errors[pick];
  if (bad.empty()) d.drawn.push_back(static_cast<double>(pick));
  return bad;
}

std::string draw_normal_vector(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const Eigen::Vector3d v0 = std::get<Eigen::Vector3d>(t.nominal.value);
  const Eigen::Vector3d dv(s.std_vec(0) * r.normal(), s.std_vec(1) * r.normal(), s.std_vec(2) * r.normal());
  const Eigen::Vector3d v = v0 + dv;
  const std::string bad = set_value(t, d.sc, v);
  if (bad.empty())
    for (int c = 0; c < 3; ++c) d.drawn.push_back(v(c));
  return bad;
}

std::string draw_unit_vector(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const Eigen::Vector3d n = std::get<Eigen::Vector3d>(t.nominal.value).normalized();
  Eigen::Vector3d e1, e2;
  perpendiculars(n, e1, e2);
  double theta = 0.0, phi = 0.0;
  if (s.angle_std) {  // tilt components in the plane normal to n: N(0, sigma) each (Rayleigh angle)
    const double a = *s.angle_std * r.normal(), b = *s.angle_std * r.normal();
    theta = std::hypot(a, b);
    phi = std::atan2(b, a);
  } else {  // uniform on the spherical cap of half-angle angle_max
    const double c = 1.0 - r.uniform() * (1.0 - std::cos(*s.angle_max));
    theta = std::acos(c);
    phi = 2.0 * M_PI * r.uniform();
  }
  const Eigen::Vector3d v = std::cos(theta) * n + std::sin(theta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
  const std::string bad = set_value(t, d.sc, Eigen::Vector3d(v.normalized()));
  if (bad.empty()) d.drawn.push_back(theta * kRadToDeg);
  return bad;
}

std::string draw_attitude(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const Eigen::Vector3d sigma = std::get<Eigen::Vector3d>(t.nominal.value);
  const Eigen::Vector3d phi = rotation_vector(r, s);
  const Eigen::Matrix3d C = sim::rotation_from_vector(phi) * sim::dcm_BN_from_sigma(sigma);
  const std::string bad = set_value(t, d.sc, sim::sigma_from_quaternion(sim::quaternion_from_dcm(C)));
  if (bad.empty()) d.drawn.push_back(phi.norm() * kRadToDeg);
  return bad;
}

// The drawn values stay even when the key refuses the inertia (the table
// shows what broke it).
std::string draw_inertia(const DispersionSpec& s, const McTarget& t, McStream& r, McDraw& d)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(std::get<Eigen::Matrix3d>(t.nominal.value));
  Eigen::Vector3d lam = es.eigenvalues();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (s.principal_std_rel > 0.0)
    for (int c = 0; c < 3; ++c) scale(c) = 1.0 + s.principal_std_rel * r.normal();
  lam = lam.cwiseProduct(scale);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double angle = 0.0;
  if (s.angle_std) {
    const Eigen::Vector3d phi = *s.angle_std * Eigen::Vector3d(r.normal(), r.normal(), r.normal());
    R = sim::rotation_from_vector(phi);
    angle = phi.norm();
  }
  const Eigen::Matrix3d V = R * es.eigenvectors();
  Eigen::Matrix3d Ip = V * lam.asDiagonal() * V.transpose();
  Ip = 0.5 * (Ip + Ip.transpose()).eval();
  d.drawn.push_back(angle * kRadToDeg);
  if (s.principal_std_rel > 0.0)
    for (int c = 0; c < 3; ++c) d.drawn.push_back(scale(c));
  return set_value(t, d.sc, Ip);
}

std::string draw_target(const DispersionSpec& s, const McTarget& t, uint64_t master, uint64_t run, McDraw& d)
{
  if (!t.error.empty()) return t.error;
  McStream r(master, run, t.name);
  try {
    switch (s.dist) {
      case DistKind::Normal: return set_number(t, d, s.mean.value_or(as_double(t.nominal)) + s.std * r.normal());
      case DistKind::TruncatedNormal: return draw_truncated_normal(s, t, r, d);
      case DistKind::Uniform: return draw_uniform(s, t, r, d);
      case DistKind::Choice: return draw_choice(s, t, r, d);
      case DistKind::NormalVector: return draw_normal_vector(s, t, r, d);
      case DistKind::UnitVector: return draw_unit_vector(s, t, r, d);
      case DistKind::Attitude: return draw_attitude(s, t, r, d);
      case DistKind::Inertia: return draw_inertia(s, t, r, d);
    }
  } catch (const ScenarioError& e) {
    return e.issues().front().message;
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

void check_drawn_scenario(McDraw& d, bool plant_and_fsw)
{
  try {
    const std::string src = d.sc.source_file;
    d.sc = reload_canonical_scenario(d.sc, "(drawn scenario)");
    d.sc.source_file = src;
    if (plant_and_fsw) check_run_configuration(d.sc);
  } catch (const ScenarioError& e) {
    const ScenarioIssue& is = e.issues().front();
    d.invalid = is.key + ": " + is.message;
  }
}

McDraw draw_run(const Scenario& nominal, const McBinding& bound, uint64_t master, uint64_t run, bool check)
{
  McDraw d;
  d.sc = nominal;
  d.sc.monte_carlo.reset();
  d.sc.seed = mc_run_seed(master, run);
  for (const McTarget& t : bound.targets) {
    const std::string bad = draw_target(bound.specs[t.dispersion], t, master, run, d);
    if (!bad.empty()) {  // the remaining columns are not drawn
      d.invalid = t.name + ": " + bad;
      d.drawn.resize(bound.columns.size(), std::nan(""));
      return d;
    }
  }
  if (check) check_drawn_scenario(d);
  return d;
}

McDraw draw_run(const Scenario& nominal, uint64_t master, uint64_t run, bool check)
{
  return draw_run(nominal, bind_dispersions(nominal), master, run, check);
}

}  // namespace harness
