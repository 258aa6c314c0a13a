// branch: runs that start from a checkpoint's state instead of tick 0 -- the
// runs of a campaign branched from it, and their manifests replayed
// (docs/checkpoint.md, "Branching a campaign").
//
// A branched run's scenario is the checkpoint's but for what may change
// after the checkpoint: its seed (the sensors' noise from the restore on),
// the time events still to come (t at or after the checkpoint's time: their
// times and actions) and events added at or after that time (the values of
// keys settable during a run, as their event actions).  Its
// Scenario::from_checkpoint names the file and its checksum.
#ifndef HARNESS_DRIVE_BRANCH_H
#define HARNESS_DRIVE_BRANCH_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/checkpoint.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace harness {

// A checkpoint read to start runs from.
struct Branch {
  std::string path;       // absolute
  uint64_t fnv1a64 = 0;   // the checksum the file ends with
  CheckpointInfo info;
  std::vector<uint8_t> state;
  Scenario scenario;      // the checkpoint's scenario, read back
  double t() const;       // [s] the checkpoint's time: its next tick times dt
  CheckpointRef ref() const;
};

// Reads and decodes the file (CheckpointError naming it: missing, damaged,
// a run that had ended).
std::shared_ptr<const Branch> read_branch(const std::string& path);

// "" when `sc` may start from the checkpoint (see above), else why not: the
// first difference from the checkpoint's scenario, or an added event before
// the checkpoint's time.
std::string branch_difference(const Branch& b, const Scenario& sc);

// The checkpoint sc.from_checkpoint names, checked: the file is there, its
// checksum is the recorded one and sc may start from it (CheckpointError).
std::shared_ptr<const Branch> open_branch(const Scenario& sc);

// RunConfig::accept_events of a run started from b (the saved run's: the
// state's layout depends on it).
bool branch_accepts_events(const Branch& b);

// Restores b's state into `run` (built from the branched scenario with
// branch_accepts_events, its sinks attached, no tick run) but the sensors'
// random streams, which start as the run's own seed starts them
// (restore_branch_state).
void start_branch(Run& run, const Branch& b);

}  // namespace harness

#endif  // HARNESS_DRIVE_BRANCH_H
