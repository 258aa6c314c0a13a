// outputs: the result files of a run (harness_io).
//   results.h5        HDF5 (C API), streamed in chunks as the run goes:
//                     one dataset per recorded quantity, /<message>/<quantity>
//                     shaped (samples, components), float64, chunked, shuffle
//                     + deflate, attributes unit, frame, columns; /t (samples,
//                     1) the time.  Root attributes: kestrel_version,
//                     scenario, seed, dt, duration, manifest, column_names,
//                     column_units, column_datasets (the flat table's order),
//                     rows and complete (written at the end).
//   telemetry.csv     optional: header "name [unit]", %.17g values, streamed.
//   manifest.json     fully resolved scenario (reload with `kestrel run`).
//   report_data.json  data for the HTML report (schema in docs/report.md):
//                     time series decimated for display (min/max per bucket),
//                     full-rate body rates for the jitter spectrum's window.
//   dataflow.dot      the data-flow map.
#ifndef HARNESS_OUTPUT_OUTPUTS_H
#define HARNESS_OUTPUT_OUTPUTS_H

#include <atomic>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/core/recorder.h"
#include "harness/core/run.h"
#include "harness/output/metrics.h"
#include "harness/scenario/scenario.h"

namespace harness {

struct PacingStats;  // harness/core/pacer.h

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---- sinks --------------------------------------------------------------------
// Streams the rows into an HDF5 file (created at begin, closed at end).
class Hdf5Sink : public RecordSink {
 public:
  Hdf5Sink(std::string path, const Scenario& sc, std::string manifest_text);
  ~Hdf5Sink() override;
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool complete) override;
  // The run's applied events (Run::events_applied()), written at end() as
  // /events (rows: tick, t [s]; attributes names, actions) when the
  // scenario has events.  Alive until end().
  void set_events(const std::vector<AppliedEvent>* log) { events_ = log; }

 private:
  const std::vector<AppliedEvent>* events_ = nullptr;
  struct File;
  std::string path_;
  const Scenario& sc_;
  std::string manifest_;
  std::unique_ptr<File> f_;
  size_t nc_total_ = 0;
};

// Streams the rows into a CSV file.
class CsvSink : public RecordSink {
 public:
  explicit CsvSink(std::string path) : path_(std::move(path)) {}
  ~CsvSink() override;
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool complete) override;

 private:
  std::string path_;
  FILE* f_ = nullptr;
  size_t nc_ = 0;
};

// Keeps what the report shows, bounded for any duration: with more rows
// than 2 * kReportBuckets, each column is reduced to its minimum and maximum
// per bucket of consecutive rows (in the order they occurred, at the times of
// the bucket's first and last rows; t and the attitude quaternion take the
// values of those rows), so no extreme is lost; the last kSpectrumRows rows
// of t, the body rates and the pointing error are kept at full rate for the
// jitter spectrum.  Fewer rows are kept as they are.
class ReportSink : public RecordSink {
 public:
  static constexpr size_t kReportBuckets = 4000;
  static constexpr size_t kSpectrumRows = 32768;
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool complete) override;
  // The report's series (a JSON object text: "series", "units", "attitude",
  // and "spectrum" / "decimation" when reduced); valid after end().
  std::string series_json() const;
  bool decimated() const { return bucket_rows_ > 1; }

 private:
  void close_bucket();
  RecordLayout layout_;
  std::vector<char> endpoint_col_;  // 1: first/last row values (t, q_BN), 0: min/max
  size_t bucket_rows_ = 1;          // rows per bucket (1: every row kept)
  uint64_t rows_seen_ = 0;
  // display points: 2 per bucket (or 1 per row when not decimated)
  std::vector<double> points_;      // npoints x ncols, row-major
  // the open bucket
  size_t in_bucket_ = 0;
  std::vector<double> first_, last_, lo_, hi_;
  std::vector<uint64_t> lo_at_, hi_at_;
  // full-rate ring for the spectrum: t, omega_BN_B_x/y/z, pointing_error_deg
  std::vector<size_t> spec_cols_;
  std::vector<double> ring_;
  uint64_t ring_n_ = 0;
};

// ---- files ----------------------------------------------------------------------
// How a run ended, as recorded in its manifest ("result") and summary.
struct RunStatus {
  bool complete = false;       // every tick ran, no failure, no interrupt
  uint64_t ticks = 0;          // ticks executed
  double t_reached = 0.0;      // [s] time of the last recorded row
  std::string stopped_by;      // "" | "SIGINT" | "SIGTERM" | the failure's message
  std::vector<AppliedEvent> events;  // applied scenario events (written when the scenario has events)
};
// The resolved scenario (reload it with `kestrel run manifest.json`); with a
// status, also a "result" object saying how the run ended.
std::string manifest_text(const Scenario& sc, const std::vector<Override>& overrides,
                          const RunStatus* status = nullptr);
// What a run says of itself, written alike into summary.txt and
// report_data.json (one source): the summary items, every warning the run
// printed, and the scenario's requirement lines evaluated on the run.
struct RunStory {
  std::vector<SummaryItem> summary;
  std::vector<std::string> warnings;
  std::vector<RequirementResult> requirements;
};
// report_data.json from a finished run and its report sink (with a status,
// meta also has t_reached and stopped_by; with pacing figures, the rt_*
// figures of summary.txt).  With a story: its summary, "warnings" and
// "requirements"; without: Run::summary() alone.
std::string report_data_text(const Run& run, const ReportSink& report, const RunStatus* status = nullptr,
                             const PacingStats* pacing = nullptr, const RunStory* story = nullptr);
// The report's "geometry" object (wheel axes and positions, thrusters), as
// JSON text: report_data.json and the live view.
std::string geometry_json_text(const Run& run);
void write_text(const std::string& path, const std::string& text);

// Read-back (tests, tools): the flat telemetry table of an HDF5 results file.
struct Hdf5Table {
  std::vector<std::string> names, units, datasets;
  uint64_t rows = 0;
  std::vector<double> data;  // row-major
  std::string version, scenario, manifest;
  uint64_t seed = 0;
  double dt = 0.0, duration = 0.0;
  bool chunked = false, deflate = false, complete = false;
  std::vector<AppliedEvent> events;  // /events, when the file has it
};
Hdf5Table read_hdf5(const std::string& path);

}  // namespace harness

#endif  // HARNESS_OUTPUT_OUTPUTS_H
