// Python in the loop (docs/python.md, "Python in the loop"):
//   PyFsw       a harness::FswEndpoint calling a Python callable once per
//               control period: sensor message (a dict of NumPy arrays and
//               numbers, the fields of kestrel.fsw.Acs.cycle) -> actuator
//               message (a dict of the same fields; absent fields zero)
//   PyEffector  a sim::ForceTorqueEffector calling f(t, state) ->
//               (force_B, torque_B) at the start of a tick (every tick or
//               every rate_hz period) and holding it over the plant's RK4
//               sub-steps until the next call
//   PySensor    a recorded quantity f(t, truth) -> reading (size,) at every
//               recorded row (RunConfig::truth_sources), group "python"
// Both take the GIL for the call (the run steps with it released) and turn a
// Python exception into the run's failure at that tick (FswEndpointError,
// InLoopError), with the traceback in the message.
#include "loop_py.h"

#include <cmath>
#include <limits>

#include "fsw_field.h"
#include "harness/core/fsw_endpoint.h"
#include "harness/core/loop_error.h"
#include "harness/core/loop_messages.h"
#include "sim/effector.h"

namespace kpy {

namespace {

std::string object_name(const py::handle& o)
{
  py::object qn = py::getattr(o, "__qualname__", py::none());
  py::object mod = py::getattr(o, "__module__", py::none());
  if (qn.is_none()) {  // an instance: its class
    qn = py::getattr(py::type::of(o), "__qualname__", py::str("?"));
    mod = py::getattr(py::type::of(o), "__module__", py::none());
  }
  const std::string m = mod.is_none() ? "" : py::str(mod).cast<std::string>() + ".";
  return "python:" + m + py::str(qn).cast<std::string>();
}

// The Python traceback of e as text (what the run's failure message holds).
std::string traceback_text(py::error_already_set& e)
{
  try {
    py::list lines = py::module_::import("traceback").attr("format_exception")(e.type(), e.value(), e.trace());
    std::string s;
    for (const py::handle l : lines) s += py::str(l).cast<std::string>();
    return s;
  } catch (const std::exception&) {
    return e.what();
  }
}

// Runs fn with the GIL; a Python exception or a conversion error becomes
// "" + its text (returned), nothing thrown.
template <class Fn>
std::string call_guarded(Fn&& fn)
{
  try {
    fn();
  } catch (py::error_already_set& e) {
    return traceback_text(e);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

py::array_t<double> vec(const double* p, py::ssize_t n)
{
  py::array_t<double> a(n);
  for (py::ssize_t i = 0; i < n; ++i) a.mutable_data()[i] = p[i];
  return a;
}

// A 3-vector from Python: shape (3,), finite; else the error names `what`.
void vec3_from(const py::handle& h, double* out, const std::string& what)
{
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 1 || a.shape(0) != 3) {
    PyErr_Clear();
    throw py::value_error(what + ": shape (3,) expected");
  }
  for (int i = 0; i < 3; ++i) {
    out[i] = a.data()[i];
    if (!std::isfinite(out[i])) throw py::value_error(what + ": not finite");
  }
}

class PyFsw : public harness::FswEndpoint {
 public:
  PyFsw(py::object f, std::string name, const FswAcsConfig& cfg)
      : f_(std::move(f)), name_(std::move(name)), sf_(sensor_fields()), af_(actuator_fields())
  {
    health0_.mode = cfg.initial_mode;
    health0_.actuation = cfg.initial_actuation;
  }
  ~PyFsw() override
  {
    py::gil_scoped_acquire gil;  // the run may be destroyed with the GIL released
    f_ = py::object();
  }
  std::string describe() const override { return "Python FSW " + name_ + " (in process)"; }
  void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health) override
  {
    py::gil_scoped_acquire gil;
    FswAcsActuatorMsg act{};
    const std::string err = call_guarded([&] {
      FswAcsSensorMsg s = in;
      py::object r = f_(to_dict(s, sf_));
      if (!py::isinstance<py::dict>(r))
        throw py::type_error("returned " + py::str(py::type::of(r).attr("__name__")).cast<std::string>() +
                             ", not a dict of actuator fields (" + field_names(af_) + ")");
      from_kwargs(act, af_, r.cast<py::dict>(), "actuator field");
      check_finite(act);
    });
    if (!err.empty()) throw harness::FswEndpointError("Python FSW " + name_ + ": " + err);
    out = act;
    ++health0_.cycles;
    health = health0_;  // status FSW_OK, the configured mode: the Python FSW reports no health
  }

 private:
  void check_finite(FswAcsActuatorMsg& act) const
  {
    for (const Field<FswAcsActuatorMsg>& f : af_) {
      if (f.kind != Kind::Real) continue;
      const size_t n = field_bytes(f) / kind_bytes(f.kind);
      for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(element(f.at(act), f.kind, i)))
          throw py::value_error("actuator field " + f.name + ": not finite (element " + std::to_string(i) + ")");
    }
  }
  py::object f_;
  std::string name_;
  std::vector<Field<FswAcsSensorMsg>> sf_;
  std::vector<Field<FswAcsActuatorMsg>> af_;
  FswAcsHealthMsg health0_{};
};

class PyEffector : public sim::ForceTorqueEffector {
 public:
  PyEffector(py::object f, std::string name, const sim::Plant& plant, int64_t period_ns)
      : f_(std::move(f)), name_(std::move(name)), plant_(plant), period_ns_(period_ns)
  {
  }
  ~PyEffector() override
  {
    py::gil_scoped_acquire gil;
    f_ = py::object();
  }
  const char* kind() const override { return "python"; }
  void accumulate(const sim::EffectorStage& /*stage*/, sim::EffectorSums& sums) const override
  {
    sums.F_B += F_B_;
    sums.L_B += L_B_;
  }
  // The plant's step starts: a new value when one is due (a plant step
  // split into sub-steps or segments starts here once per tick).
  // A Python object's own state is not the harness's to save: a run with a
  // Python effector is not checkpointed (docs/checkpoint.md)
  void state_io(sim::StateIO& /*io*/) override
  {
    throw std::runtime_error("checkpoint: the Python effector '" + name_ + "' keeps state the harness cannot save");
  }
  void begin_segment(int64_t t0_ns) override
  {
    if (t0_ns < next_ns_) return;
    next_ns_ = t0_ns + period_ns_;
    evaluate(t0_ns);
  }

