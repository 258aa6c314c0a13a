// checkpoint: a run's whole state in a file, to continue it later or to
// start other runs from it (docs/checkpoint.md: the layout, what is saved,
// the guarantees and limits).
//
// The file holds a header (format version, the tick to run next, the rows
// the result files hold), the scenario the run was built from (canonical
// JSON, scenario_to_json_text), the state bytes of Run::state_io and a
// checksum.  It is written whole to a temporary file, flushed to disk and
// renamed over the previous one: a crash while writing leaves the previous
// checkpoint as it was.
#ifndef HARNESS_CHECKPOINT_H
#define HARNESS_CHECKPOINT_H

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/core/run.h"

namespace harness {

// A file that is not a checkpoint, is damaged, or does not belong to the
// run it is restored into; the message says which and why.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Format 2 adds `outputs` (the results folder's state); format 1 files are
// still read (their `outputs` is empty).
constexpr uint32_t kCheckpointFormat = 2;

struct CheckpointInfo {
  uint64_t tick = 0;         // the next tick to run
  uint64_t total_ticks = 0;  // Run::total_ticks
  uint64_t sink_rows = 0;    // rows the sinks had been handed (the result files hold exactly these)
  std::string kestrel_version;
  std::string scenario_name;
  std::string scenario_text;  // canonical JSON of the run's scenario
  // What the run's results folder needs to be continued (written and read
  // by the drive room, opaque here); "" when the run has none.
  std::string outputs;
  bool accepts_events = false;  // the run was built with RunConfig::accept_events (flag bit 0)
};

// The run's state (Run::state_io) as bytes; std::logic_error when the run
// cannot be saved (Run::checkpoint_refusal).
std::vector<uint8_t> save_run_state(Run& run);
// Restores it into a run built from the same scenario (sinks attached, no
// tick run).  CheckpointError when it does not fit; the run is then unusable.
void restore_run_state(Run& run, const std::vector<uint8_t>& state);

// The same but the sensors' random streams: they keep those the run was
// built with, i.e. they start as a run of the run's own seed starts
// (sim::Rng(seed, name), from its first draw).  A run branched from a
// checkpoint (docs/checkpoint.md, "Branching a campaign") gets its own noise.
void restore_branch_state(Run& run, const std::vector<uint8_t>& state);

// FNV-1a 64 of n bytes, continued from h (kFnv1a64Start for a fresh sum):
// the checksum of checkpoint files and of kestrel run's rows file.
constexpr uint64_t kFnv1a64Start = 0xcbf29ce484222325ull;
uint64_t fnv1a64_bytes(uint64_t h, const void* p, size_t n);
// A 64-bit checksum as written in manifests and messages: 16 lowercase hex
// digits.  Inline: the Monte Carlo readers' fuzz build links none of this
// room's sources.
inline std::string hex64(uint64_t h)
{
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

// The checksum a checkpoint file ends with (FNV-1a 64 of every byte before
// it); the file is decoded first (CheckpointError when it is damaged).
uint64_t checkpoint_checksum(const std::vector<uint8_t>& file, const std::string& path = "checkpoint");

// The file's bytes and back (CheckpointError naming the problem: not a
// checkpoint, another format version, truncated, checksum mismatch).
std::vector<uint8_t> encode_checkpoint(const CheckpointInfo& info, const std::vector<uint8_t>& state);
CheckpointInfo decode_checkpoint(const std::vector<uint8_t>& file, std::vector<uint8_t>& state,
                                 const std::string& path = "checkpoint");

// Writes atomically (temporary file, fsync, rename, fsync of the folder).
// CheckpointError when the file cannot be written; the previous file then
// stays.
void write_checkpoint_file(const std::string& path, const std::vector<uint8_t>& bytes);
std::vector<uint8_t> read_checkpoint_file(const std::string& path);

// The whole round trip: `scenario_text` is the run's scenario as canonical
// JSON (scenario_to_json_text of run.scenario()).
// `outputs`: CheckpointInfo::outputs.
void save_checkpoint(Run& run, const std::string& path, const std::string& scenario_text,
                     const std::string& outputs = "");
// Refuses (CheckpointError) a checkpoint of another scenario, naming both
// and the first line where they differ.  Returns the file's header.
CheckpointInfo restore_checkpoint(Run& run, const std::string& path, const std::string& scenario_text);
// "" when the texts are equal, else where they first differ (line and both lines).
std::string first_difference(const std::string& a, const std::string& b);

}  // namespace harness

#endif  // HARNESS_CHECKPOINT_H
