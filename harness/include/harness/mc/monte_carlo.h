// monte_carlo: a campaign of dispersed runs of one scenario (docs/monte-carlo.md).
//
// The scenario's `monte_carlo` section declares the dispersions (keys by
// path, list elements included, `wheels[*].axis` for every wheel), the
// pass/fail criteria and the retention policy.  Run k's draws depend on
// (master seed, k) only (mc_draw.h), so a campaign gives the same records
// with any number of threads, MPI ranks or shards, in any order.
//
// Every run writes runs/NNNNNN/manifest.json (its resolved scenario:
// `kestrel run` on it reproduces the run bit for bit); the first
// retention.keep_first runs and the failing ones (at most
// retention.max_failing) also keep their full results and report there.
// Every run's thinned channels (retention.thin_samples samples) and metrics
// go into the summary (summary.csv, summary.h5, mc_report_data.json).
#ifndef HARNESS_MONTE_CARLO_H
#define HARNESS_MONTE_CARLO_H

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/drive/branch.h"
#include "harness/output/metrics.h"  // McMetric
#include "harness/scenario/mc_column.h"
#include "harness/scenario/scenario.h"

namespace harness {

struct McBinding;  // the dispersions bound to the nominal scenario (private)

// What a campaign records, fixed before the first run.
struct McPlan {
  Scenario nominal;            // with its monte_carlo section
  uint64_t master_seed = 1;
  uint64_t runs = 0;
  // Each dispersion's key resolved once (key definition, list element,
  // nominal value, a choice's values decoded): a run's draws only draw and
  // set values.  Shared by copies of the plan; never changed.
  std::shared_ptr<const McBinding> bound;
  std::vector<McColumn> drawn;      // the drawn values' columns
  std::vector<McMetric> metrics;    // default metrics, then one per criterion
  std::vector<std::string> series_columns;  // thinned channel columns
  std::vector<std::pair<std::string, std::vector<std::string>>> channels;  // name -> its columns
  std::vector<std::string> channel_units;
  std::vector<uint64_t> series_rows;  // recorded row index of each thinned sample
  std::vector<double> series_t;       // [s] their times
  // Branched from a checkpoint (kestrel mc --from, branch_mc_plan): every run
  // starts from its state; null: from tick 0.
  std::shared_ptr<const Branch> from;
  std::vector<char> from_settable;  // per bound target: 1 a key settable during a run, 0 an event's key
};

// The plan of a loaded scenario (throws ScenarioError: no monte_carlo
// section, a dispersion whose key does not fit the scenario, a criterion
// naming a column the run does not record).
McPlan make_mc_plan(const Scenario& nominal, uint64_t master_seed, uint64_t runs);

// Branches the campaign from a checkpoint of its nominal scenario
// (docs/checkpoint.md, "Branching a campaign"): every run then starts from
// the checkpoint's state.  Only what may change after the checkpoint may be
// dispersed: the keys of time events at or after its time, and the keys
// settable during a run (applied as event actions at the checkpoint's tick);
// each run's sensor noise starts from its own seed.  Throws CheckpointError
// (unreadable, damaged, of another scenario) or ScenarioError naming the
// dispersion of a key fixed before the checkpoint; the plan is unchanged then.
void branch_mc_plan(McPlan& plan, const std::string& checkpoint);

// Run k's drawn scenario made to start from plan.from: each drawn value of a
// settable key back to the nominal one and set instead by an event at the
// checkpoint's time, from_checkpoint set.  Returns "" or why the draw cannot
// start from the checkpoint (an event time drawn before it).
std::string branch_draw(const McPlan& plan, Scenario& sc);

// One run's outcome.
struct McRecord {
  uint64_t index = 0;
  uint64_t seed = 0;           // the run's Scenario::seed
  bool invalid = false;        // the draw is not a valid spacecraft (not run)
  bool complete = false;       // ran to its duration without failure
  bool pass = false;           // complete, valid and every criterion met
  std::string reason;          // why it did not pass
  std::vector<double> drawn;   // McPlan::drawn (NaN: not drawn)
  std::vector<double> metrics; // McPlan::metrics (NaN: not computed)
  std::vector<float> series;   // samples x series_columns, row-major (NaN where not recorded)
  bool full = false;           // runs/NNNNNN holds full results and a report
  bool interrupted = false;    // stopped by a signal before its end (not recorded)
  double wall_seconds = 0.0;
};

// Runs one run of the plan: its folder `dir` (runs/NNNNNN) gets the
// manifest, and with `full` the whole results (run_scenario).  A stop
// request (set to a signal number) ends the run at a tick boundary: the
// record then says `interrupted` (run_mc_runs drops it and its folder: the
// run is not part of the campaign; rerun it with --only).
McRecord run_mc_one(const McPlan& plan, uint64_t k, const std::filesystem::path& dir, bool full,
                    const std::atomic<int>* stop = nullptr);

// What the summary order and the outcome need of a finished run.
struct McRunState {
  uint64_t index = 0;
  bool pass = false, invalid = false, full = false;
};

// A campaign's finished runs, sorted by index, read one at a time: the
// summary files are written from such a source without holding every
// record (a journal on disk, mc_journal.h, or records in memory).
class McRecordSource {
 public:
  virtual ~McRecordSource() = default;
  virtual size_t size() const = 0;
  virtual const McRunState& state(size_t i) const = 0;
  virtual McRecord record(size_t i) const = 0;
};

// Records held in memory (sorted by index) as a source.
class McMemoryRecords : public McRecordSource {
 public:
  explicit McMemoryRecords(const std::vector<McRecord>& records);
  size_t size() const override { return recs_.size(); }
  const McRunState& state(size_t i) const override { return states_[i]; }
  McRecord record(size_t i) const override { return recs_[i]; }

