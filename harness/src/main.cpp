// kestrel: command-line front end.  Parses arguments only; every command is a
// harness library function (harness/commands.h, exit codes there).
#include <unistd.h>

#include <iostream>

#include <CLI/CLI.hpp>

#include "harness/commands.h"
#include "harness/run.h"

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
    return harness::cmd_run(rc, std::cout, std::cerr);
  }
  if (*val) return harness::cmd_validate(vpath, vsets, std::cout, std::cerr);
  if (*list) return harness::cmd_list(harness::scenario_dir(), std::cout, std::cerr);
  if (*bench) return harness::cmd_bench(harness::scenario_dir(), std::cout, std::cerr);
  return harness::kExitUsage;
}
