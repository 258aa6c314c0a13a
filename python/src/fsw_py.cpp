// kestrel.fsw: thin bindings of single FSW algorithms (fsw_c).  One generic
// wrapper: an algorithm's config fields are attributes (NumPy for arrays),
// check()/init()/reset() return the FswStatus, update(**inputs) returns
// (status, outputs dict).  Each binding is a table of the C structs' fields.
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "common.h"

#include "fsw/att_track.h"
#include "fsw/fsw_status.h"
#include "fsw/mrp_fb.h"
#include "fsw/rw_map.h"
#include "fsw/rw_sat.h"
#include "fsw/trq_lpf.h"

namespace kpy {

namespace {

enum class Kind { Real, Int, U8, U64 };

// One field of a C struct T: a scalar (rows = 0), a vector (rows, cols = 0)
// or a matrix (rows x cols).  `capacity`: a vector/matrix sized by a
// capacity (FSW_MAX_RW): Python may give fewer rows, the rest is zero.
template <class T>
struct Field {
  const char* name;
  Kind kind;
  int rows, cols;
  bool capacity;
  std::function<void*(T&)> at;
  const char* doc;
};

#define KPY_SCALAR(T, kind, expr, doc) \
  Field<T> { #expr, kind, 0, 0, false, [](T& s) -> void* { return &s.expr; }, doc }
#define KPY_VEC(T, kind, expr, n, cap, doc) \
  Field<T> { #expr, kind, n, 0, cap, [](T& s) -> void* { return &s.expr[0]; }, doc }
#define KPY_MAT(T, expr, r, c, cap, doc) \
  Field<T> { #expr, Kind::Real, r, c, cap, [](T& s) -> void* { return &s.expr[0][0]; }, doc }
// a field of a nested struct, named by its last part (guid.sigma_BR -> sigma_BR)
#define KPY_VEC_AS(T, name, expr, n, doc) \
  Field<T> { name, Kind::Real, n, 0, false, [](T& s) -> void* { return &s.expr[0]; }, doc }

double element(const void* p, Kind k, size_t i)
{
  switch (k) {
    case Kind::Real: return static_cast<double>(static_cast<const fsw_real*>(p)[i]);
    case Kind::Int: return static_cast<double>(static_cast<const int*>(p)[i]);
    case Kind::U8: return static_cast<double>(static_cast<const uint8_t*>(p)[i]);
    case Kind::U64: return static_cast<double>(static_cast<const uint64_t*>(p)[i]);
  }
  return 0.0;
}

// a Python number into one element (ints range-checked; reals any float, NaN included)
void put(void* p, Kind k, size_t i, const py::handle& h, const char* name)
{
  if (k == Kind::Real) {
    static_cast<fsw_real*>(p)[i] = static_cast<fsw_real>(py::float_(py::reinterpret_borrow<py::object>(h)).cast<double>());
    return;
  }
  py::object o = py::reinterpret_borrow<py::object>(h);
  if (py::isinstance<py::float_>(o)) {
    const double d = o.cast<double>();
    if (!(std::isfinite(d) && d == std::floor(d))) throw py::value_error(std::string(name) + ": an integer");
    o = py::int_(o);
  }
  if (k == Kind::U64) {
    const py::int_ n(o);
    if (n < py::int_(0)) throw py::value_error(std::string(name) + ": >= 0");
    const unsigned long long u = PyLong_AsUnsignedLongLong(n.ptr());
    if (PyErr_Occurred()) {
      PyErr_Clear();
      throw py::value_error(std::string(name) + ": out of the range of uint64");
    }
    static_cast<uint64_t*>(p)[i] = static_cast<uint64_t>(u);
    return;
  }
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(py::int_(o).ptr(), &overflow);
  if (overflow != 0) throw py::value_error(std::string(name) + ": out of range");
  if (k == Kind::Int) {
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      throw py::value_error(std::string(name) + ": out of the range of a C int");
    static_cast<int*>(p)[i] = static_cast<int>(v);
  } else {
    if (v < 0 || v > 255) throw py::value_error(std::string(name) + ": 0..255");
    static_cast<uint8_t*>(p)[i] = static_cast<uint8_t>(v);
  }
}

template <class T>
py::object get_field(T& s, const Field<T>& f)
{
  const void* p = f.at(s);
  if (f.rows == 0) {
    if (f.kind == Kind::Real) return py::float_(element(p, f.kind, 0));
    if (f.kind == Kind::U64) return py::int_(static_cast<unsigned long long>(*static_cast<const uint64_t*>(p)));
    return py::int_(static_cast<long long>(element(p, f.kind, 0)));
  }
  if (f.cols == 0) {
    py::array_t<double> a(f.rows);
    for (int i = 0; i < f.rows; ++i) a.mutable_at(i) = element(p, f.kind, static_cast<size_t>(i));
    return std::move(a);
  }
  py::array_t<double> a({f.rows, f.cols});
  for (int i = 0; i < f.rows; ++i)
    for (int j = 0; j < f.cols; ++j) a.mutable_at(i, j) = element(p, f.kind, static_cast<size_t>(i * f.cols + j));
  return std::move(a);
}

// bytes of a field's storage (every row of a capacity-sized array)
template <class T>
size_t field_bytes(const Field<T>& f)
{
  const size_t elem = f.kind == Kind::Real ? sizeof(fsw_real)
                      : f.kind == Kind::Int ? sizeof(int)
                      : f.kind == Kind::U64 ? sizeof(uint64_t)
                                            : 1;
  const size_t rows = static_cast<size_t>(f.rows == 0 ? 1 : f.rows);
  return rows * static_cast<size_t>(f.cols == 0 ? 1 : f.cols) * elem;
}

template <class T>
void set_field(T& s, const Field<T>& f, const py::handle& h)
{
  void* p = f.at(s);
  if (f.rows == 0) {
    if (!(py::isinstance<py::int_>(h) || py::isinstance<py::float_>(h) ||
          py::isinstance(h, py::module_::import("numpy").attr("number"))))
      throw py::type_error(std::string(f.name) + ": a number");
    put(p, f.kind, 0, h, f.name);
    return;
  }
  if (py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h) || h.is_none())
    throw py::type_error(std::string(f.name) + ": an array");
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
    throw py::type_error(std::string(f.name) + ": an array of numbers");
  }
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(f.name) + ": an array of numbers");
  }
  const int want_nd = f.cols == 0 ? 1 : 2;
  const std::string shape = f.cols == 0 ? "(" + std::to_string(f.rows) + ",)"
                                        : "(" + std::to_string(f.rows) + ", " + std::to_string(f.cols) + ")";
  const bool rows_ok = a.ndim() == want_nd && (f.capacity ? a.shape(0) <= f.rows : a.shape(0) == f.rows);
  const bool cols_ok = want_nd == 1 || (a.ndim() == 2 && a.shape(1) == f.cols);
  if (!rows_ok || !cols_ok)
    throw py::value_error(std::string(f.name) + ": shape " + shape + (f.capacity ? " (at most that many rows)" : ""));
  const size_t width = static_cast<size_t>(f.cols == 0 ? 1 : f.cols);
  const size_t n = static_cast<size_t>(a.shape(0)) * width;
  const size_t total = static_cast<size_t>(f.rows) * width;
  // checked first, written after: a bad element leaves the field unchanged
  std::vector<unsigned char> backup(field_bytes(f));
  std::memcpy(backup.data(), p, backup.size());
  try {
    const double* d = a.data();
    for (size_t i = 0; i < total; ++i) put(p, f.kind, i, py::float_(i < n ? d[i] : 0.0), f.name);
  } catch (...) {
    std::memcpy(p, backup.data(), backup.size());
    throw;
  }
}

template <class T>
py::dict to_dict(T& s, const std::vector<Field<T>>& fs)
{
  py::dict d;
  for (const Field<T>& f : fs) d[f.name] = get_field(s, f);
  return d;
}

template <class Cfg, class St, class In, class Out>
struct Algorithm {
  Cfg cfg{};
  St st{};
  // The configuration the last successful init() checked: the C update
  // trusts its config (counts index fixed arrays), so update() refuses to
  // run on a configuration changed since (issue 39: num_rw = 100000 after
  // init() wrote far past the arrays).
  Cfg init_cfg{};
  bool inited = false;
};

// The config fields whose value differs from the one init() checked ("" when none).
template <class Cfg>
std::string changed_fields(Cfg& now, Cfg& then, const std::vector<Field<Cfg>>& fs)
{
  std::string names;
  for (const Field<Cfg>& f : fs)
    if (std::memcmp(f.at(now), f.at(then), field_bytes(f)) != 0) names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

template <class Cfg, class St, class In, class Out>
void bind_algorithm(py::module_& m, const char* name, const char* doc, FswStatus (*check)(const Cfg*),
                    FswStatus (*init)(St*, const Cfg*), void (*reset)(St*),
                    FswStatus (*update)(St*, const Cfg*, const In*, Out*), std::vector<Field<Cfg>> cfg_fields,
                    std::vector<Field<In>> in_fields, std::vector<Field<Out>> out_fields,
                    std::vector<Field<St>> state_fields)
{
  using A = Algorithm<Cfg, St, In, Out>;
  auto cls = py::class_<A>(m, name, doc);
  auto cf = std::make_shared<std::vector<Field<Cfg>>>(std::move(cfg_fields));
  auto inf = std::make_shared<std::vector<Field<In>>>(std::move(in_fields));
  auto outf = std::make_shared<std::vector<Field<Out>>>(std::move(out_fields));
  auto stf = std::make_shared<std::vector<Field<St>>>(std::move(state_fields));
  cls.def(py::init([cf](const py::kwargs& kw) {
            auto a = std::make_unique<A>();
            for (auto kv : kw) {
              const std::string k = py::str(kv.first);
              bool found = false;
              for (const Field<Cfg>& f : *cf)
                if (k == f.name) {
                  set_field(a->cfg, f, kv.second);
                  found = true;
                }
              if (!found) throw py::type_error(std::string("unknown config field '") + k + "'");
            }
            return a;
          }),
          "A zeroed configuration; keyword arguments set config fields.");
  for (size_t i = 0; i < cf->size(); ++i) {
    const Field<Cfg>* f = &(*cf)[i];
    cls.def_property(
        f->name, [cf, f](A& a) { return get_field(a.cfg, *f); },
        [cf, f](A& a, const py::handle& v) { set_field(a.cfg, *f, v); }, f->doc);
  }
  cls.def("check", [check](A& a) { return static_cast<int>(check(&a.cfg)); },
          "fsw_*_check on the configuration: the FswStatus (kestrel.fsw.OK = 0)")
      .def(
          "init",
          [init](A& a) {
            const FswStatus s = init(&a.st, &a.cfg);
            a.inited = s == FSW_OK;
            if (a.inited) a.init_cfg = a.cfg;
            return static_cast<int>(s);
          },
          "check, then a fresh state (the configuration update() runs with; change it, then init() again)")
      .def("reset", [reset](A& a) { reset(&a.st); })
      .def(
          "update",
          [name, update, cf, inf, outf](A& a, const py::kwargs& kw) {
            if (a.inited) {
              const std::string changed = changed_fields(a.cfg, a.init_cfg, *cf);
              if (!changed.empty())
                throw py::value_error(std::string(name) + ".update: the configuration changed after init() (" +
                                      changed + "): call init() again (it checks the new one)");
            }
            In in{};
            for (auto kv : kw) {
              const std::string k = py::str(kv.first);
              bool found = false;
              for (const Field<In>& f : *inf)
                if (k == f.name) {
                  set_field(in, f, kv.second);
                  found = true;
                }
              if (!found) {
                std::string names;
                for (const Field<In>& f : *inf) names += std::string(names.empty() ? "" : ", ") + f.name;
                throw py::type_error("unknown input '" + k + "' (inputs: " + names + ")");
              }
            }
            Out out{};
            const FswStatus s = update(&a.st, &a.cfg, &in, &out);
            return py::make_tuple(static_cast<int>(s), to_dict(out, *outf));
          },
          "One update with the inputs given by keyword (absent inputs are zero); returns (status, outputs dict "
          "of NumPy arrays).  Before a successful init() the status is E_NOT_INIT; after a configuration change "
          "ValueError naming the changed fields until init() again.")
      .def_property_readonly("config", [cf](A& a) { return to_dict(a.cfg, *cf); }, "every config field, as a dict")
      .def_property_readonly("state", [stf](A& a) { return to_dict(a.st, *stf); }, "the state's fields, as a dict")
      .def_property_readonly_static("inputs", [inf](const py::object&) {
        std::vector<std::string> v;
        for (const auto& f : *inf) v.push_back(f.name);
        return v;
      })
      .def_property_readonly_static("outputs", [outf](const py::object&) {
        std::vector<std::string> v;
        for (const auto& f : *outf) v.push_back(f.name);
        return v;
      });
}

}  // namespace

void bind_fsw(py::module_& m)
{
  m.attr("MAX_RW") = FSW_MAX_RW;
  m.attr("REAL_IS_FLOAT") = static_cast<bool>(FSW_USE_FLOAT);
  const std::pair<const char*, FswStatus> codes[] = {
      {"OK", FSW_OK},           {"W_SINGULAR", FSW_W_SINGULAR},   {"W_SAT", FSW_W_SAT},
      {"W_RATE", FSW_W_RATE},   {"E_NULL_ARG", FSW_E_NULL_ARG},   {"E_CONFIG", FSW_E_CONFIG},
      {"E_CAPACITY", FSW_E_CAPACITY}, {"E_SINGULAR", FSW_E_SINGULAR}, {"E_BAD_INPUT", FSW_E_BAD_INPUT},
      {"E_TIME", FSW_E_TIME},   {"E_UNSUPPORTED", FSW_E_UNSUPPORTED}, {"E_NOT_INIT", FSW_E_NOT_INIT}};
  for (const auto& c : codes) m.attr(c.first) = static_cast<int>(c.second);
  m.def("status_name", [](int s) { return std::string(fsw_status_name(static_cast<FswStatus>(s))); },
        "'FSW_OK', 'FSW_E_CONFIG', ...");

  using MC = FswMrpFbConfig;
  using MI = FswMrpFbIn;
  using MO = FswMrpFbOut;
  using MS = FswMrpFbState;
  bind_algorithm<MC, MS, MI, MO>(
      m, "MrpFb", "MRP feedback control law (fsw_c/include/fsw/mrp_fb.h, docs/fsw/mrp_fb.md)", fsw_mrp_fb_check,
      fsw_mrp_fb_init, fsw_mrp_fb_reset, fsw_mrp_fb_update,
      {KPY_SCALAR(MC, Kind::Real, K, "[N*m] attitude gain"), KPY_SCALAR(MC, Kind::Real, P, "[N*m*s] rate gain"),
       KPY_SCALAR(MC, Kind::Real, K_i, "[1/(kg*m^2)] integral gain; <= 0 disables"),
       KPY_SCALAR(MC, Kind::Real, integral_limit, "[N*m*s] per-component bound on int_sigma"),
       KPY_SCALAR(MC, Kind::Int, control_law_type, "0 or 1"),
       KPY_VEC(MC, Kind::Real, known_torque_B, 3, false, "[N*m] known external torque"),
       KPY_MAT(MC, I_B, 3, 3, false, "[kg*m^2] inertia about the CoM, B"),
       KPY_SCALAR(MC, Kind::Int, num_rw, "wheels in H, 0..MAX_RW"),
       KPY_MAT(MC, gs_hat_B, FSW_MAX_RW, 3, true, "(num_rw, 3) spin axes"),
       KPY_VEC(MC, Kind::Real, J_s, FSW_MAX_RW, true, "[kg*m^2] (num_rw) wheel spin inertias")},
      {KPY_SCALAR(MI, Kind::U64, t_ns, "[ns]"), KPY_VEC_AS(MI, "sigma_BR", guid.sigma_BR, 3, "[-]"),
       KPY_VEC_AS(MI, "omega_BR_B", guid.omega_BR_B, 3, "[rad/s]"),
       KPY_VEC_AS(MI, "omega_RN_B", guid.omega_RN_B, 3, "[rad/s]"),
       KPY_VEC_AS(MI, "omega_dot_RN_B", guid.omega_dot_RN_B, 3, "[rad/s^2]"),
       KPY_VEC(MI, Kind::Real, Omega, FSW_MAX_RW, true, "[rad/s] (num_rw) wheel speeds"),
       KPY_VEC(MI, Kind::U8, rw_avail, FSW_MAX_RW, true, "(num_rw) 0 available, 1 unavailable")},
      {KPY_VEC(MO, Kind::Real, torque_B, 3, false, "[N*m] Lr"),
       KPY_VEC(MO, Kind::Real, int_torque_B, 3, false, "[N*m] integral part")},
      {KPY_SCALAR(MS, Kind::Int, ready, ""), KPY_VEC(MS, Kind::Real, int_sigma, 3, false, "[N*m*s]")});

  using RC = FswRwMapConfig;
  using RI = FswRwMapIn;
  using RO = FswRwMapOut;
  using RS = FswRwMapState;
  bind_algorithm<RC, RS, RI, RO>(
      m, "RwMap", "Reaction-wheel torque mapping (fsw_c/include/fsw/rw_map.h, docs/fsw/rw_map.md)",
      fsw_rw_map_check, fsw_rw_map_init, fsw_rw_map_reset, fsw_rw_map_update,
      {KPY_SCALAR(RC, Kind::Int, num_rw, "1..MAX_RW"), KPY_MAT(RC, gs_hat_B, FSW_MAX_RW, 3, true, "(num_rw, 3) spin axes"),
       KPY_SCALAR(RC, Kind::Int, num_axes, "controlled axes 0..3"),
       KPY_MAT(RC, ctrl_axes_B, 3, 3, true, "(num_axes, 3) control axes, rows"),
       KPY_SCALAR(RC, Kind::Int, mode, "0 min-norm, 1 power"), KPY_SCALAR(RC, Kind::Real, eps_P, "[rad^2/s^2] power mode")},
      {KPY_VEC(RI, Kind::Real, Lr_B, 3, false, "[N*m] torque the wheels must apply to the body"),
       KPY_VEC(RI, Kind::Real, Omega, FSW_MAX_RW, true, "[rad/s] (num_rw) wheel speeds"),
       KPY_VEC(RI, Kind::U8, avail, FSW_MAX_RW, true, "(num_rw) 0 available, 1 unavailable")},
      {KPY_VEC(RO, Kind::Real, u_s, FSW_MAX_RW, true, "[N*m] motor torques (MAX_RW; 0 beyond num_rw)")},
      {KPY_SCALAR(RS, Kind::Int, ready, "")});

  using SC = FswRwSatConfig;
  using SI = FswRwSatIn;
  using SO = FswRwSatOut;
  using SS = FswRwSatState;
  bind_algorithm<SC, SS, SI, SO>(
      m, "RwSat", "Reaction-wheel torque saturation (fsw_c/include/fsw/rw_sat.h)", fsw_rw_sat_check,
      fsw_rw_sat_init, fsw_rw_sat_reset, fsw_rw_sat_update,
      {KPY_SCALAR(SC, Kind::Int, num_rw, "1..MAX_RW"),
       KPY_VEC(SC, Kind::Real, u_max, FSW_MAX_RW, true, "[N*m] (num_rw) torque limits"),
       KPY_SCALAR(SC, Kind::Int, mode, "0 scale, 1 clip")},
      {KPY_VEC(SI, Kind::Real, u_s, FSW_MAX_RW, true, "[N*m] (num_rw) commanded torques"),
       KPY_VEC(SI, Kind::U8, avail, FSW_MAX_RW, true, "(num_rw) 0 available, 1 unavailable")},
      {KPY_VEC(SO, Kind::Real, u_s, FSW_MAX_RW, true, "[N*m] limited torques")}, {KPY_SCALAR(SS, Kind::Int, ready, "")});

  using LC = FswTrqLpfConfig;
  using LI = FswTrqLpfIn;
  using LO = FswTrqLpfOut;
  using LS = FswTrqLpfState;
  bind_algorithm<LC, LS, LI, LO>(
      m, "TrqLpf", "Control-torque low-pass filter, first-order Tustin (fsw_c/include/fsw/trq_lpf.h, docs/fsw/trq_lpf.md)",
      fsw_trq_lpf_check, fsw_trq_lpf_init, fsw_trq_lpf_reset, fsw_trq_lpf_update,
      {KPY_SCALAR(LC, Kind::Real, h, "[s] assumed call period"), KPY_SCALAR(LC, Kind::Real, omega_c, "[rad/s] cut-off")},
      {KPY_VEC(LI, Kind::Real, Lr_B, 3, false, "[N*m] control torque"), KPY_SCALAR(LI, Kind::U64, t_ns, "[ns]")},
      {KPY_VEC(LO, Kind::Real, LrF_B, 3, false, "[N*m] filtered torque")},
      {KPY_SCALAR(LS, Kind::Int, ready, ""), KPY_VEC(LS, Kind::Real, Lr_prev, 3, false, "[N*m]"),
       KPY_VEC(LS, Kind::Real, LrF_prev, 3, false, "[N*m]")});

  using TC = FswAttTrackConfig;
  using TI = FswAttTrackIn;
  using TO = FswAttTrackOut;
  using TS = FswAttTrackState;
  bind_algorithm<TC, TS, TI, TO>(
      m, "AttTrack", "Attitude tracking error (fsw_c/include/fsw/att_track.h, docs/fsw/att_track.md)",
      fsw_att_track_check, fsw_att_track_init, fsw_att_track_reset, fsw_att_track_update,
      {KPY_VEC(TC, Kind::Real, sigma_R0R, 3, false, "[-] nominal reference rel. the corrected one")},
      {KPY_VEC(TI, Kind::Real, sigma_BN, 3, false, "[-]"), KPY_VEC(TI, Kind::Real, omega_BN_B, 3, false, "[rad/s]"),
       KPY_VEC_AS(TI, "sigma_RN", ref.sigma_RN, 3, "[-] reference"),
       KPY_VEC_AS(TI, "omega_RN_N", ref.omega_RN_N, 3, "[rad/s]"),
       KPY_VEC_AS(TI, "omega_dot_RN_N", ref.omega_dot_RN_N, 3, "[rad/s^2]")},
      {KPY_VEC(TO, Kind::Real, sigma_BR, 3, false, "[-]"), KPY_VEC(TO, Kind::Real, omega_BR_B, 3, false, "[rad/s]"),
       KPY_VEC(TO, Kind::Real, omega_RN_B, 3, false, "[rad/s]"),
       KPY_VEC(TO, Kind::Real, omega_dot_RN_B, 3, false, "[rad/s^2]")},
      {KPY_SCALAR(TS, Kind::Int, ready, "")});
}

}  // namespace kpy
