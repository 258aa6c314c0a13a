// outputs: result files of a run.
//   results.h5        HDF5 (C API): /telemetry [rows x cols] float64, chunked,
//                     shuffle + deflate; attributes column_names, column_units
//                     on the dataset; kestrel_version, scenario, seed, dt,
//                     duration, manifest on the root group.
//   telemetry.csv     optional: header "name [unit]", %.17g values.
//   manifest.json     fully resolved scenario (reload with `kestrel run`).
//   report_data.json  data for the HTML report (schema in docs/harness.md).
//   dataflow.dot      the data-flow map.
#ifndef HARNESS_OUTPUTS_H
#define HARNESS_OUTPUTS_H

#include <stdexcept>
#include <string>
#include <vector>

#include "harness/recorder.h"
#include "harness/run.h"
#include "harness/scenario.h"

namespace harness {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void write_hdf5(const std::string& path, const Recorder& rec, const Scenario& sc,
                const std::string& manifest_text);
void write_csv(const std::string& path, const Recorder& rec);
std::string manifest_text(const Scenario& sc, const std::vector<Override>& overrides);
std::string report_data_text(const Run& run);
void write_text(const std::string& path, const std::string& text);

// Read-back helpers (tests, tools): the telemetry table of an HDF5 file.
struct Hdf5Table {
  std::vector<std::string> names, units;
  uint64_t rows = 0;
  std::vector<double> data;  // row-major
  std::string version, scenario, manifest;
  uint64_t seed = 0;
  double dt = 0.0, duration = 0.0;
  bool chunked = false, deflate = false;
};
Hdf5Table read_hdf5(const std::string& path);

}  // namespace harness

#endif  // HARNESS_OUTPUTS_H