 private:
  const std::vector<McRecord>& recs_;
  std::vector<McRunState> states_;
};

struct McProgress {
  uint64_t done = 0, total = 0, failed = 0;
  double elapsed_s = 0.0;
};

struct McRunOptions {
  unsigned jobs = 1;
  std::vector<uint64_t> indices;   // the runs to do (any order)
  const std::atomic<int>* stop = nullptr;
  std::function<void(const McProgress&)> progress;  // called from worker threads, serialised
  // false: dir/records is cleared first; true: the runs of `indices` that
  // have a record in dir/records already are not run again (--resume)
  bool resume = false;
  // [s] the first pass commits its records to the journal in groups, at
  // most this far apart (McJournalWriter); 0: each record as it finishes
  double commit_seconds = 1.0;
};

// Runs the given indices on `jobs` threads into dir/runs/, each finished
// run's record kept durably in dir/records/ (mc_journal.h: committed in
// groups at most opt.commit_seconds apart, and when the pass ends);
// returns the finished runs' states sorted by index (the records stay on
// disk: memory does not grow with the number of runs).  After the first
// pass, failing runs beyond keep_first are rerun with full results
// (retention), and the rerun must give the same metrics (else the record
// says so).
std::vector<McRunState> run_mc_journal(const McPlan& plan, const std::filesystem::path& dir, const McRunOptions& opt,
                                       bool& stopped);
// The same, the records read back into memory (sorted by index).
std::vector<McRecord> run_mc_runs(const McPlan& plan, const std::filesystem::path& dir, const McRunOptions& opt,
                                  bool& stopped);

// Summary files of a campaign in `dir`: summary.csv, summary.h5,
// mc_report_data.json, mc_runs.json (lossless, for merging) and the
// report page when the report library is in the build.
struct McSummaryInfo {
  std::string source;
  std::vector<std::string> overrides;
  bool complete = true;          // every planned run is in `records`
  double wall_seconds = 0.0;
  std::string partition;         // e.g. "shard 1/4", "" for a whole campaign
};
// The files are written streaming, one record in memory at a time (the
// series percentiles through a scratch file in `dir`, removed after).
void write_mc_outputs(const McPlan& plan, const McRecordSource& records, const McSummaryInfo& info,
                      const std::filesystem::path& dir);
void write_mc_outputs(const McPlan& plan, const std::vector<McRecord>& records, const McSummaryInfo& info,
                      const std::filesystem::path& dir);

// mc_runs.json <-> records (merge).
std::string mc_records_json(const std::vector<McRecord>& records);
// One record as mc_runs.json holds it (JSON text of one element of "records").
std::string mc_record_json(const McRecord& r);
std::vector<McRecord> mc_records_from_json(const std::string& text);

// Records ordered for the summary table: failing (invalid, failed) first,
// then by index.
std::vector<size_t> mc_table_order(const std::vector<McRecord>& records);
std::vector<size_t> mc_table_order(const McRecordSource& records);

}  // namespace harness

#endif  // HARNESS_MONTE_CARLO_H
