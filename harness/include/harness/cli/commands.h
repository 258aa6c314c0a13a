// commands: everything the `kestrel` program does, as library functions.
// The executable (src/cli/main.cpp) only parses arguments and calls these
// (and cmd_run_program, src/cli/run_program.h, for the live view).
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

#include "harness/drive/run_scenario.h"
#include "harness/link/remote_fsw.h"

namespace harness {

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

// --live and its options (docs/live.md): the live view the run command
// serves while the run goes (cmd_run_program, src/cli/run_program.h).
struct LiveRequest {
  bool on = false;                  // serve the live view
  bool paused = false;              // start paused
  int port = 0;                     // TCP port (0: a free one, printed)
  std::string host = "127.0.0.1";   // address to bind
  double linger = 10.0;             // [s] the page stays served after the run
  double wait = -1.0;               // [s] wait after tick 0 for a page; < 0: 60 s unpaced, 0 paced (docs/live.md)
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
  const std::atomic<int>* stop = nullptr;  // set to a signal number to stop the run (stop_on_signals())
  std::string fsw;                  // "" in process; udp:HOST:PORT / serial:DEVICE:BAUD / pil:TARGET (docs/hwil.md)
  // The link's options as given (--on-missing, --link-*, --reply-timeout,
  // --pil-bin, --pil-emulator; fault probabilities in [0, 1]), passed to the
  // run unchanged; LinkOptions::for_run applies a run's defaulting rules
  // (on_missing: fail in lockstep, hold with faults or --realtime).
  LinkOptions link;
  LiveRequest live;                 // --live (cmd_run_program)
  RunControl* control = nullptr;    // steers the run while it goes: the live view (docs/live.md)
  double checkpoint_every = 0.0;    // [s] > 0: --checkpoint-every (docs/checkpoint.md)
  std::string resume;               // --resume DIR: continue the killed run of these results
};

// Writes the FSW configuration image of a scenario (docs/hwil.md).
int cmd_fsw_config(const std::string& scenario, const std::vector<std::string>& sets, const std::string& out_file,
                   std::ostream& out, std::ostream& err);

// The run's options of a run command and its loaded scenario: results
// folder (default runs/<name>), overrides, pacing, the FSW link and its
// options (c.link, as given), the run control.
RunOptions run_options_of(const RunCommand& c, const Scenario& sc, const std::vector<Override>& overrides);
int cmd_run(const RunCommand& c, std::ostream& out, std::ostream& err);

// SIGINT/SIGTERM during a run or a campaign: installs handlers that set the
// returned flag to the signal number (the run stops at the next tick
// boundary and writes what it has); SA_RESETHAND: a second signal ends the
// process at once.
const std::atomic<int>* stop_on_signals();

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
  std::string resume;                // --resume DIR: continue the interrupted campaign in DIR
  std::string from;                  // --from CHECKPOINT: every run starts from its state
  bool progress = false;
  const std::atomic<int>* stop = nullptr;
};
int cmd_mc(const McCommand& c, std::ostream& out, std::ostream& err);
// `kestrel mc` as the program runs it: the scenario is required, --shard
// "i/N" is checked and set, a progress bar on a terminal, stop on signals.
int cmd_mc_program(McCommand c, const std::string& shard, std::ostream& out, std::ostream& err);
// Joins the shard folders of one campaign into out_dir.
int cmd_mc_merge(const std::string& out_dir, const std::vector<std::string>& shards, bool force, std::ostream& out,
                 std::ostream& err);
int cmd_validate(const std::string& scenario, const std::vector<std::string>& sets, std::ostream& out,
                 std::ostream& err);
int cmd_list(const std::string& dir, std::ostream& out, std::ostream& err);
// `kestrel bench`: the reference cases (only those named in `only`, when
// it is not empty: s1-0.01, s1-0.1, s1-substeps, s2, or an extra case); exit 2
// on an unknown name.
struct BenchOptions {
  std::vector<std::string> only;  // --case
  bool callgrind = false;         // --callgrind: instructions per tick when valgrind is on PATH
  bool once = false;              // --once: one plain run of each case, nothing printed (callgrind's child)
  uint64_t mc_runs = 0;           // --mc-runs: the Monte Carlo cases' runs (0: their own, 20)
  double mc_duration = 0.0;       // --mc-duration [s]: their runs' duration (0: their own)
  std::string mc_part = "both";   // --mc-part: both, campaign or bare (one half, to be timed as a process)
  std::string valgrind;           // set by cmd_bench
};
int cmd_bench(const std::string& dir, BenchOptions o, std::ostream& out, std::ostream& err);

// Directory of the shipped scenarios: $KESTREL_SCENARIO_DIR, else the
// installed ones (share/kestrel/scenarios beside the installed program's
// bin/), else the source tree's scenarios/ (compiled in: a build tree), else
// ./scenarios.
std::string scenario_dir();
// A scenario argument as given when it names a file (or holds a '/'), else
// the shipped scenario of that name in scenario_dir() (with or without
// .yaml): `kestrel run s1_sun_pointing`.
std::string resolve_scenario(const std::string& arg);
// `kestrel schema`: the scenario file's JSON Schema, to `out` or out_file.
int cmd_schema(const std::string& out_file, std::ostream& out, std::ostream& err);

}  // namespace harness

#endif  // HARNESS_COMMANDS_H