 private:
  void evaluate(int64_t t_ns)
  {
    py::gil_scoped_acquire gil;
    double F[3], L[3];
    const std::string err = call_guarded([&] {
      py::dict st;
      const Eigen::Vector3d s = plant_.sigma_BN(), w = plant_.omega_BN_B(), r = plant_.r_BN_N(), v = plant_.v_BN_N();
      st["sigma_BN"] = vec(s.data(), 3);
      st["omega_BN_B"] = vec(w.data(), 3);
      st["r_BN_N"] = vec(r.data(), 3);
      st["v_BN_N"] = vec(v.data(), 3);
      std::vector<double> Om;
      for (int i = 0; i < plant_.num_rw(); ++i) Om.push_back(plant_.Omega(i));
      st["Omega"] = vec(Om.data(), static_cast<py::ssize_t>(Om.size()));
      py::object out = f_(static_cast<double>(t_ns) / 1e9, st);
      if (!py::isinstance<py::sequence>(out) || py::len(out) != 2)
        throw py::type_error("returned " + py::str(py::type::of(out).attr("__name__")).cast<std::string>() +
                             ", not (force_B, torque_B)");
      vec3_from(out[py::int_(0)], F, "force_B");
      vec3_from(out[py::int_(1)], L, "torque_B");
    });
    if (!err.empty()) throw harness::InLoopError("Python effector " + name_ + ": " + err);
    F_B_ = Eigen::Vector3d(F[0], F[1], F[2]);
    L_B_ = Eigen::Vector3d(L[0], L[1], L[2]);
  }
  py::object f_;
  std::string name_;
  const sim::Plant& plant_;
  int64_t period_ns_;
  int64_t next_ns_ = std::numeric_limits<int64_t>::min();
  Eigen::Vector3d F_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d L_B_ = Eigen::Vector3d::Zero();
};

// Held by shared_ptr in the recorder's fill function (copied without the GIL).
class PySensor {
 public:
  PySensor(const PyLoop::Sensor& s, int num_rw) : s_(s), num_rw_(num_rw) {}
  ~PySensor()
  {
    py::gil_scoped_acquire gil;
    s_.f = py::object();
  }
  void fill(int64_t t_ns, const harness::TruthMsg& x, double* out)
  {
    py::gil_scoped_acquire gil;
    const std::string err = call_guarded([&] {
      py::dict st;
      st["sigma_BN"] = vec(x.sigma_BN, 3);
      st["omega_BN_B"] = vec(x.omega_BN_B, 3);
      st["r_BN_N"] = vec(x.r_BN_N, 3);
      st["v_BN_N"] = vec(x.v_BN_N, 3);
      st["Omega"] = vec(x.Omega, num_rw_);
      st["m_sc"] = x.m_sc;
      st["field_B"] = vec(x.field_B, 3);
      st["illumination"] = x.illumination;
      py::object r = s_.f(static_cast<double>(t_ns) / 1e9, st);
      py::array_t<double, py::array::c_style | py::array::forcecast> a;
      try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(r);
      } catch (const py::error_already_set&) {
      }
      const bool scalar_ok = s_.size == 1 && a && a.ndim() == 0;
      if (!a || !(scalar_ok || (a.ndim() == 1 && a.shape(0) == s_.size))) {
        PyErr_Clear();
        throw py::value_error("reading: shape (" + std::to_string(s_.size) + ",) expected");
      }
      for (int i = 0; i < s_.size; ++i) {
        out[i] = a.data()[i];
        if (!std::isfinite(out[i])) throw py::value_error("reading: not finite (element " + std::to_string(i) + ")");
      }
    });
    if (!err.empty()) throw harness::InLoopError("Python sensor " + s_.name + " (" + s_.object_name + "): " + err);
  }

