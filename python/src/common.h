// Shared declarations of the kestrel Python module (docs/python.md).
#ifndef KESTREL_PYTHON_COMMON_H
#define KESTREL_PYTHON_COMMON_H

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "harness/core/recorder.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace kpy {

namespace py = pybind11;

// A scenario as Python sees it: a value (copied on Run and run()).
struct PyScenario {
  harness::Scenario sc;
};

// The recorded rows of a run, copied out of the C++ run (the arrays stay
// valid after the run is gone).
struct Results {
  std::vector<harness::Column> columns;
  py::array_t<double> data;  // (samples, columns)
  py::dict summary;          // key -> value; plus "complete", "t_reached"
  py::dict summary_units;    // key -> unit
  std::string manifest;
  py::list events;           // dicts: name, tick, t, what
  bool complete = false;
  std::string failure;
  std::vector<std::string> files;  // written (run(sc, out_dir=...))
  double wall_seconds = 0.0;
  // The scenario of a whole run (kestrel.run): Results.write() reruns it.
  std::shared_ptr<const harness::Scenario> scenario;
};

// Rows of a MemorySink (or `rows` rows of a raw table) into Results.
void fill_results(Results& r, const std::vector<harness::Column>& cols, const double* data, uint64_t rows);

// A C++ string as a Python str; bytes that are not UTF-8 (a scenario file
// may hold any) as \xNN escapes instead of a UnicodeDecodeError.
py::str text(const std::string& s);

// What `kestrel validate` checks: the schema (a scenario changed by set()),
// the run's configuration and, with run_checks_only false and a
// monte_carlo section, the campaign's plan.  Throws ScenarioError.
void validate_like_cli(const harness::Scenario& sc, bool with_monte_carlo);

void bind_scenario(py::module_& m);
void bind_run(py::module_& m);
void bind_mc(py::module_& m);
void bind_fsw(py::module_& m);

}  // namespace kpy

#endif
