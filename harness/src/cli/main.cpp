// kestrel: command-line front end.  Parses arguments only; every command is a
// harness library function (harness/commands.h, exit codes there), `run`
// through cmd_run_program (cli/run_program.h: the live view and signals).
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/run_program.h"
#include "harness/cli/commands.h"
#include "harness/core/pacer.h"
#include "harness/core/scenario_types.h"
#include "harness/core/run.h"
#include "scenario/scenario_limits.h"  // kMaxMcRuns

namespace {

// --fsw, --pil-*, --on-missing, --link-*: straight into the run command's
// link options (RunCommand::link); the fault flags are in percent.
void add_link_flags(CLI::App* run, harness::RunCommand& rc)
{
  harness::LinkOptions& l = rc.link;
  run->add_option("--fsw", rc.fsw,
                  "run the FSW behind the link: udp:HOST:PORT or serial:DEVICE:BAUD (docs/hwil.md), the "
                  "KESTREL_ACS cFS application through ci_lab and to_lab: cfs:HOST[:PORT[:TLMPORT]] (ci_lab's "
                  "port, default 1234; to_lab's telemetry to TLMPORT here, default 1235; docs/hwil.md), or on an "
                  "emulated processor: pil:aarch64-linux, pil:armhf-linux, pil:cortex-m4f, pil:cortex-m4f-float "
                  "(docs/pil.md)");
  run->add_option("--pil-bin", l.pil_bin, "with --fsw pil:TARGET: the cross-built FSW program to run (default: this "
                                          "build's)");
  run->add_option("--pil-emulator", l.pil_emulator,
                  "with --fsw pil:TARGET: the emulator command, words separated by spaces (default: the target's QEMU)");
  run->add_option_function<std::string>(
         "--on-missing",
         [&l](const std::string& v) {
           l.on_missing = v == "zero" ? harness::LinkOptions::Missing::kZero : harness::LinkOptions::Missing::kHold;
           l.on_missing_set = true;
         },
         "a cycle without a reply: hold (last command) or zero (safe output)")
      ->check(CLI::IsMember({"hold", "zero"}));
  run->add_option("--link-timeout", l.timeout_s, "lockstep: fail when a reply takes longer [s] (default 10)")
      ->check(CLI::PositiveNumber);
  run->add_option("--reply-timeout", l.reply_timeout_s, "hold/zero: give a cycle up after [s] (default 0.5)")
      ->check(CLI::PositiveNumber);
  run->add_option("--link-key", l.key_file,
                  "UDP and PIL Linux targets: authenticate every packet with the shared key in FILE (hex, mode 0600; "
                  "kestrel-fsw --key FILE at the other end)");
  run->add_option("--link-retransmit", l.retransmit_s,
                  "lockstep over UDP: send the sensor packet again after [s] without a reply (default 0.25)")
      ->check(CLI::Range(0.001, 60.0));
  run->add_option("--link-retransmits", l.retransmits,
                  "lockstep over UDP: at most this many retransmissions a cycle (default 8, 0: none)")
      ->check(CLI::Range(0, 1000));
  const auto percent = [run](const char* name, double& p, const char* help) {
    run->add_option_function<double>(name, [&p](double v) { p = v / 100.0; }, help)->check(CLI::Range(0.0, 100.0));
  };
  percent("--link-loss", l.loss, "fault: sensor packets lost [%]");
  percent("--link-corrupt", l.corrupt, "fault: sensor packets with 1-3 flipped bits [%]");
  percent("--link-duplicate", l.duplicate, "fault: sensor packets sent twice [%]");
  percent("--link-reorder", l.reorder, "fault: sensor packets swapped with the next [%]");
  percent("--link-delay", l.delay, "fault: sensor packets sent --link-delay-cycles late [%]");
  run->add_option("--link-delay-cycles", l.delay_cycles, "FSW cycles a delayed packet is late (default 2)")
      ->check(CLI::Range(1, 1000));
  run->add_option("--link-seed", l.seed, "seed of the fault injector (default 1)");
}

void add_live_flags(CLI::App* run, harness::LiveRequest& live)
{
  run->add_flag("--live", live.on, "serve the live view while the run goes (docs/live.md): prints its URL");
  run->add_option("--port", live.port, "with --live: TCP port (default 0: a free one, printed)")
      ->check(CLI::Range(0, 65535));
  run->add_option("--live-host", live.host, "with --live: address to bind (default 127.0.0.1)");
  run->add_option("--live-linger", live.linger, "with --live: seconds the page stays served after the run (default 10)")
      ->check(CLI::Range(0.0, 86400.0));
  run->add_flag("--live-paused", live.paused, "with --live: start paused (resume from the page)");
  run->add_option("--live-wait", live.wait,
                  "with --live: after t = 0 wait this long at most for a page to connect (default 60 s for an "
                  "unpaced run, 0 with --realtime; 0: do not wait)")
      ->check(CLI::Range(0.0, 86400.0));
}

CLI::App* add_run(CLI::App& app, harness::RunCommand& rc)
{
  auto* run = app.add_subcommand("run", "run a scenario (YAML or a run manifest.json) and write its results");
  run->add_option("scenario", rc.scenario,
                  "scenario file or manifest.json (with --resume: optional, must be the checkpoint's scenario)");
  run->add_option("-o,--output", rc.out_dir, "results directory (default runs/<scenario name>)");
  run->add_option("--set", rc.sets, "override a scenario key: key.path=value (repeatable)");
  run->add_flag("--csv", rc.csv, "also write telemetry.csv");
  run->add_flag("--force", rc.force, "replace an existing results folder whole");
  run->add_flag("--realtime", rc.realtime, "pace the ticks to the wall clock (absolute deadlines)");
  run->add_option("--rt-scale", rc.rt_scale, "with --realtime: multiple of real time in [1e-6, 1e6] (default 1)")
      ->check(CLI::Validator(
          [](std::string& v) {
            double x = 0.0;
            try {
              size_t used = 0;
              x = std::stod(v, &used);
              if (used != v.size()) return std::string("not a number");
            } catch (const std::exception&) {
              return std::string("not a number");
            }
            const std::string why = harness::Pacer::check_scale(x);
            return why;  // CLI11 puts "--rt-scale: " before it
          },
          "SCALE"));
  run->add_option("--checkpoint-every", rc.checkpoint_every,
                  "write a checkpoint every T simulated seconds (rounded to whole ticks) so that --resume can "
                  "continue the run if it is killed; not with --fsw or --live (docs/checkpoint.md)")
      ->type_name("T")
      ->check(CLI::PositiveNumber);
  run->add_option("--resume", rc.resume,
                  "continue the killed run of the results folder DIR (started with --checkpoint-every) from its "
                  "last checkpoint; the scenario, --set lines and interval are the checkpoint's")
      ->type_name("DIR")
      ->excludes("--checkpoint-every");
  add_link_flags(run, rc);
  add_live_flags(run, rc.live);
  return run;
}

// The arguments of a command that takes a scenario and --set (fsw-config, validate).
struct ScenarioArgs {
  std::string path, out_file;
  std::vector<std::string> sets;
};

CLI::App* add_fsw_config(CLI::App& app, ScenarioArgs& a)
{
  auto* fcfg = app.add_subcommand("fsw-config", "write the FSW configuration image of a scenario (for kestrel-fsw)");
  fcfg->add_option("scenario", a.path, "scenario file or manifest.json")->required();
  fcfg->add_option("-o,--output", a.out_file, "image file")->required();
  fcfg->add_option("--set", a.sets, "override a scenario key: key.path=value (repeatable)");
  return fcfg;
}

CLI::App* add_validate(CLI::App& app, ScenarioArgs& a)
{
  auto* val = app.add_subcommand("validate", "check a scenario without running it");
  val->add_option("scenario", a.path, "scenario file or manifest.json")->required();
  val->add_option("--set", a.sets, "override a scenario key: key.path=value (repeatable)");
  return val;
}

CLI::App* add_mc(CLI::App& app, harness::McCommand& mc, std::string& shard)
{
  auto* mcc = app.add_subcommand("mc", "run a Monte Carlo campaign of a scenario's monte_carlo section (docs/monte-carlo.md)");
  mcc->add_option("scenario", mc.scenario, "scenario file with a monte_carlo section, or its manifest");
  mcc->add_option("--runs", mc.runs, "number of runs (default monte_carlo.runs)")->check(CLI::Range(uint64_t(1), harness::kMaxMcRuns));
  mcc->add_option("--seed", mc.seed, "master seed, an integer in [0, 2^64 - 1] (default monte_carlo.seed)")
      ->check(CLI::Validator(
          [](std::string& v) {
            // as the YAML key: digits only (CLI11 would take -1 as 2^64 - 1
            // and saturate 2^64), at most 2^64 - 1
            bool ok = !v.empty() && v.size() <= 20 && v.find_first_not_of("0123456789") == std::string::npos;
            if (ok) {
              try {
                (void)std::stoull(v);
              } catch (const std::exception&) {
                ok = false;
              }
            }
            return ok ? std::string()
                      : "expected an integer in [0, 2^64 - 1] (as monte_carlo.seed), got '" +
                            harness::escape_bytes(v) + "'";
          },
          "SEED"));
  mcc->add_option("-j,--jobs", mc.jobs, "threads (default 1)")->check(CLI::Range(1u, 1024u));
  mcc->add_option("-o,--output", mc.out_dir, "campaign folder (default runs/<name>_mc)");
  mcc->add_option("--set", mc.sets, "override a key of the nominal scenario: key.path=value (repeatable)");
  // an empty list selects no run: refused rather than taken for "every run"
  mcc->add_option("--only", mc.only, "rerun just these runs: 17,42,100-120")
      ->check(CLI::Validator(
          [](std::string& v) {
            return v.empty() ? std::string("an empty list selects no run: give run indices (17,42,100-120), or leave "
                                           "--only out to run every run")
                             : std::string();
          },
          "RUNS"));
  mcc->add_option("--shard", shard, "run slice i of N (i/N, 0 <= i < N) for batch arrays; join with mc merge");
  mcc->add_option("--slurm", mc.slurm_tasks, "write Slurm array scripts for this many shards to <output>.slurm/")
      ->check(CLI::Range(1u, 100000u));
  mcc->add_flag("--force", mc.force, "replace an existing campaign folder whole");
  mcc->add_option("--resume", mc.resume,
                  "continue the interrupted (killed or stopped) campaign in this folder: only its missing runs");
  mcc->add_option("--from", mc.from,
                  "start every run from this checkpoint of the nominal scenario; only events after it, keys settable "
                  "during a run and the sensor noise may be dispersed (docs/checkpoint.md, \"Branching a campaign\")");
  return mcc;
}

struct MergeArgs {
  std::string out;
  std::vector<std::string> in;
  bool force = false;
};

CLI::App* add_merge(CLI::App* mcc, MergeArgs& m)
{
  auto* merge = mcc->add_subcommand("merge", "join the shard folders of one campaign");
  merge->add_option("-o,--output", m.out, "campaign folder to write")->required();
  merge->add_option("shards", m.in, "shard folders")->required();
  merge->add_flag("--force", m.force, "replace an existing campaign folder whole");
  return merge;
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Kestrel closed-loop harness"};
  app.set_version_flag("--version", std::string(harness::version()));
  app.require_subcommand(1);
  harness::RunCommand rc;
  auto* run = add_run(app, rc);
  ScenarioArgs fa, va;
  auto* fcfg = add_fsw_config(app, fa);
  auto* val = add_validate(app, va);
  harness::McCommand mc;
  std::string shard;
  auto* mcc = add_mc(app, mc, shard);
  MergeArgs ma;
  auto* merge = add_merge(mcc, ma);
  auto* list = app.add_subcommand("list", "list the shipped scenarios (run one by its name: kestrel run NAME)");
  auto* schema = app.add_subcommand("schema", "print the scenario file's JSON Schema, for editors (docs/scenario-schema.md)");
  std::string schema_out;
  schema->add_option("-o,--output", schema_out, "write it to this file instead");
  auto* bench = app.add_subcommand("bench", "print real-time factors of the reference scenarios");
  harness::BenchOptions bo;
  bench->add_option("--case", bo.only, "only these cases: s1-0.01, s1-0.1, s1-substeps, s2; extra (only when named): s1-fsw-every-step, s1-leo-env, s1-leo-off, s3-env, s3-env-balanced, s1-mc, s3-mc (repeatable)");
  bench->add_option("--mc-runs", bo.mc_runs, "runs of the Monte Carlo cases (default 20)")->check(CLI::Range(1, 100000));
  bench->add_option("--mc-duration", bo.mc_duration, "[s] duration of the Monte Carlo cases' runs (default: s1-mc 600, s3-mc 300)")
      ->check(CLI::Range(1.0, 1e6));
  bench->add_option("--mc-part", bo.mc_part, "the Monte Carlo cases' halves: both (default, the overhead printed), campaign or bare (only that half: time two processes against each other)")
      ->check(CLI::IsMember({"both", "campaign", "bare"}));
  bench->add_flag("--callgrind", bo.callgrind, "also count instructions per tick under valgrind's callgrind (skipped without valgrind)");
  bench->add_flag("--once", bo.once, "run each case once, print nothing (what --callgrind counts)")->group("");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc_cli = app.exit(e);
    return rc_cli == 0 ? harness::kExitOk : harness::kExitUsage;
  }
  // a shipped scenario by its name (kestrel list)
  for (std::string* a : {&rc.scenario, &mc.scenario, &va.path, &fa.path}) *a = harness::resolve_scenario(*a);
  if (*run) return harness::cmd_run_program(rc, std::cout, std::cerr);
  if (*merge) return harness::cmd_mc_merge(ma.out, ma.in, ma.force, std::cout, std::cerr);
  if (*mcc) return harness::cmd_mc_program(mc, shard, std::cout, std::cerr);
  if (*val) return harness::cmd_validate(va.path, va.sets, std::cout, std::cerr);
  if (*fcfg) return harness::cmd_fsw_config(fa.path, fa.sets, fa.out_file, std::cout, std::cerr);
  if (*list) return harness::cmd_list(harness::scenario_dir(), std::cout, std::cerr);
  if (*schema) return harness::cmd_schema(schema_out, std::cout, std::cerr);
  if (*bench) return harness::cmd_bench(harness::scenario_dir(), bo, std::cout, std::cerr);
  return harness::kExitUsage;
}
