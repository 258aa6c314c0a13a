// kestrel: the Python module (docs/python.md).  Scenario, run, Results,
// Run (stepping), monte_carlo and the fsw submodule.
#include <stdexcept>

#include "common.h"
#include "harness/mc/monte_carlo.h"
#include "harness/drive/run_scenario.h"
#include "harness/output/results_dir.h"

// The FSW library's assert hook (fsw_status.h): the module returns
// FSW_E_NULL_ARG; nothing is printed or aborted inside the interpreter.
extern "C" void fsw_assert_failed(const char* file, int line)
{
  (void)file;
  (void)line;
}

namespace py = pybind11;

// The extension kestrel._kestrel; the package kestrel (python/kestrel/__init__.py)
// re-exports its names and registers kestrel.fsw.
PYBIND11_MODULE(_kestrel, m)
{
  m.doc() = "Kestrel: scenarios, closed-loop runs, Monte Carlo campaigns and the FSW algorithms (docs/python.md)";
  m.attr("__version__") = harness::version();

  // ScenarioError -> kestrel.ScenarioError (a ValueError): the message is
  // the CLI's "file:line:col: key: message" lines; .issues holds them as
  // tuples (file, line, column, key, message).
  static py::exception<harness::ScenarioError> scenario_error(m, "ScenarioError", PyExc_ValueError);
  static py::exception<harness::OutputError> output_error(m, "OutputError", PyExc_OSError);
  static py::exception<harness::ResultsDirRefused> refused(m, "ResultsDirRefused", PyExc_FileExistsError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const harness::ScenarioError& e) {
      py::list issues;
      for (const harness::ScenarioIssue& i : e.issues())
        issues.append(py::make_tuple(kpy::text(i.file), i.line, i.column, kpy::text(i.key), kpy::text(i.message)));
      py::object inst = py::reinterpret_borrow<py::object>(scenario_error.ptr())(kpy::text(e.what()));
      inst.attr("issues") = issues;
      PyErr_SetObject(scenario_error.ptr(), inst.ptr());
    } catch (const harness::OutputError& e) {
      PyErr_SetObject(output_error.ptr(), kpy::text(e.what()).ptr());
    } catch (const harness::ResultsDirRefused& e) {
      PyErr_SetObject(refused.ptr(), kpy::text(e.what()).ptr());
    }
  });

  kpy::bind_scenario(m);
  kpy::bind_run(m);
  kpy::bind_mc(m);
  py::module_ fsw = m.def_submodule("fsw", "Thin bindings of single FSW algorithms (fsw_c), NumPy in and out");
  kpy::bind_fsw(fsw);
}
