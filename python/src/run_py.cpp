// kestrel.run, kestrel.Results, kestrel.Run (stepping).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>

#include "common.h"
#include "harness/core/checkpoint.h"
#include "loop_py.h"
#include "harness/drive/run_scenario.h"
#include "core/events.h"  // check_event_action, event_actions
#include "scenario/scenario_limits.h"  // kMaxScenarioEvents

namespace kpy {

namespace {

std::string quantity_key(const harness::Column& c)
{
  return c.group.empty() ? c.quantity : c.group + "/" + c.quantity;
}

// columns [first, first + n) of a quantity or a column named `name`:
// "omega_BN_B" (a quantity, if only one group records it), "truth/omega_BN_B"
// (group/quantity) or a column name ("omega_BN_B_x").
bool find_columns(const std::vector<harness::Column>& cols, const std::string& name, size_t& first, size_t& n,
                  std::string& why)
{
  // a quantity by group/quantity or by its name alone
  std::vector<std::string> groups;
  size_t f = 0, cnt = 0;
  std::string hit;
  for (size_t i = 0; i < cols.size(); ++i) {
    const std::string key = quantity_key(cols[i]);
    if (key == name || cols[i].quantity == name) {
      if (cnt == 0) {
        hit = key;
        f = i;
      }
      if (std::find(groups.begin(), groups.end(), key) == groups.end()) groups.push_back(key);
      if (key == hit) ++cnt;
    }
  }
  if (groups.size() > 1) {
    why = "'" + name + "' is recorded by several messages: ";
    for (size_t i = 0; i < groups.size(); ++i) why += (i ? ", " : "") + groups[i];
    return false;
  }
  if (cnt > 0) {
    first = f;
    n = cnt;
    return true;
  }
  for (size_t i = 0; i < cols.size(); ++i)
    if (cols[i].name == name) {
      first = i;
      n = 1;
      return true;
    }
  why = "no recorded quantity or column '" + name + "' (Results.columns, Results.quantities)";
  return false;
}

py::array_t<double> slice(const Results& r, size_t first, size_t n)
{
  const py::ssize_t rows = r.data.shape(0), nc = r.data.shape(1);
  py::array_t<double> out({rows, static_cast<py::ssize_t>(n)});
  const double* src = r.data.data();
  double* dst = out.mutable_data();
  for (py::ssize_t i = 0; i < rows; ++i)
    for (size_t j = 0; j < n; ++j) dst[static_cast<size_t>(i) * n + j] = src[i * nc + static_cast<py::ssize_t>(first + j)];
  return out;
}

py::array_t<double> get_quantity(const Results& r, const std::string& name)
{
  size_t first = 0, n = 0;
  std::string why;
  if (!find_columns(r.columns, name, first, n, why)) throw py::key_error(why);
  return slice(r, first, n);
}

void summary_from_items(Results& r, const std::vector<harness::SummaryItem>& items)
{
  for (const harness::SummaryItem& it : items) {
    r.summary[py::str(it.key)] = it.value;
    r.summary_units[py::str(it.key)] = it.unit;
  }
}

py::list events_list(const std::vector<harness::AppliedEvent>& ev)
{
  py::list l;
  for (const harness::AppliedEvent& e : ev) {
    py::dict d;
    d["name"] = e.name;
    d["tick"] = e.tick;
    d["t"] = e.t;
    d["what"] = e.what;
    l.append(d);
  }
  return l;
}

std::string read_file(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// summary.txt "key = value unit    # what" -> summary, units
void summary_from_text(Results& r, const std::string& text)
{
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t eq = line.find(" = ");
    if (eq == std::string::npos) continue;
    std::string rest = line.substr(eq + 3);
    const size_t hash = rest.find('#');
    if (hash != std::string::npos) rest = rest.substr(0, hash);
    std::istringstream vs(rest);
    std::string value, unit;
    vs >> value >> unit;
    const std::string key = line.substr(0, eq);
    double v = std::numeric_limits<double>::quiet_NaN();
    try {
      v = std::stod(value);
    } catch (const std::exception&) {
    }
    r.summary[py::str(key)] = v;
    r.summary_units[py::str(key)] = unit;
  }
}

// A Run owned by Python, with the scenario it was built from.
struct PyRun {
  // With the GIL held (the Python objects in the loop are installed with it).
  PyRun(const harness::Scenario& s, PyLoop l) : sc(s), loop(std::move(l))
  {
    {
      py::gil_scoped_release nogil;
      validate_like_cli(sc, false);
    }
    harness::RunConfig cfg;
    cfg.keep_in_memory = true;
    cfg.chunk_rows = 1;  // every row reaches the memory sink at once: results() at any tick
    cfg.accept_events = true;  // apply_event()
    install_fsw(loop, sc, cfg);
    install_sensors(loop, sc, cfg);
    {
      py::gil_scoped_release nogil;
      run = std::make_unique<harness::Run>(sc, std::move(cfg));
    }
    install_effectors(loop, sc, *run);
  }
  harness::Scenario sc;
  PyLoop loop;  // Python objects in the loop (docs/python.md)
  std::unique_ptr<harness::Run> run;
  std::mutex mu;  // one Python thread at a time steps or reads this run
  struct Applied {
    uint64_t tick;
    double t;
    std::string what;
  };
  std::vector<Applied> applied;  // apply_event() log
};

Results results_of(harness::Run& run, const harness::Scenario& sc, const PyLoop& loop)
{
  Results r;
  const harness::MemorySink& mem = run.memory();
  fill_results(r, mem.columns(), mem.data(), mem.rows());
  harness::RunStatus st;
  st.complete = run.done() && run.failure().empty();
  st.ticks = run.tick();
  st.t_reached = run.recorder().rows() > 0 ? run.recorder().last_row()[0] : 0.0;
  st.stopped_by = run.failure();
  st.events = run.events_applied();
  r.complete = st.complete;
  r.failure = run.failure();
  r.summary["complete"] = st.complete ? 1.0 : 0.0;
  r.summary["t_reached"] = st.t_reached;
  r.summary_units["complete"] = "";
  r.summary_units["t_reached"] = "s";
  summary_from_items(r, run.summary());
  r.manifest = manifest_with_loop(harness::manifest_text(sc, {}, &st), loop);
  r.events = events_list(st.events);
  return r;
}

Results run_to_results(const harness::Scenario& sc, const py::object& out_dir, bool force, const PyLoop& loop = {})
{
  if (loop.any() && !out_dir.is_none())
    throw py::value_error("run(out_dir=...) with Python in the loop: not supported (the CLI's files are written by a "
                          "run of the C FSW); keep the Results (r.manifest names the Python objects)");
  if (out_dir.is_none()) {
    std::unique_ptr<harness::Run> run;
    double wall = 0.0;
    {
      py::gil_scoped_release nogil;
      validate_like_cli(sc, false);  // a scenario changed by set(): the checks of loading it
    }
    harness::RunConfig cfg;
    cfg.keep_in_memory = true;
    install_fsw(loop, sc, cfg);
    install_sensors(loop, sc, cfg);
    {
      py::gil_scoped_release nogil;
      run = std::make_unique<harness::Run>(sc, std::move(cfg));
    }
    install_effectors(loop, sc, *run);
    {
      py::gil_scoped_release nogil;
      const auto t0 = std::chrono::steady_clock::now();
      while (!run->done())
        if (!run->step_ticks(1000)) break;
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      run->finish();
    }
    Results r = results_of(*run, sc, loop);
    r.wall_seconds = wall;
    // write() reruns the scenario alone: not these results with Python in the loop
    if (!loop.any()) r.scenario = std::make_shared<const harness::Scenario>(sc);
    return r;
  }
  // the CLI's files and report (run_scenario), and the rows in memory too
  harness::RunOptions opt;
  opt.out_dir = py::str(out_dir).cast<std::string>();
  opt.force = force;
  harness::MemorySink mem;
  opt.extra_sinks.push_back(&mem);
  harness::RunResult rr;
  {
    py::gil_scoped_release nogil;
    validate_like_cli(sc, false);
    rr = harness::run_scenario(sc, opt);
  }
  Results r;
  fill_results(r, mem.columns(), mem.data(), mem.rows());
  r.complete = rr.status.complete;
  r.failure = rr.failure;
  r.files = rr.files;
  r.wall_seconds = rr.wall_seconds;
  for (const std::string& f : rr.files) {
    const std::string base = f.substr(f.find_last_of('/') + 1);
    if (base == "summary.txt") summary_from_text(r, read_file(f));
    if (base == "manifest.json") r.manifest = read_file(f);
  }
  r.events = events_list(rr.status.events);
  r.scenario = std::make_shared<const harness::Scenario>(sc);
  return r;
}

}  // namespace

void fill_results(Results& r, const std::vector<harness::Column>& cols, const double* data, uint64_t rows)
{
  r.columns = cols;
  r.data = py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols.size())});
  if (rows > 0 && !cols.empty()) std::memcpy(r.data.mutable_data(), data, sizeof(double) * rows * cols.size());
}

