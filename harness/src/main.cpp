// kestrel: command-line front end.  Parses arguments only; every command is a
// harness library function (harness/commands.h, exit codes there).
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <iostream>

#include <CLI/CLI.hpp>

#include "harness/commands.h"
#include "harness/run.h"

namespace {

// SIGINT/SIGTERM during `run`: the first asks the run to stop at a tick
// boundary and write what it has; the handler is installed with
// SA_RESETHAND, so a second one ends the process at once.
std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "signal handler needs a lock-free flag");

extern "C" void on_stop_signal(int sig)
{
  g_stop.store(sig);
}

void install_stop_handlers()
{
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Kestrel closed-loop harness"};
  app.set_version_flag("--version", std::string(harness::version()));
  app.require_subcommand(1);

  harness::RunCommand rc;
  auto* run = app.add_subcommand("run", "run a scenario (YAML or a run manifest.json) and write its results");
  run->add_option("scenario", rc.scenario, "scenario file or manifest.json")->required();
  run->add_option("-o,--output", rc.out_dir, "results directory (default runs/<scenario name>)");
  run->add_option("--set", rc.sets, "override a scenario key: key.path=value (repeatable)");
  run->add_flag("--csv", rc.csv, "also write telemetry.csv");
  run->add_flag("--force", rc.force, "replace an existing results folder whole");
  run->add_flag("--realtime", rc.realtime, "pace the ticks to the wall clock (absolute deadlines)");
  run->add_option("--rt-scale", rc.rt_scale, "with --realtime: multiple of real time (default 1)")
      ->check(CLI::PositiveNumber);

  std::string vpath;
  std::vector<std::string> vsets;
  auto* val = app.add_subcommand("validate", "check a scenario without running it");
  val->add_option("scenario", vpath, "scenario file or manifest.json")->required();
  val->add_option("--set", vsets, "override a scenario key: key.path=value (repeatable)");

  auto* list = app.add_subcommand("list", "list the shipped scenarios");
  auto* bench = app.add_subcommand("bench", "print real-time factors of the reference scenarios");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc_cli = app.exit(e);
    return rc_cli == 0 ? harness::kExitOk : harness::kExitUsage;
  }
  if (*run) {
    rc.progress = isatty(STDERR_FILENO) != 0;
    rc.stop = &g_stop;
    install_stop_handlers();
    return harness::cmd_run(rc, std::cout, std::cerr);
  }
  if (*val) return harness::cmd_validate(vpath, vsets, std::cout, std::cerr);
  if (*list) return harness::cmd_list(harness::scenario_dir(), std::cout, std::cerr);
  if (*bench) return harness::cmd_bench(harness::scenario_dir(), std::cout, std::cerr);
  return harness::kExitUsage;
}
