// kestrel.fsw: the generic part of the FSW bindings (docs/python.md, "Flight
// algorithms").  A C struct is described by a table of Field: name, element
// kind, shape and where it lives; one template binds any module of the
// fsw_c shape (config/state/in/out, check/init/reset/update) from its tables,
// and nest() reuses a module's config table inside fsw_acs's config.
#ifndef KESTREL_PYTHON_FSW_FIELD_H
#define KESTREL_PYTHON_FSW_FIELD_H

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common.h"

#include "fsw/att_track.h"
#include "fsw/bdot.h"
#include "fsw/css_sun.h"
#include "fsw/fsw_acs.h"
#include "fsw/rw_null_regen.h"
#include "fsw/thr_pulse_round.h"

namespace kpy {

enum class Kind { Real, Int, U8, U32, U64 };

// One field of a C struct T: a scalar (rows = 0), a vector (rows, cols = 0)
// or a matrix (rows x cols).  `capacity`: a vector/matrix sized by a
// capacity (FSW_MAX_RW): Python may give fewer rows, the rest is zero.
// `count_max` > 0: a count (0..count_max) that sizes the module's state: it
// cannot change while the module holds an initialised state.
template <class T>
struct Field {
  std::string name;
  Kind kind;
  int rows, cols;
  bool capacity;
  std::function<void*(T&)> at;
  const char* doc;
  int count_max = 0;
};

#define KPY_AT(T, expr) [](T& s) -> void* { return &s.expr; }
#define KPY_SCALAR_AS(T, name, kind, expr, doc) \
  Field<T> { name, kind, 0, 0, false, KPY_AT(T, expr), doc }
#define KPY_SCALAR(T, kind, expr, doc) KPY_SCALAR_AS(T, #expr, kind, expr, doc)
#define KPY_COUNT_AS(T, name, expr, max, doc) \
  Field<T> { name, Kind::Int, 0, 0, false, KPY_AT(T, expr), doc, max }
#define KPY_COUNT(T, expr, max, doc) KPY_COUNT_AS(T, #expr, expr, max, doc)
#define KPY_VEC_K(T, name, kind, expr, n, cap, doc) \
  Field<T> { name, kind, n, 0, cap, KPY_AT(T, expr[0]), doc }
#define KPY_VEC(T, kind, expr, n, cap, doc) KPY_VEC_K(T, #expr, kind, expr, n, cap, doc)
// a real vector of a nested struct, named by its last part (guid.sigma_BR -> sigma_BR)
#define KPY_VEC_AS(T, name, expr, n, doc) KPY_VEC_K(T, name, Kind::Real, expr, n, false, doc)
#define KPY_MAT_AS(T, name, expr, r, c, cap, doc) \
  Field<T> { name, Kind::Real, r, c, cap, KPY_AT(T, expr[0][0]), doc }
#define KPY_MAT(T, expr, r, c, cap, doc) KPY_MAT_AS(T, #expr, expr, r, c, cap, doc)
#define RW_CAP FSW_MAX_RW
#define THR_CAP FSW_MAX_THR
// fields many modules share
#define KPY_RW_AXES(T) KPY_MAT(T, gs_hat_B, RW_CAP, 3, true, "(num_rw, 3) spin axes")
#define KPY_RW_VEC(T, expr, doc) KPY_VEC(T, Kind::Real, expr, RW_CAP, true, doc)
#define KPY_RW_MASK(T, expr) KPY_VEC(T, Kind::U8, expr, RW_CAP, true, "(num_rw) 0 available, 1 unavailable")
#define KPY_RW_SPEEDS(T) KPY_RW_VEC(T, Omega, "[rad/s] (num_rw) wheel speeds")
// a module's check, init, reset and update
#define KPY_FNS(mod) fsw_##mod##_check, fsw_##mod##_init, fsw_##mod##_reset, fsw_##mod##_update

static_assert(sizeof(FswStatus) == sizeof(int) && sizeof(FswCssSunMode) == sizeof(int),
              "C enums read as int (Kind::Int)");

// The fields of `in`, as fields of O under `prefix.` (fsw_acs's module configs).
template <class O, class I>
std::vector<Field<O>> nest(const std::string& prefix, I O::*member, const std::vector<Field<I>>& in)
{
  std::vector<Field<O>> out;
  for (const Field<I>& f : in) {
    auto at = f.at;
    out.push_back(Field<O>{prefix + "." + f.name, f.kind, f.rows, f.cols, f.capacity,
                           [at, member](O& o) -> void* { return at(o.*member); }, f.doc, f.count_max});
  }
  return out;
}

template <class O>
void append(std::vector<Field<O>>& to, const std::vector<Field<O>>& more)
{
  to.insert(to.end(), more.begin(), more.end());
}

// ---- element access (fsw_field.cpp) -----------------------------------------
size_t kind_bytes(Kind k);
double element(const void* p, Kind k, size_t i);
// a Python number into one element (ints range-checked; reals any float, NaN included)
void put(void* p, Kind k, size_t i, const py::handle& h, const std::string& name);
py::object get_raw(const void* p, Kind k, int rows, int cols);
// a Python value of the field's shape into p (all or nothing)
void set_raw(void* p, Kind k, int rows, int cols, bool capacity, const py::handle& h, const std::string& name);

// The status as kestrel.fsw.Status (an IntEnum).
py::object status_obj(int s);
// Raise kestrel.fsw.ConfigError (a ValueError) with .status and .field.
[[noreturn]] void raise_config_error(const std::string& who, int status, const std::string& field,
                                     const std::string& how);

template <class T>
size_t field_bytes(const Field<T>& f)
{
  return static_cast<size_t>(f.rows == 0 ? 1 : f.rows) * static_cast<size_t>(f.cols == 0 ? 1 : f.cols) *
         kind_bytes(f.kind);
}

template <class T>
py::object get_field(T& s, const Field<T>& f)
{
  return get_raw(f.at(s), f.kind, f.rows, f.cols);
}

template <class T>
void set_field(T& s, const Field<T>& f, const py::handle& h)
{
  set_raw(f.at(s), f.kind, f.rows, f.cols, f.capacity, h, f.name);
}

template <class T>
py::dict to_dict(T& s, const std::vector<Field<T>>& fs)
{
  py::dict d;
  for (const Field<T>& f : fs) d[py::str(f.name)] = get_field(s, f);
  return d;
}

template <class T>
const Field<T>* find_field(const std::vector<Field<T>>& fs, const std::string& k)
{
  for (const Field<T>& f : fs)
    if (k == f.name) return &f;
  return nullptr;
}

template <class T>
std::string field_names(const std::vector<Field<T>>& fs)
{
  std::string names;
  for (const Field<T>& f : fs) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

// A struct T from keyword arguments (absent fields zero); `what` names them
// in the error ("input", "command", "config field").
template <class T>
void from_kwargs(T& s, const std::vector<Field<T>>& fs, const py::dict& kw, const char* what)
{
  for (auto kv : kw) {
    const std::string k = py::str(kv.first);
    const Field<T>* f = find_field(fs, k);
    if (f == nullptr) throw py::type_error(std::string("unknown ") + what + " '" + k + "' (" + field_names(fs) + ")");
    set_field(s, *f, kv.second);
  }
}

// The config fields whose value differs between two configs ("" when none).
template <class Cfg>
std::string changed_fields(Cfg& now, Cfg& then, const std::vector<Field<Cfg>>& fs)
{
  std::string names;
  for (const Field<Cfg>& f : fs)
    if (std::memcmp(f.at(now), f.at(then), field_bytes(f)) != 0) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

// Set field f of `cfg` to h; a count refuses a new value while `frozen`
// (the module's state was sized by it).
template <class Cfg>
void set_config(Cfg& cfg, const Field<Cfg>& f, const py::handle& h, bool frozen, const char* cls)
{
  Cfg next = cfg;
  set_field(next, f, h);
  if (frozen && f.count_max > 0 && std::memcmp(f.at(next), f.at(cfg), field_bytes(f)) != 0)
    throw py::value_error(std::string(cls) + "." + f.name +
                          ": a count, fixed after init() (the module's state is sized by it); "
                          "make a new " + cls + " for another count");
  std::memcpy(f.at(cfg), f.at(next), field_bytes(f));
}

// The config field a module's check rejects, when the C check does not say:
// a count beyond its capacity, a non-finite real, else the one field that
// makes check pass when it is given back its last accepted value (`good`,
// may be null) or, for reals, its magnitude (a sign error).  "" when none
// of these isolates it.
template <class Cfg>
std::string find_bad_field(const Cfg& cfg, const std::vector<Field<Cfg>>& fs, FswStatus (*check)(const Cfg*),
                           const Cfg* good)
{
  Cfg c = cfg;
  for (const Field<Cfg>& f : fs) {
    if (f.count_max > 0) {
      const int v = *static_cast<const int*>(f.at(c));
      if (v < 0 || v > f.count_max) return f.name;
    }
  }
  for (const Field<Cfg>& f : fs) {
    if (f.kind != Kind::Real) continue;
    const size_t n = field_bytes(f) / sizeof(fsw_real);
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(element(f.at(c), f.kind, i))) return f.name;
  }
  for (const Field<Cfg>& f : fs) {
    if (good != nullptr) {
      Cfg t = cfg;
      Cfg g = *good;
      std::memcpy(f.at(t), f.at(g), field_bytes(f));
      if (check(&t) == FSW_OK) return f.name;
    }
    if (f.kind == Kind::Real) {
      Cfg t = cfg;
      fsw_real* p = static_cast<fsw_real*>(f.at(t));
      for (size_t i = 0; i < field_bytes(f) / sizeof(fsw_real); ++i) p[i] = std::fabs(p[i]);
      if (check(&t) == FSW_OK) return f.name;
    }
  }
  return "";
}

// ---- the config tables of every module (fsw_py.cpp), for fsw_acs ----------
std::vector<Field<FswMrpFbConfig>> mrp_fb_config();
std::vector<Field<FswRwMapConfig>> rw_map_config();
std::vector<Field<FswRwSatConfig>> rw_sat_config();
std::vector<Field<FswTrqLpfConfig>> trq_lpf_config();
std::vector<Field<FswAttTrackConfig>> att_track_config();
std::vector<Field<FswBdotConfig>> bdot_config();
std::vector<Field<FswCssSunConfig>> css_sun_config();
std::vector<Field<FswGuidInertialConfig>> guid_inertial_config();
std::vector<Field<FswGuidOrbitConfig>> guid_orbit_config();
std::vector<Field<FswGuidSunsafeConfig>> guid_sunsafe_config();
std::vector<Field<FswMtqDesatConfig>> mtq_desat_config();
std::vector<Field<FswMtqMapConfig>> mtq_map_config();
std::vector<Field<FswRwBiasConfig>> rw_bias_config();
std::vector<Field<FswRwNullConfig>> rw_null_config();
std::vector<Field<FswRwSpeedFilterConfig>> rw_speed_filter_config();
std::vector<Field<FswRwVoltConfig>> rw_volt_config();
std::vector<Field<FswThrMapConfig>> thr_map_config();
std::vector<Field<FswThrMomentumConfig>> thr_momentum_config();
std::vector<Field<FswThrPulseRemConfig>> thr_pulse_rem_config();
std::vector<Field<FswThrPulseSchmittConfig>> thr_pulse_schmitt_config();
std::vector<Field<FswThrPulseRoundConfig>> thr_pulse_round_config();
// fsw_acs's messages (fsw_acs_py.cpp): kestrel.fsw.Acs and the Python FSW in the loop
std::vector<Field<FswAcsSensorMsg>> sensor_fields();
std::vector<Field<FswAcsCmdMsg>> cmd_fields();
std::vector<Field<FswAcsActuatorMsg>> actuator_fields();
std::vector<Field<FswRwNullRegenConfig>> rw_null_regen_config();

void bind_fsw_acs(py::module_& m);

}  // namespace kpy

#endif