namespace {

// Actions as one scenario event at this tick boundary, exactly as if the
// scenario had listed it (Run::add_event: checked like one, logged in the
// results' events and replayed by the run's scenario).  `who` heads the
// ValueError.  With r.mu held.
void add_actions(PyRun& r, const std::vector<harness::EventActionSpec>& acts, const std::string& who)
{
  // the scenario's cap counts the scenario's own events and these
  if (r.run->scenario().events.size() >= harness::kMaxScenarioEvents)
    throw py::value_error(who + ": at most " + std::to_string(harness::kMaxScenarioEvents) +
                          " events in a run (the scenario's and apply_event's), as in a scenario");
  const uint64_t k = r.run->tick();
  harness::EventSpec e;
  e.name = "py" + std::to_string(r.applied.size() + 1);
  for (bool taken = true; taken;) {  // unique among the scenario's names
    taken = false;
    for (const harness::EventSpec& x : r.run->scenario().events) taken = taken || x.name == e.name;
    if (taken) e.name += "_";
  }
  const double t = static_cast<double>(k * r.sc.tick_ns()) / 1e9;  // as the recorded t
  e.t = t;
  e.actions = acts;
  try {
    r.run->add_event(e);
  } catch (const harness::ScenarioError& ex) {
    throw py::value_error(who + ": " + ex.what());
  }
  for (const harness::EventActionSpec& a : acts) {
    std::string what = a.device + " " + a.action;
    if (!std::isnan(a.value)) what += " " + py::str(py::float_(a.value)).cast<std::string>();
    r.applied.push_back({k, t, what});
  }
}

// A 1-D array of n finite numbers for set_state's `field` (ValueError naming it).
std::vector<double> state_values(const py::object& v, const char* field, size_t n)
{
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() > 1 || static_cast<size_t>(a.size()) != n)
    throw py::value_error(std::string("set_state: ") + field + " takes " + std::to_string(n) + " number" +
                          (n == 1 ? "" : "s"));
  std::vector<double> out(a.data(), a.data() + n);
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(out[i]))
      throw py::value_error(std::string("set_state: ") + field + "[" + std::to_string(i) + "] is not finite");
  return out;
}

