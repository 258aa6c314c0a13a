// run_checkpoints: `kestrel run --checkpoint-every T` and `--resume DIR`
// (docs/checkpoint.md, "Continuing a kestrel run").
//
// A run with checkpoints keeps, in its working folder, the rows its sinks
// were handed (checkpoint.rows, row_journal.h) and, every T simulated
// seconds, the checkpoint (checkpoint.kckp): the run's state, its scenario,
// and what its results folder needs (the source file and --set lines of
// the manifest, the checkpoint interval, the rows file's mark).  The rows
// are flushed to disk before the checkpoint that claims them is renamed
// into place.  A resumed run rebuilds every result file from the rows (the
// sinks are handed the same rows in the same writes as the first time, so
// the HDF5 file, the CSV, the report's series and the requirement figures
// come out as an uninterrupted run's), restores the state and goes on.
#ifndef HARNESS_DRIVE_RUN_CHECKPOINTS_H
#define HARNESS_DRIVE_RUN_CHECKPOINTS_H

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/run.h"
#include "harness/output/row_journal.h"
#include "harness/scenario/scenario.h"

namespace harness {

class RunCheckpoints {
 public:
  static constexpr const char* kCheckpointName = "checkpoint.kckp";
  static constexpr const char* kRowsName = "checkpoint.rows";

  // A new run: a checkpoint every `every_s` simulated seconds, rounded to
  // the nearest whole tick (at least one).
  RunCheckpoints(const std::filesystem::path& work, const Scenario& sc, const std::vector<Override>& overrides,
                 double every_s);
  // A run continued: reads the checkpoint in `work` (CheckpointError: not a
  // checkpoint, damaged, of another format, or not of a kestrel run).
  explicit RunCheckpoints(const std::filesystem::path& work);
  RunCheckpoints(const RunCheckpoints&) = delete;
  RunCheckpoints& operator=(const RunCheckpoints&) = delete;
  ~RunCheckpoints();

  bool resuming() const { return resume_; }
  // The run's scenario (a resumed run: the checkpoint's, with its source
  // file) and --set lines (the manifest's).
  const Scenario& scenario() const { return sc_; }
  const std::vector<Override>& overrides() const { return overrides_; }
  double every_seconds() const;

  // After the run's sinks are attached: CheckpointError when the run
  // cannot be checkpointed (Run::checkpoint_refusal); adds the rows sink;
  // resuming: hands `sinks` the rows up to the checkpoint and restores the
  // run's state.
  void attach(Run& run, const std::vector<RecordSink*>& sinks);
  // At a tick boundary: writes the checkpoint when one is due; the ticks
  // to the next one.
  uint64_t boundary(Run& run);
  // The run ended: removes the checkpoint and the rows file (they are not
  // part of the results).
  void discard();

 private:
  std::filesystem::path work_;
  bool resume_ = false;
  Scenario sc_;
  std::vector<Override> overrides_;
  std::string scenario_text_;
  uint64_t every_ticks_ = 1;
  uint64_t last_saved_ = 0;
  RowJournal::Mark mark_;
  std::vector<uint8_t> state_;  // resuming: the state to restore
  uint64_t sink_rows_ = 0;      // resuming: the checkpoint's
  std::unique_ptr<RowJournal> rows_;
};

}  // namespace harness

#endif  // HARNESS_DRIVE_RUN_CHECKPOINTS_H
