// kestrel.Scenario: load, typed get/set by key path, validate, to_json.
#include <cmath>
#include <limits>

#include "common.h"
#include "harness/mc/monte_carlo.h"

namespace kpy {

namespace {

py::object to_python(const harness::ParameterValue& v)
{
  return std::visit(
      [](const auto& x) -> py::object {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
          py::array_t<double> a(3);
          for (int i = 0; i < 3; ++i) a.mutable_at(i) = x(i);
          return std::move(a);
        } else if constexpr (std::is_same_v<T, Eigen::Matrix3d>) {
          py::array_t<double> a({3, 3});
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) a.mutable_at(i, j) = x(i, j);
          return std::move(a);
        } else {
          if constexpr (std::is_same_v<T, std::string>) return text(x);
          else return py::cast(x);
        }
      },
      v.value);
}

// A Python value as set_parameter takes it: bool, int, float, str, a
// 3-vector or a 3x3 matrix (any sequence NumPy turns into float64 of that
// shape).  Anything else: TypeError / ValueError.
harness::ParameterValue from_python(const py::handle& h)
{
  if (py::isinstance<py::bool_>(h)) return harness::ParameterValue(h.cast<bool>());
  if (py::isinstance<py::int_>(h)) {
    // Python ints are unbounded: outside long long / uint64 -> OverflowError
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(h.ptr(), &overflow);
    if (overflow == 0) {
      if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
      return harness::ParameterValue(v);
    }
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(h.ptr());
      if (PyErr_Occurred()) throw py::error_already_set();
      return harness::ParameterValue(u);
    }
    throw py::value_error("integer too small for any scenario key");
  }
  if (py::isinstance<py::float_>(h)) return harness::ParameterValue(h.cast<double>());
  if (py::isinstance<py::str>(h)) return harness::ParameterValue(h.cast<std::string>());
  // NumPy scalars
  py::module_ np = py::module_::import("numpy");
  if (py::isinstance(h, np.attr("bool_"))) return harness::ParameterValue(h.cast<bool>());
  if (py::isinstance(h, np.attr("integer"))) return from_python(py::int_(py::reinterpret_borrow<py::object>(h)));
  if (py::isinstance(h, np.attr("floating"))) return harness::ParameterValue(h.cast<double>());
  if (py::isinstance<py::bytes>(h) || h.is_none() || !(py::isinstance<py::sequence>(h) || py::isinstance<py::array>(h)))
    throw py::type_error("a scenario value is a bool, int, float, str, 3-vector or 3x3 matrix, not " +
                         std::string(py::str(py::type::of(h).attr("__name__"))));
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
    throw py::type_error("a scenario value is a bool, int, float, str, 3-vector or 3x3 matrix");
  }
  if (!a) {
    PyErr_Clear();
    throw py::type_error("a scenario value is a bool, int, float, str, 3-vector or 3x3 matrix");
  }
  if (a.ndim() == 1 && a.shape(0) == 3) return harness::ParameterValue(Eigen::Vector3d(a.at(0), a.at(1), a.at(2)));
  if (a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3) {
    Eigen::Matrix3d M;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) M(i, j) = a.at(i, j);
    return harness::ParameterValue(M);
  }
  std::string shape = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
  throw py::value_error("an array value is a 3-vector or a 3x3 matrix, not shape " + shape + ")");
}

std::vector<harness::Override> overrides_of(const py::object& o)
{
  std::vector<harness::Override> ov;
  if (o.is_none()) return ov;
  if (py::isinstance<py::dict>(o)) {
    // {"duration": 10} -> duration=10 (values as YAML text, like --set)
    for (auto kv : o.cast<py::dict>()) {
      py::object v = py::reinterpret_borrow<py::object>(kv.second);
      if (py::hasattr(v, "tolist")) v = v.attr("tolist")();  // NumPy arrays and scalars
      std::string text;
      if (py::isinstance<py::bool_>(v)) text = v.cast<bool>() ? "true" : "false";
      else if (py::isinstance<py::str>(v)) text = v.cast<std::string>();
      else if (py::isinstance<py::float_>(v)) text = py::str(py::repr(v)).cast<std::string>();
      else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) text = py::repr(py::list(v)).cast<std::string>();
      else text = py::str(v).cast<std::string>();
      ov.push_back({py::str(kv.first).cast<std::string>(), text});
    }
    return ov;
  }
  for (const py::handle& s : o) ov.push_back(harness::parse_override(s.cast<std::string>()));
  return ov;
}

// A nested dict as the JSON text of a scenario file (JSON is YAML), read by
// the YAML reader: the same checks and messages, each naming its key path.
// NumPy arrays and scalars are taken as their lists and numbers.
std::string dict_text(const py::dict& d)
{
  py::module_ json = py::module_::import("json");
  py::cpp_function plain([](const py::object& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("a scenario value is a number, bool, str, list or dict, not " +
                         std::string(py::str(py::type::of(o).attr("__name__"))));
  });
  return json.attr("dumps")(d, py::arg("indent") = 1, py::arg("allow_nan") = false, py::arg("default") = plain)
      .cast<std::string>();
}

}  // namespace