py::array_t<double> to_array(const double* p, size_t n)
{
  py::array_t<double> a(static_cast<py::ssize_t>(n));
  std::copy(p, p + n, a.mutable_data());
  return a;
}

// The plant's truth now: the state vector's parts as NumPy arrays.
py::dict plant_state(const sim::Plant& p)
{
  const sim::StateVector& x = p.state();
  const sim::StateLayout& L = p.layout();
  py::dict d;
  d["attitude"] = to_array(x.data() + sim::StateLayout::sigma_BN, 3);
  d["omega"] = to_array(x.data() + sim::StateLayout::omega_BN_B, 3);
  d["wheel_speeds"] = to_array(x.data() + (p.num_rw() ? L.Omega(0) : 0), static_cast<size_t>(p.num_rw()));
  d["position"] = to_array(x.data() + sim::StateLayout::r_BN_N, 3);
  d["velocity"] = to_array(x.data() + sim::StateLayout::v_BN_N, 3);
  d["propellant"] = to_array(x.data() + (p.num_tanks() ? L.m_p(0) : 0), static_cast<size_t>(p.num_tanks()));
  d["t"] = static_cast<double>(p.t_ns()) / 1e9;
  return d;
}

// set_state's fields as event actions; the whole set checked before any is applied.
void set_plant_state(PyRun& r, const py::dict& fields)
{
  static const char* const kAxes = "xyz";
  const harness::Scenario& sc = r.run->scenario();
  std::vector<harness::EventActionSpec> acts;
  std::vector<std::string> field_of;
  auto vec = [&](const char* field, const char* prefix) {
    if (!fields.contains(field) || fields[field].is_none()) return;
    const std::vector<double> v = state_values(fields[field], field, 3);
    for (size_t i = 0; i < 3; ++i) {
      acts.push_back({"spacecraft", std::string(prefix) + kAxes[i], v[i]});
      field_of.push_back(std::string(field) + "[" + std::to_string(i) + "]");
    }
  };
  for (const auto& kv : fields) {
    const std::string k = py::str(kv.first);
    if (k != "attitude" && k != "omega" && k != "wheel_speeds" && k != "position" && k != "velocity" &&
        k != "propellant")
      throw py::type_error("set_state: no field '" + k +
                           "' (attitude, omega, wheel_speeds, position, velocity, propellant)");
  }
  vec("attitude", "sigma_BN_");
  vec("omega", "omega_BN_B_");
  vec("position", "r_N_");
  vec("velocity", "v_N_");
  if (fields.contains("wheel_speeds") && !fields["wheel_speeds"].is_none()) {
    const std::vector<double> v = state_values(fields["wheel_speeds"], "wheel_speeds", sc.wheels.size());
    for (size_t i = 0; i < v.size(); ++i) {
      acts.push_back({sc.wheels[i].name, "speed", v[i]});
      field_of.push_back("wheel_speeds[" + std::to_string(i) + "]");
    }
  }
  if (fields.contains("propellant") && !fields["propellant"].is_none()) {
    acts.push_back({"spacecraft", "propellant_mass", state_values(fields["propellant"], "propellant", 1)[0]});
    field_of.push_back("propellant");
  }
  for (size_t j = 0; j < acts.size(); ++j) {
    std::string key;
    const std::string why = harness::check_event_action(sc, acts[j], key);
    if (!why.empty()) throw py::value_error("set_state: " + field_of[j] + ": " + why);
  }
  if (!acts.empty()) add_actions(r, acts, "set_state");
}

