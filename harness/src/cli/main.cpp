// kestrel: command-line front end.  Parses arguments only; every command is a
// harness library function (harness/commands.h, exit codes there).
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <optional>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "harness/cli/commands.h"
#include "harness/core/run.h"
#ifdef KESTREL_HAVE_LIVE
#include "live/live_server.h"
#endif

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
  run->add_option("--fsw", rc.fsw,
                  "run the FSW behind the link: udp:HOST:PORT or serial:DEVICE:BAUD (docs/hwil.md), or on an "
                  "emulated processor: pil:aarch64-linux, pil:armhf-linux, pil:cortex-m4f, pil:cortex-m4f-float "
                  "(docs/pil.md)");
  run->add_option("--pil-bin", rc.pil_bin, "with --fsw pil:TARGET: the cross-built FSW program to run (default: this "
                                           "build's)");
  run->add_option("--pil-emulator", rc.pil_emulator,
                  "with --fsw pil:TARGET: the emulator command, words separated by spaces (default: the target's QEMU)");
  run->add_option("--on-missing", rc.on_missing, "a cycle without a reply: hold (last command) or zero (safe output)")
      ->check(CLI::IsMember({"hold", "zero"}));
  run->add_option("--link-timeout", rc.link_timeout, "lockstep: fail when a reply takes longer [s] (default 10)")
      ->check(CLI::PositiveNumber);
  run->add_option("--reply-timeout", rc.reply_timeout, "hold/zero: give a cycle up after [s] (default 0.5)")
      ->check(CLI::PositiveNumber);
  run->add_option("--link-loss", rc.loss, "fault: sensor packets lost [%]")->check(CLI::Range(0.0, 100.0));
  run->add_option("--link-corrupt", rc.corrupt, "fault: sensor packets with 1-3 flipped bits [%]")
      ->check(CLI::Range(0.0, 100.0));
  run->add_option("--link-duplicate", rc.duplicate, "fault: sensor packets sent twice [%]")
      ->check(CLI::Range(0.0, 100.0));
  run->add_option("--link-reorder", rc.reorder, "fault: sensor packets swapped with the next [%]")
      ->check(CLI::Range(0.0, 100.0));
  run->add_option("--link-delay", rc.delay, "fault: sensor packets sent --link-delay-cycles late [%]")
      ->check(CLI::Range(0.0, 100.0));
  run->add_option("--link-delay-cycles", rc.delay_cycles, "FSW cycles a delayed packet is late (default 2)")
      ->check(CLI::Range(1, 1000));
  run->add_option("--link-seed", rc.link_seed, "seed of the fault injector (default 1)");
  bool live_on = false, live_paused = false;
  int live_port = 0;
  std::string live_host = "127.0.0.1";
  double live_linger = 10.0;
  run->add_flag("--live", live_on, "serve the live view while the run goes (docs/live.md): prints its URL");
  run->add_option("--port", live_port, "with --live: TCP port (default 0: a free one, printed)")
      ->check(CLI::Range(0, 65535));
  run->add_option("--live-host", live_host, "with --live: address to bind (default 127.0.0.1)");
  run->add_option("--live-linger", live_linger, "with --live: seconds the page stays served after the run (default 10)")
      ->check(CLI::Range(0.0, 86400.0));
  run->add_flag("--live-paused", live_paused, "with --live: start paused (resume from the page)");

  std::string cpath, cout_file;
  std::vector<std::string> csets;
  auto* fcfg = app.add_subcommand("fsw-config", "write the FSW configuration image of a scenario (for kestrel-fsw)");
  fcfg->add_option("scenario", cpath, "scenario file or manifest.json")->required();
  fcfg->add_option("-o,--output", cout_file, "image file")->required();
  fcfg->add_option("--set", csets, "override a scenario key: key.path=value (repeatable)");

  std::string vpath;
  std::vector<std::string> vsets;
  auto* val = app.add_subcommand("validate", "check a scenario without running it");
  val->add_option("scenario", vpath, "scenario file or manifest.json")->required();
  val->add_option("--set", vsets, "override a scenario key: key.path=value (repeatable)");

  harness::McCommand mc;
  std::string shard;
  auto* mcc = app.add_subcommand("mc", "run a Monte Carlo campaign of a scenario's monte_carlo section (docs/monte-carlo.md)");
  mcc->add_option("scenario", mc.scenario, "scenario file with a monte_carlo section, or its manifest");
  mcc->add_option("--runs", mc.runs, "number of runs (default monte_carlo.runs)")->check(CLI::Range(1ULL, 10000000ULL));
  mcc->add_option("--seed", mc.seed, "master seed (default monte_carlo.seed)");
  mcc->add_option("-j,--jobs", mc.jobs, "threads (default 1)")->check(CLI::Range(1u, 1024u));
  mcc->add_option("-o,--output", mc.out_dir, "campaign folder (default runs/<name>_mc)");
  mcc->add_option("--set", mc.sets, "override a key of the nominal scenario: key.path=value (repeatable)");
  mcc->add_option("--only", mc.only, "rerun just these runs: 17,42,100-120");
  mcc->add_option("--shard", shard, "run slice i of N (i/N, 0 <= i < N) for batch arrays; join with mc merge");
  mcc->add_option("--slurm", mc.slurm_tasks, "write Slurm array scripts for this many shards to <output>.slurm/")
      ->check(CLI::Range(1u, 100000u));
  mcc->add_flag("--force", mc.force, "replace an existing campaign folder whole");
  std::string merge_out;
  std::vector<std::string> merge_in;
  bool merge_force = false;
  auto* merge = mcc->add_subcommand("merge", "join the shard folders of one campaign");
  merge->add_option("-o,--output", merge_out, "campaign folder to write")->required();
  merge->add_option("shards", merge_in, "shard folders")->required();
  merge->add_flag("--force", merge_force, "replace an existing campaign folder whole");

  auto* list = app.add_subcommand("list", "list the shipped scenarios");
  auto* bench = app.add_subcommand("bench", "print real-time factors of the reference scenarios");
  std::vector<std::string> bench_cases;
  bench->add_option("--case", bench_cases, "only these cases: s1-0.01, s1-0.1, s1-substeps, s2 (repeatable)");

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
#ifdef KESTREL_HAVE_LIVE
    std::unique_ptr<harness::LiveServer> live;
    if (live_on) {
      harness::LiveOptions lo;
      lo.host = live_host;
      lo.port = live_port;
      lo.start_paused = live_paused;
      try {
        live = std::make_unique<harness::LiveServer>(lo);
      } catch (const std::exception& e) {
        std::cerr << "kestrel: " << e.what() << "\n";
        return harness::kExitUsage;
      }
      std::cout << "live view: " << live->url() << std::endl;
      rc.control = live.get();
    }
    const int code = harness::cmd_run(rc, std::cout, std::cerr);
    if (live) {
      const harness::LiveCounters n = live->counters();
      std::cout << "live view: " << n.published << " frames published, " << n.dropped_busy + n.dropped_unread
                << " dropped (" << n.dropped_busy << " while a page read, " << n.dropped_unread << " unread); "
                << n.commands_applied << " commands applied, " << n.commands_refused << " refused; paused "
                << n.paused_s << " s of wall time" << std::endl;
      // the page shows the end and links the report (not when nothing ran, nor after Ctrl-C)
      if (live_linger > 0 && g_stop.load() == 0 && (code == harness::kExitOk || code == harness::kExitRunFailed)) {
        std::cout << "live view: the page stays at " << live->url() << " for " << live_linger
                  << " s (Ctrl-C ends it)" << std::endl;
        live->linger(live_linger, &g_stop);
      }
    }
    return code;