 private:
  PyLoop::Sensor s_;
  py::ssize_t num_rw_;
};

// The declared rate_hz of o as a whole number of ticks (1 without one).
uint64_t period_ticks(const py::object& o, const std::string& name, const harness::Scenario& sc, const char* what)
{
  if (!py::hasattr(o, "rate_hz")) return 1;
  const double hz = py::float_(o.attr("rate_hz")).cast<double>();
  const double n = std::round(1.0 / (hz * sc.rates.dt));
  if (!(hz > 0.0) || !std::isfinite(hz) || n < 1.0 || std::fabs(n * sc.rates.dt * hz - 1.0) > 1e-9)
    throw py::value_error(std::string(what) + " " + name + ": rate_hz = " + std::to_string(hz) +
                          " Hz is not a whole number of ticks (rates.dt = " + std::to_string(sc.rates.dt) + " s)");
  return static_cast<uint64_t>(n);
}

}  // namespace

PyLoop loop_from(const py::object& fsw, const py::object& effectors, const py::object& sensors)
{
  PyLoop l;
  l.fsw = fsw;
  if (!fsw.is_none()) {
    if (!PyCallable_Check(fsw.ptr())) throw py::type_error("fsw: a callable f(sensors: dict) -> dict");
    l.fsw_name = object_name(fsw);
  }
  if (!sensors.is_none()) {
    if (!py::isinstance<py::dict>(sensors)) throw py::type_error("sensors: a dict name -> (callable, size)");
    for (auto kv : sensors.cast<py::dict>()) {
      PyLoop::Sensor s;
      s.name = py::str(kv.first).cast<std::string>();
      py::tuple t;
      if (py::isinstance<py::tuple>(kv.second)) t = kv.second.cast<py::tuple>();
      if (t.size() != 2 || !PyCallable_Check(t[0].ptr()) || !py::isinstance<py::int_>(t[1]))
        throw py::type_error("sensors['" + s.name + "']: (f(t, truth: dict) -> reading, size: int)");
      s.f = t[0];
      s.size = t[1].cast<int>();
      if (s.size < 1 || s.size > 64) throw py::value_error("sensors['" + s.name + "']: size in [1, 64]");
      if (s.name.empty() || s.name.find_first_of("/ ") != std::string::npos)
        throw py::value_error("sensors: '" + s.name + "' is not a column name (no '/', no space)");
      s.object_name = object_name(s.f);
      l.sensors.push_back(s);
    }
  }
  if (effectors.is_none()) return l;
  py::list list;
  if (PyCallable_Check(effectors.ptr()))
    list.append(effectors);
  else
    list = py::list(effectors);
  for (const py::handle e : list) {
    if (!PyCallable_Check(e.ptr())) throw py::type_error("effectors: callables f(t, state: dict) -> (force_B, torque_B)");
    l.effectors.push_back(py::reinterpret_borrow<py::object>(e));
    l.effector_names.push_back(object_name(e));
  }
  return l;
}