py::str text(const std::string& s)
{
  PyObject* o = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "backslashreplace");
  if (o == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

void validate_like_cli(const harness::Scenario& sc, bool with_monte_carlo)
{
  harness::validate_scenario(sc);
  harness::check_run_configuration(sc);
  if (with_monte_carlo && sc.monte_carlo) (void)harness::make_mc_plan(sc, sc.monte_carlo->seed, sc.monte_carlo->runs);
}

void bind_scenario(py::module_& m)
{
  py::class_<PyScenario>(m, "Scenario",
                         "A scenario (docs/harness.md): loaded from YAML or a run manifest, changed key by key "
                         "with the CLI's checks and messages")
      .def_static(
          "load",
          [](const std::string& path, const py::object& overrides) {
            auto ov = overrides_of(overrides);
            py::gil_scoped_release nogil;
            return PyScenario{harness::load_scenario(path, ov)};
          },
          py::arg("path"), py::arg("overrides") = py::none(),
          "Loads and validates a scenario file (or a run manifest).  overrides: ['duration=10', ...] or "
          "{'duration': 10}, as `kestrel run --set`.  Raises kestrel.ScenarioError (file:line:col: key: message).")
      .def_static(
          "from_text",
          [](const std::string& text, const std::string& name, const py::object& overrides) {
            return PyScenario{harness::load_scenario_text(text, name, overrides_of(overrides))};
          },
          py::arg("text"), py::arg("name") = "<text>", py::arg("overrides") = py::none(),
          "The same from YAML (or JSON) text; `name` is used in messages.")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::string& name, const py::object& overrides) {
            const std::string t = dict_text(d);
            return PyScenario{harness::load_scenario_text(t, name, overrides_of(overrides))};
          },
          py::arg("d"), py::arg("name") = "<dict>", py::arg("overrides") = py::none(),
          "A scenario from a nested dict of the file's keys ({'rates': {...}, 'spacecraft': {...}, ...}), "
          "with the file's checks and messages (`name`:line:col: key.path: message); NumPy values are accepted.")
      .def(
          "to_dict",
          [](const PyScenario& s) {
            return py::module_::import("json").attr("loads")(harness::scenario_to_json_text(s.sc, -1));
          },
          "The resolved scenario as a nested dict of plain Python values: every key with its effective value "
          "(SI spellings, attitudes as MRPs), the form to_json() writes; Scenario.from_dict(s.to_dict()) == s.")
      .def(
          "__eq__",
          [](const PyScenario& a, const py::object& b) -> py::object {
            if (!py::isinstance<PyScenario>(b)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            return py::bool_(harness::scenario_to_json_text(a.sc, -1) ==
                             harness::scenario_to_json_text(b.cast<const PyScenario&>().sc, -1));
          },
          py::is_operator(), "Equal resolved scenarios: the same to_json() (every key's effective value).")
      .def(
          "get", [](const PyScenario& s, const std::string& path) { return to_python(harness::get_parameter(s.sc, path)); },
          py::arg("path"),
          "The value of a key ('fsw.mrp_fb.K', 'wheels[0].Omega_0_rpm', 'spacecraft.inertia'): float, int, bool, "
          "str, or a NumPy 3-vector / 3x3 matrix, in the unit of the path's spelling.")
      .def(
          "set",
          [](PyScenario& s, const std::string& path, const py::handle& value) {
            harness::set_parameter(s.sc, path, from_python(value));
          },
          py::arg("path"), py::arg("value"),
          "Sets a key with the checks of the key's definition (type, bounds, unit vector, inertia).  Raises "
          "kestrel.ScenarioError naming the key and leaves the scenario unchanged.  Checks across keys: validate().")
      .def(
          "validate",
          [](const PyScenario& s) {
            py::gil_scoped_release nogil;
            validate_like_cli(s.sc, true);
          },
          "Every check of `kestrel validate`: the schema (reloaded from its canonical form), what a run checks "
          "before its first step (plant, FSW configuration, sensors) and a monte_carlo section's criteria.  "
          "Raises kestrel.ScenarioError.")
      .def("to_json", [](const PyScenario& s, int indent) { return harness::scenario_to_json_text(s.sc, indent); },
           py::arg("indent") = 2, "The resolved scenario as canonical JSON (SI keys; reload with Scenario.from_text).")
      .def("copy", [](const PyScenario& s) { return PyScenario{s.sc}; })
      .def("__copy__", [](const PyScenario& s) { return PyScenario{s.sc}; })
      .def("__deepcopy__", [](const PyScenario& s, const py::object&) { return PyScenario{s.sc}; })
      .def_static("keys", &harness::scenario_key_paths, "Every key path the schema knows ([i] for list elements).")
      .def_property_readonly("name", [](const PyScenario& s) { return text(s.sc.name); })
      .def_property_readonly("description", [](const PyScenario& s) { return text(s.sc.description); })
      .def_property_readonly("duration", [](const PyScenario& s) { return s.sc.duration; }, "[s]")
      .def_property_readonly("dt", [](const PyScenario& s) { return s.sc.rates.dt; }, "[s] base tick")
      .def_property_readonly("seed", [](const PyScenario& s) { return s.sc.seed; })
      .def_property_readonly("num_ticks", [](const PyScenario& s) { return s.sc.num_ticks(); })
      .def_property_readonly("source_file", [](const PyScenario& s) { return s.sc.source_file; })
      .def_property_readonly("has_monte_carlo", [](const PyScenario& s) { return s.sc.monte_carlo.has_value(); })
      .def("__repr__", [](const PyScenario& s) {
        return "<kestrel.Scenario '" + s.sc.name + "' duration=" + py::str(py::float_(s.sc.duration)).cast<std::string>() +
               " s>";
      });
}

}  // namespace kpy