#else
    if (live_on) {
      std::cerr << "kestrel: this build has no live view (cpp-httplib was missing at build time)\n";
      return harness::kExitUsage;
    }
    return harness::cmd_run(rc, std::cout, std::cerr);
#endif
  }
  if (*merge) return harness::cmd_mc_merge(merge_out, merge_in, merge_force, std::cout, std::cerr);
  if (*mcc) {
    if (mc.scenario.empty()) {
      std::cerr << "kestrel mc: a scenario file is required (or: kestrel mc merge -o DIR SHARD...)\n";
      return harness::kExitUsage;
    }
    if (!shard.empty()) {
      unsigned long long i = 0, n = 0;
      char extra = 0;
      if (std::sscanf(shard.c_str(), "%llu/%llu%c", &i, &n, &extra) != 2 || n < 1 || i >= n || n > 100000) {
        std::cerr << "kestrel mc: --shard expects i/N with 0 <= i < N <= 100000, got '" << shard << "'\n";
        return harness::kExitUsage;
      }
      mc.shard_index = static_cast<uint32_t>(i);
      mc.shard_count = static_cast<uint32_t>(n);
    }
    mc.progress = isatty(STDERR_FILENO) != 0;
    mc.stop = &g_stop;
    install_stop_handlers();
    return harness::cmd_mc(mc, std::cout, std::cerr);
  }
  if (*val) return harness::cmd_validate(vpath, vsets, std::cout, std::cerr);
  if (*fcfg) return harness::cmd_fsw_config(cpath, csets, cout_file, std::cout, std::cerr);
  if (*list) return harness::cmd_list(harness::scenario_dir(), std::cout, std::cerr);
  if (*bench) return harness::cmd_bench(harness::scenario_dir(), bench_cases, std::cout, std::cerr);
  return harness::kExitUsage;
}