void install_fsw(const PyLoop& loop, const harness::Scenario& sc, harness::RunConfig& cfg)
{
  if (!loop.has_fsw()) return;
  // it runs at the scenario's FSW rate; a declared rate_hz must be that one
  if (py::hasattr(loop.fsw, "rate_hz") && period_ticks(loop.fsw, loop.fsw_name, sc, "fsw") != sc.rates.fsw_divisor)
    throw py::value_error("fsw " + loop.fsw_name + ": rate_hz is not the scenario's FSW rate " +
                          std::to_string(1.0 / (sc.rates.dt * sc.rates.fsw_divisor)) +
                          " Hz (1 / (rates.dt * rates.fsw_divisor))");
  FswAcsConfig c{};
  try {
    c = harness::fsw_acs_config_of(sc);
  } catch (const harness::ScenarioError& e) {
    throw py::value_error(e.what());
  }
  cfg.fsw = std::make_unique<PyFsw>(loop.fsw, loop.fsw_name, c);
}

void install_sensors(const PyLoop& loop, const harness::Scenario& sc, harness::RunConfig& cfg)
{
  for (const PyLoop::Sensor& s : loop.sensors) {
    harness::Quantity q;
    q.name = s.name;
    q.unit = "-";
    for (int i = 0; i < s.size; ++i) q.columns.push_back(s.size == 1 ? s.name : s.name + "_" + std::to_string(i));
    auto ps = std::make_shared<PySensor>(s, static_cast<int>(sc.wheels.size()));
    cfg.truth_sources.push_back(
        {"python", {q}, [ps](int64_t t_ns, const harness::TruthMsg& x, double* out) { ps->fill(t_ns, x, out); }});
  }
}

void install_effectors(const PyLoop& loop, const harness::Scenario& sc, harness::Run& run)
{
  for (size_t i = 0; i < loop.effectors.size(); ++i) {
    const uint64_t n = period_ticks(loop.effectors[i], loop.effector_names[i], sc, "effector");
    const int64_t period_ns = static_cast<int64_t>(n * sc.tick_ns());
    try {
      run.plant().add_effector(
          std::make_unique<PyEffector>(loop.effectors[i], loop.effector_names[i], run.plant(), period_ns));
    } catch (const std::invalid_argument& e) {  // more than sim::kMaxEffectors
      throw py::value_error(std::string("effectors: ") + e.what());
    }
  }
}

std::string manifest_with_loop(const std::string& manifest, const PyLoop& loop)
{
  if (!loop.any()) return manifest;
  py::dict d;
  if (loop.has_fsw()) d["fsw"] = loop.fsw_name;
  if (!loop.effectors.empty()) d["effectors"] = loop.effector_names;
  py::dict sd;
  for (const PyLoop::Sensor& x : loop.sensors) sd[py::str(x.name)] = x.object_name;
  if (!loop.sensors.empty()) d["sensors"] = sd;
  const std::string j = py::module_::import("json").attr("dumps")(d).cast<std::string>();
  const size_t open = manifest.find('{');
  if (open == std::string::npos) return manifest;
  return manifest.substr(0, open + 1) + "\n  \"python_in_loop\": " + j + "," + manifest.substr(open + 1);
}

}  // namespace kpy
