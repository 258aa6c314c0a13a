// commands: everything the `kestrel` program does, as library functions.
// The executable (src/main.cpp) only parses arguments and calls these.
//
// Exit codes (docs/harness.md):
//   0  ok
//   1  run failed (non-finite plant state, recorder overflow, internal error)
//   2  usage error (bad arguments, malformed --set)
//   3  invalid scenario (unknown key, wrong type, invalid value, unreadable
//      file, YAML syntax, configuration rejected by the plant or an FSW module)
//   4  output error (results folder or files cannot be written, not enough
//      free space); the target folder is left as it was
//   5  results folder refused: it already holds results (without --force),
//      holds foreign files, or another run is writing it; nothing was run
//   6  Monte Carlo: the campaign ran and at least one run failed its
//      criteria, failed, or was an invalid draw (docs/monte-carlo.md)
//   130, 143  interrupted by SIGINT / SIGTERM (128 + the signal): the rows
//      computed so far are written, marked incomplete
#ifndef HARNESS_COMMANDS_H
#define HARNESS_COMMANDS_H

#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace harness {

class RunControl;  // outputs.h

enum ExitCode : int {
  kExitOk = 0,
  kExitRunFailed = 1,
  kExitUsage = 2,
  kExitInvalidScenario = 3,
  kExitOutput = 4,
  kExitRefused = 5,
  kExitMcFailures = 6,
  kExitInterruptedBase = 128,  // + the signal number
};

struct RunCommand {
  std::string scenario;             // YAML scenario or manifest.json
  std::string out_dir;              // "" : runs/<scenario name>
  std::vector<std::string> sets;    // "key.path=value"
  bool csv = false;                 // also write telemetry.csv
  bool progress = false;            // draw a progress bar on `err`
  bool force = false;               // replace an existing results folder whole
  bool realtime = false;            // pace to the wall clock (pacer.h)
  double rt_scale = 1.0;            // ... at this multiple of real time
  const std::atomic<int>* stop = nullptr;  // set to a signal number to stop the run (main.cpp)
  std::string fsw;                  // "" in process; udp:HOST:PORT / serial:DEVICE:BAUD (docs/hwil.md)
  std::string on_missing;           // "" (fail in lockstep, hold with faults or --realtime), hold, zero
  double link_timeout = 10.0;       // lockstep reply timeout [s]
  std::string pil_bin;              // --fsw pil:TARGET: the FSW program ("" : the build's, docs/pil.md)
  std::string pil_emulator;         // ... and the emulator command ("" : the target's QEMU)
  double reply_timeout = 0.5;       // hold/zero: give a cycle up after [s]
  double loss = 0, corrupt = 0, duplicate = 0, reorder = 0, delay = 0;  // fault probabilities [%]
  int delay_cycles = 2;
  uint64_t link_seed = 1;
  RunControl* control = nullptr;    // steers the run while it goes: the live view (docs/live.md)
};

// Writes the FSW configuration image of a scenario (docs/hwil.md).
int cmd_fsw_config(const std::string& scenario, const std::vector<std::string>& sets, const std::string& out_file,
                   std::ostream& out, std::ostream& err);

int cmd_run(const RunCommand& c, std::ostream& out, std::ostream& err);

// `kestrel mc` (docs/monte-carlo.md).
struct McCommand {
  std::string scenario;              // YAML scenario (with monte_carlo) or a manifest of one
  std::vector<std::string> sets;     // --set overrides (of the nominal scenario)
  std::string out_dir;               // "" : runs/<name>_mc
  std::optional<uint64_t> runs;      // default: monte_carlo.runs
  std::optional<uint64_t> seed;      // default: monte_carlo.seed
  unsigned jobs = 1;                 // threads (per MPI rank)
  std::string only;                  // "17,42,100-120": just these runs
  uint32_t shard_index = 0, shard_count = 1;  // --shard i/N
  unsigned slurm_tasks = 0;          // > 0: write Slurm batch scripts for this many shards instead
  bool force = false;
  bool progress = false;
  const std::atomic<int>* stop = nullptr;
};
int cmd_mc(const McCommand& c, std::ostream& out, std::ostream& err);
// Joins the shard folders of one campaign into out_dir.
int cmd_mc_merge(const std::string& out_dir, const std::vector<std::string>& shards, bool force, std::ostream& out,
                 std::ostream& err);
int cmd_validate(const std::string& scenario, const std::vector<std::string>& sets, std::ostream& out,
                 std::ostream& err);
int cmd_list(const std::string& dir, std::ostream& out, std::ostream& err);
// `kestrel bench`: the reference cases (only those named in `only`, when
// it is not empty: s1-0.01, s1-0.1, s1-substeps, s2); exit 2 on an unknown name.
int cmd_bench(const std::string& dir, const std::vector<std::string>& only, std::ostream& out, std::ostream& err);

// Directory of the shipped scenarios: $KESTREL_SCENARIO_DIR, else the
// source tree's scenarios/ (compiled in), else ./scenarios.
std::string scenario_dir();

}  // namespace harness

#endif  // HARNESS_COMMANDS_H