// What can be set during this run: every device's actions this scenario accepts.
py::list settable_list(const PyRun& r)
{
  const harness::Scenario& sc = r.run->scenario();
  std::vector<std::string> names = harness::event_device_names(sc);
  if (r.run->fsw_accepts_commands()) names.push_back("fsw");
  py::list out;
  for (const std::string& name : names) {
    harness::EventTarget tg;
    if (!harness::resolve_event_device(sc, name, tg).empty()) continue;
    for (const harness::EventActionDef& d : harness::event_actions(tg.device)) {
      const double probe = d.value == harness::EventValue::None ? std::numeric_limits<double>::quiet_NaN() : 0.5;
      std::string key;
      if (!harness::check_event_action(sc, {name, d.word, probe}, key).empty()) continue;
      py::dict e;
      e["device"] = name;
      e["action"] = d.word;
      e["takes_value"] = d.value != harness::EventValue::None;
      e["unit"] = d.unit;
      e["description"] = d.what;
      out.append(e);
    }
  }
  return out;
}

}  // namespace

void bind_run(py::module_& m)
{
  py::class_<Results>(m, "Results",
                      "The recorded rows of a run as NumPy arrays, with units, the summary, the manifest and the "
                      "applied events")
      .def("__getitem__", &get_quantity, py::arg("name"),
           "A quantity ('omega_BN_B', 'truth/omega_BN_B') or one column ('omega_BN_B_x') as an array shaped "
           "(samples, components).  KeyError if not recorded.")
      .def("quantity", &get_quantity, py::arg("name"), "Same as res[name].")
      .def(
          "column",
          [](const Results& r, const std::string& name) {
            for (size_t i = 0; i < r.columns.size(); ++i)
              if (r.columns[i].name == name) {
                py::array_t<double> a = slice(r, i, 1);
                return a.attr("reshape")(-1).cast<py::array_t<double>>();
              }
            throw py::key_error("no recorded column '" + name + "'");
          },
          py::arg("name"), "One flat column as a 1-D array (samples,).")
      .def("unit",
           [](const Results& r, const std::string& name) {
             size_t first = 0, n = 0;
             std::string why;
             if (!find_columns(r.columns, name, first, n, why)) throw py::key_error(why);
             return r.columns[first].unit;
           })
      .def("__contains__",
           [](const Results& r, const std::string& name) {
             size_t first = 0, n = 0;
             std::string why;
             return find_columns(r.columns, name, first, n, why);
           })
      .def("__len__", [](const Results& r) { return r.data.shape(0); })
      .def_property_readonly("t", [](const Results& r) { return slice(r, 0, 1).attr("reshape")(-1); }, "[s] (samples,)")
      .def_readonly("data", &Results::data, "The whole table (samples, columns), in the order of .columns")
      .def_property_readonly("columns",
                             [](const Results& r) {
                               std::vector<std::string> v;
                               for (const auto& c : r.columns) v.push_back(c.name);
                               return v;
                             })
      .def_property_readonly("units",
                             [](const Results& r) {
                               py::dict d;
                               for (const auto& c : r.columns) d[py::str(c.name)] = c.unit;
                               return d;
                             },
                             "column name -> unit")
      .def_property_readonly("quantities",
                             [](const Results& r) {
                               // "group/quantity" -> (unit, frame, [columns]) in recording order
                               py::dict d;
                               for (const auto& c : r.columns) {
                                 const std::string key = quantity_key(c);
                                 if (!d.contains(key)) d[py::str(key)] = py::make_tuple(c.unit, c.frame, py::list());
                                 d[py::str(key)].cast<py::tuple>()[2].cast<py::list>().append(c.name);
                               }
                               return d;
                             },
                             "'group/quantity' -> (unit, frame, [column names])")
      .def_readonly("summary", &Results::summary, "The figures of summary.txt: key -> value")
      .def_readonly("summary_units", &Results::summary_units)
      .def_readonly("manifest", &Results::manifest, "manifest.json text (the resolved scenario and how the run ended)")
      .def_readonly("events", &Results::events, "Applied scenario events: dicts name, tick, t, what")
      .def_readonly("complete", &Results::complete)
      .def_readonly("failure", &Results::failure)
      .def_readonly("files", &Results::files, "Files written (run(sc, out_dir=...))")
      .def(
          "write",
          [](const Results& r, const py::object& out_dir, bool force) {
            if (!r.scenario)
              throw py::value_error("write(): only the Results of kestrel.run() without Python in the loop (a Run's "
                                    "results() may hold faults applied from Python that a rerun would not have)");
            if (out_dir.is_none()) throw py::type_error("write(out_dir): a folder");
            Results again = run_to_results(*r.scenario, out_dir, force);
            // a run depends on its scenario only: the rerun's rows are these
            const bool same = again.data.size() == r.data.size() &&
                              std::memcmp(again.data.data(), r.data.data(), sizeof(double) * r.data.size()) == 0;
            if (!same) throw std::runtime_error("write(): the rerun differs from these results (a bug: report it)");
            return again.files;
          },
          py::arg("out_dir"), py::arg("force") = false,
          "Writes the CLI's files and report of this run into out_dir by running its scenario again "
          "(run_scenario; a run is deterministic, and the rerun's rows are checked equal to these).  Returns the "
          "files written.")
      .def_readonly("wall_seconds", &Results::wall_seconds, "Wall time of the stepping (without the copy to NumPy)")
      .def("__repr__", [](const Results& r) {
        return "<kestrel.Results " + std::to_string(r.data.shape(0)) + " samples x " + std::to_string(r.columns.size()) +
               " columns" + (r.complete ? "" : ", incomplete") + ">";
      });

  m.def(
      "run",
      [](const PyScenario& s, const py::object& out_dir, bool force, const py::object& fsw, const py::object& effectors,
         const py::object& sensors) { return run_to_results(s.sc, out_dir, force, loop_from(fsw, effectors, sensors)); },
      py::arg("scenario"), py::arg("out_dir") = py::none(), py::arg("force") = false, py::arg("fsw") = py::none(),
      py::arg("effectors") = py::none(), py::arg("sensors") = py::none(),
      "Runs a scenario to its end (the GIL released) and returns Results.  With out_dir, also writes the CLI's "
      "files and report there (run_scenario: results.h5, manifest.json, summary.txt, report.html, ...); force "
      "replaces an existing results folder.  fsw: a Python flight software f(sensors: dict) -> actuator dict in "
      "place of the C FSW; effectors: Python force/torque effectors f(t, state: dict) -> (force_B, torque_B); "
      "sensors: {name: (f(t, truth: dict) -> reading, size)}, recorded as python/name "
      "(docs/python.md, \"Python in the loop\"; not with out_dir).");

  py::class_<PyRun>(m, "Run", "A run stepped from Python: step(n), tick, t, state(), apply_event(), results()")
      .def(py::init([](const PyScenario& s, const py::object& fsw, const py::object& effectors,
                       const py::object& sensors) {
             return std::make_unique<PyRun>(s.sc, loop_from(fsw, effectors, sensors));
           }),
           py::arg("scenario"), py::arg("fsw") = py::none(), py::arg("effectors") = py::none(),
           py::arg("sensors") = py::none(),
           "A run of the scenario; fsw, effectors: Python in the loop as in kestrel.run()")
      .def(
          "step",
          [](PyRun& r, py::object n_obj) {
            if (!py::isinstance<py::int_>(n_obj)) throw py::type_error("step(n): n is an int");
            // any non-negative int: more ticks than the run has is "to the end"
            if (n_obj.cast<py::int_>() < py::int_(0)) throw py::value_error("step(n): n >= 0");
            unsigned long long n = PyLong_AsUnsignedLongLong(n_obj.ptr());
            if (PyErr_Occurred()) {
              PyErr_Clear();
              n = std::numeric_limits<unsigned long long>::max();
            }
            bool ok = false;
            {
              py::gil_scoped_release nogil;
              std::lock_guard<std::mutex> g(r.mu);
              ok = r.run->step_ticks(static_cast<uint64_t>(n));
            }
            return ok;
          },
          py::arg("n") = 1,
          "Runs up to n more ticks (fewer at the end; the GIL released).  False once the run has failed (failure).")
      .def(
          "run_to_end",
          [](PyRun& r) {
            py::gil_scoped_release nogil;
            std::lock_guard<std::mutex> g(r.mu);
            while (!r.run->done())
              if (!r.run->step_ticks(1000)) return false;
            return true;
          },
          "Steps to the end.")
      .def_property_readonly("tick", [](PyRun& r) { return r.run->tick(); }, "the next tick to run")
      .def_property_readonly("total_ticks", [](PyRun& r) { return r.run->total_ticks(); })
      .def_property_readonly("t", [](PyRun& r) { return static_cast<double>(r.run->tick()) * r.sc.rates.dt; },
                             "[s] time of the next tick")
      .def_property_readonly("done", [](PyRun& r) { return r.run->done(); })
      .def_property_readonly(
          "scenario",
          [](PyRun& r) {
            std::lock_guard<std::mutex> g(r.mu);
            return PyScenario{r.run->scenario()};
          },
          "A copy of the run's scenario, with the events added during the run (what its manifest replays)")
      .def(
          "save",
          [](PyRun& r, const std::string& path) {
            py::gil_scoped_release nogil;
            std::lock_guard<std::mutex> g(r.mu);
            const std::string why = r.run->checkpoint_refusal();
            if (!why.empty()) throw py::value_error("Run.save: " + why);
            // the run's scenario: with the events apply_event added
            harness::save_checkpoint(*r.run, path, harness::scenario_to_json_text(r.run->scenario()));
          },
          py::arg("path"),
          "Writes a checkpoint of the run between two ticks (docs/checkpoint.md; atomic: temporary file, fsync, "
          "rename).  ValueError when the run cannot be saved (ended, failed).")
      .def_static(
          "restore",
          [](const std::string& path) {
            std::vector<uint8_t> state;
            std::string scenario_text;
            {
              py::gil_scoped_release nogil;
              scenario_text = harness::decode_checkpoint(harness::read_checkpoint_file(path), state, path).scenario_text;
            }
            // built with the GIL held, like any PyRun (no Python objects in its loop)
            auto r = std::make_unique<PyRun>(harness::load_scenario_text(scenario_text, path), PyLoop{});
            {
              py::gil_scoped_release nogil;
              harness::restore_run_state(*r->run, state);
            }
            return r;
          },
          py::arg("path"),
          "A Run continued from a checkpoint Run.save wrote: it goes on exactly as the saved run would.  Its "
          "results() hold the rows from the checkpoint on.  RuntimeError naming the problem for a damaged file or "
          "a checkpoint of another build.")
      .def_property_readonly("failure", [](PyRun& r) { return r.run->failure(); })
      .def(
          "state",
          [](PyRun& r) {
            std::lock_guard<std::mutex> g(r.mu);
            py::dict d;
            const double* row = r.run->recorder().last_row();
            if (row == nullptr) return d;
            for (size_t i = 0; i < r.run->recorder().columns().size(); ++i)
              d[py::str(r.run->recorder().columns()[i].name)] = row[i];
            return d;
          },
          "The latest recorded row: column name -> value ({} before the first row)")
      .def(
          "apply_event",
          [](PyRun& r, const std::string& device, const std::string& action, const py::object& value) {
            std::lock_guard<std::mutex> g(r.mu);
            harness::EventActionSpec a;
            a.device = device;
            a.action = action;
            a.value = std::numeric_limits<double>::quiet_NaN();  // no value
            if (!value.is_none()) {
              if (!(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) ||
                  py::isinstance<py::bool_>(value))
                throw py::type_error("apply_event: " + action + " takes a number as its value");
              a.value = value.cast<double>();
              if (std::isnan(a.value)) throw py::value_error("apply_event: " + action + ": the value is NaN");
            }
            add_actions(r, {a}, "apply_event");
          },
          py::arg("device"), py::arg("action"), py::arg("value") = py::none(),
          "Applies a scenario event action at this tick boundary (before the next tick): any device and action of "
          "a scenario's events (docs/events.md), e.g. apply_event('rw2', 'fail_off'), ('rw1', 'torque_limit', 0.05), "
          "('gyro', 'noise_scale', 3), ('fsw', 'mode_inertial').  Checked like a scenario event (ValueError naming "
          "the problem); logged in r.applied and in the results' events.")
      .def_property_readonly(
          "applied",
          [](PyRun& r) {
            py::list l;
            for (const PyRun::Applied& a : r.applied) {
              py::dict e;
              e["tick"] = a.tick;
              e["t"] = a.t;
              e["what"] = a.what;
              l.append(e);
            }
            return l;
          },
          "apply_event() log: dicts tick, t, what")
      .def(
          "get_state",
          [](PyRun& r) {
            std::lock_guard<std::mutex> g(r.mu);
            return plant_state(r.run->plant());
          },
          "The plant's truth now (not the last recorded row), as NumPy arrays: attitude (MRP sigma_BN), omega "
          "(omega_BN_B [rad/s]), wheel_speeds (each wheel's rotor speed relative to the body [rad/s]), position "
          "(r_BN_N [m]), velocity (v_BN_N [m/s]), propellant (each tank [kg]); t [s], the plant's time")
      .def(
          "set_state",
          [](PyRun& r, const py::kwargs& fields) {
            std::lock_guard<std::mutex> g(r.mu);
            set_plant_state(r, fields);
          },
          "Sets parts of the plant's state at this tick boundary (in effect when the next tick starts): "
          "attitude (3, MRP; the shadow set if |sigma| > 1), omega (3, rad/s), wheel_speeds (one per wheel, "
          "rad/s, within Omega_max), position (3, m), velocity (3, m/s), propellant (kg, the first tank, within "
          "[0, its load]).  Each component is one action of one event (device spacecraft or the wheel), logged "
          "in applied and replayed by the run's manifest.  ValueError naming the field; nothing is set then.")
      .def(
          "settable",
          [](PyRun& r) {
            std::lock_guard<std::mutex> g(r.mu);
            return settable_list(r);
          },
          "Everything that can be set during this run (the event actions this scenario accepts, "
          "docs/events.md): dicts device, action, takes_value, unit, description")
      .def(
          "results",
          [](PyRun& r) {
            std::lock_guard<std::mutex> g(r.mu);
            // the run's scenario: the events apply_event() added are in its
            // manifest, which replays them
            return results_of(*r.run, r.run->scenario(), r.loop);
          },
          "The rows recorded so far as Results (the run goes on).");
}

}  // namespace kpy
