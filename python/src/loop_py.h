// Python in the loop (docs/python.md, "Python in the loop"): a Python flight
// software through the harness's FSW endpoint seam and Python force/torque
// effectors in the plant, given to kestrel.run() and kestrel.Run.
#ifndef KESTREL_PYTHON_LOOP_PY_H
#define KESTREL_PYTHON_LOOP_PY_H

#include <string>
#include <vector>

#include "common.h"

namespace kpy {

// The Python objects of one run (fsw: None or a callable; effectors: a
// callable or a sequence of them), checked when the run is built.
struct PyLoop {
  py::object fsw;  // None: the C FSW
  std::vector<py::object> effectors;
  std::string fsw_name;                // "python:module.qualname"
  std::vector<std::string> effector_names;
  bool has_fsw() const { return fsw && !fsw.is_none(); }
  struct Sensor {
    std::string name;  // its recorded quantity (group "python")
    py::object f;
    int size = 0;  // columns
    std::string object_name;
  };
  std::vector<Sensor> sensors;
  bool any() const { return has_fsw() || !effectors.empty() || !sensors.empty(); }
};

// TypeError when fsw, an effector or a sensor is not callable (sensors: None
// or a dict name -> (callable, size)).
PyLoop loop_from(const py::object& fsw, const py::object& effectors, const py::object& sensors = py::none());
// Before the Run: a Python FSW becomes cfg.fsw (ValueError when its declared
// rate_hz is not the scenario's FSW rate).
void install_fsw(const PyLoop& loop, const harness::Scenario& sc, harness::RunConfig& cfg);
// Before the Run: the sensors become cfg.truth_sources.
void install_sensors(const PyLoop& loop, const harness::Scenario& sc, harness::RunConfig& cfg);
// After the Run is built, before its first step: the effectors join its plant.
void install_effectors(const PyLoop& loop, const harness::Scenario& sc, harness::Run& run);
// The manifest text with a "python_in_loop" object naming the objects
// (the CLI refuses to rerun such a manifest).
std::string manifest_with_loop(const std::string& manifest, const PyLoop& loop);

}  // namespace kpy

#endif
