// run_scenario.cpp: a whole run into a results directory, streamed.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "harness/drive/run_scenario.h"
#include "harness/link/pil.h"
#include "harness/output/results_dir.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

namespace fs = std::filesystem;

namespace {

// A generous estimate of a run's output [bytes]: the HDF5 file uncompressed
// (deflate only makes it smaller), the CSV at ~25 characters a value, the
// report's bounded series twice (JSON and the HTML page), and 1 MiB of small
// files.
uint64_t output_estimate(const Run& run, const Scenario& sc)
{
  const uint64_t rows = run.recorder().capacity();
  const uint64_t cols = run.recorder().num_columns();
  uint64_t b = (1u << 20);
  if (sc.outputs.hdf5) b += rows * (cols + 1) * 8;
  if (sc.outputs.csv) b += rows * cols * 25;
  if (sc.outputs.report_data) {
    const uint64_t shown = std::min<uint64_t>(rows, 2 * ReportSink::kReportBuckets) * cols +
                           std::min<uint64_t>(rows, ReportSink::kSpectrumRows) * 5;
    b += 2 * shown * 25;
  }
  return b;
}

std::string signal_name(int s)
{
  switch (s) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "signal " + std::to_string(s);
  }
}

// The endpoint behind the link.  With real-time pacing a cycle waits at most
// one FSW period of wall time and, unless told otherwise, holds the last
// command when its reply is late.
std::unique_ptr<FswEndpoint> make_remote_fsw(const Scenario& sc, const RunOptions& opt, RemoteFsw*& remote,
                                             std::function<double()> time_left)
{
  LinkOptions lo = opt.link;
  if (opt.realtime_scale > 0) {
    if (!lo.on_missing_set) lo.on_missing = LinkOptions::Missing::kHold;
    lo.on_missing_set = true;
    lo.reply_timeout_s = sc.rates.dt * sc.rates.fsw_divisor / opt.realtime_scale;
    lo.time_left = std::move(time_left);
  }
  const FswAcsConfig fcfg = fsw_acs_config_of(sc);
  auto r = std::make_unique<RemoteFsw>(open_fsw_transport(opt.fsw_link, fcfg, lo), fcfg, lo);
  remote = r.get();
  return r;
}

}  // namespace

RunResult run_scenario(const Scenario& sc, const RunOptions& opt)
{
  RunResult res;
  const bool files = !opt.out_dir.empty();
  // lock, refuse or replace, working folder: before anything is simulated
  std::optional<ResultsDir> rdir;
  if (files) rdir.emplace(opt.out_dir, opt.force);
  RunConfig cfg;
  cfg.keep_in_memory = false;  // streamed: memory does not grow with the duration
  RemoteFsw* remote = nullptr;
  // paced: the FSW link waits for a reply at most until the deadline of the
  // tick after the one being computed (pacer below, created after the run)
  std::optional<Pacer> pacer;
  uint64_t pacing_tick = 0;
  if (!opt.fsw_link.empty())
    cfg.fsw = make_remote_fsw(sc, opt, remote, [&pacer, &pacing_tick] {
      return pacer ? pacer->seconds_to(pacing_tick + 1) : std::numeric_limits<double>::infinity();
    });
  cfg.accept_events = opt.control != nullptr;  // the live view's commands are events
  Run run(sc, std::move(cfg));
  if (rdir) rdir->require_free_space(output_estimate(run, sc));
  const fs::path dir = files ? rdir->work() : fs::path();
  const std::string manifest = files ? manifest_text(sc, opt.overrides) : std::string();
  std::vector<std::string> written;  // names in the results folder, in order
  if (files) {
    // the input record first: a run killed outright leaves it in the working folder
    write_text((dir / "manifest.json").string(), manifest);
    written.push_back("manifest.json");
  }
  std::optional<Hdf5Sink> h5;
  std::optional<CsvSink> csv;
  std::optional<ReportSink> report;
  if (files && sc.outputs.hdf5) {
    h5.emplace((dir / "results.h5").string(), run.scenario(), manifest);  // with the events added while running
    h5->set_events(&run.events_applied());
    run.add_sink(*h5);
  }
  if (files && sc.outputs.csv) {
    csv.emplace((dir / "telemetry.csv").string());
    run.add_sink(*csv);
  }
  if (files && sc.outputs.report_data) {
    report.emplace();
    run.add_sink(*report);
  }
  for (RecordSink* s : opt.extra_sinks) run.add_sink(*s);
  // chunks of at most 1000 ticks: a stop request is seen within milliseconds
  const uint64_t total = run.total_ticks();
  const uint64_t chunk = std::clamp<uint64_t>(total / 200, 1, 1000);
  uint64_t notice_every = 1;  // paced: ticks per ~10 s of wall time (one notice at most)
  auto pace_at = [&](double scale) {
    if (!pacer) {
      pacer.emplace(sc.tick_ns(), scale);
      const std::string w = pacer->request_realtime();
      if (!w.empty() && opt.notice) opt.notice(w);
    } else {
      pacer->restart(scale);
    }
    notice_every = std::max<uint64_t>(1, static_cast<uint64_t>(1e10 * scale / static_cast<double>(sc.tick_ns())));
  };
  if (opt.realtime_scale > 0.0) pace_at(opt.realtime_scale);
  if (opt.control) opt.control->started(run, opt.realtime_scale, opt.stop);
  const auto t0 = std::chrono::steady_clock::now();
  while (!run.done()) {
    if (opt.stop && opt.stop->load() != 0) {
      res.stopped_by_signal = opt.stop->load();
      break;
    }
    uint64_t limit = chunk;
    if (opt.control) {  // commands enter here, at a tick boundary; a pause waits here
      double pace = 0.0;
      limit = std::min(chunk, opt.control->boundary(run, pace));
      if (pace > 0.0) pace_at(pace);
      if (opt.stop && opt.stop->load() != 0) continue;
    }
    if (pacer) {  // one tick at a time, each at its deadline
      const uint64_t k = run.tick();
      pacer->wait_for(k);
      pacing_tick = k;
      if (!run.step_ticks(1)) break;
      pacer->done(k);
      if ((k + 1) % notice_every == 0) {
        const uint64_t late = pacer->take_new_overruns();
        if (late > 0 && opt.notice)
          opt.notice("cannot keep up: " + std::to_string(late) + " of the last " + std::to_string(notice_every) +
                     " ticks overran their deadline");
      }
      if (opt.progress && (k + 1) % chunk == 0) opt.progress(static_cast<double>(run.tick()) / static_cast<double>(total));
      continue;
    }
    if (!run.step_ticks(limit)) break;
    if (opt.progress) opt.progress(static_cast<double>(run.tick()) / static_cast<double>(total));
  }
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (pacer) {
    res.paced = true;
    res.pacing = pacer->stats();
  }
  res.ticks = run.tick();
  res.sim_seconds = sc.duration;
  res.failure = run.failure();
  res.ok = res.failure.empty() && res.stopped_by_signal == 0;
  // Results are written also for a failed or interrupted run (never lose
  // data): the rows recorded up to there are in the files, marked incomplete.
  run.finish();
  if (remote != nullptr) {
    res.linked = true;
    res.link = remote->counters();
  }
  res.final_pointing_error_deg = run.final_pointing_error_deg();
  res.max_jitter_step = run.max_jitter_step();
  RunStatus& st = res.status;
  st.complete = res.ok && run.done();
  st.ticks = run.tick();
  st.t_reached = run.recorder().rows() > 0 ? run.recorder().last_row()[0] : 0.0;
  st.stopped_by = res.stopped_by_signal ? signal_name(res.stopped_by_signal) : res.failure;
  st.events = run.events_applied();
  if (!files) {
    if (opt.control) opt.control->ended(run, res);
    return res;
  }
  if (h5) written.push_back("results.h5");
  if (csv) written.push_back("telemetry.csv");
  if (report) {
    const std::string data = report_data_text(run, *report, &st, res.paced ? &res.pacing : nullptr);
    write_text((dir / "report_data.json").string(), data);
    written.push_back("report_data.json");
#ifdef KESTREL_HAVE_REPORT
    try {
      report::write_html(data, (dir / "report.html").string());
    } catch (const std::exception& e) {
      throw OutputError(e.what());
    }
    written.push_back("report.html");
#endif
  }
  write_text((dir / "dataflow.dot").string(), run.dataflow().to_dot(sc.name));
  written.push_back("dataflow.dot");
  std::ostringstream health;
  for (const std::string& l : run.fsw_health_lines()) health << l << "\n";
  write_text((dir / "fsw_health.txt").string(), health.str());
  written.push_back("fsw_health.txt");
  std::ostringstream summ;
  summ << std::setprecision(10);
  if (!st.complete)
    summ << "# INCOMPLETE: stopped" << (st.stopped_by.empty() ? "" : " (" + st.stopped_by + ")") << " at t = "
         << st.t_reached << " s of " << sc.duration << " s\n";
  summ << "complete = " << (st.complete ? 1 : 0) << "     # 1: the run reached its duration\n";
  summ << "t_reached = " << st.t_reached << " s    # time of the last recorded row\n";
  for (const SummaryItem& it : run.summary())
    summ << it.key << " = " << it.value << " " << it.unit << "    # " << it.what << "\n";
  if (res.paced) {
    const PacingStats& p = res.pacing;
    summ << "rt_scale = " << p.scale << "     # paced at this multiple of real time\n";
    summ << "rt_lateness_p50 = " << p.lateness_p50_s << " s    # tick wake-up after its deadline, median\n";
    summ << "rt_lateness_p99 = " << p.lateness_p99_s << " s    # 99th percentile\n";
    summ << "rt_lateness_max = " << p.lateness_max_s << " s    # maximum\n";
    summ << "rt_overruns = " << p.overruns << "     # ticks whose work ended after the next deadline\n";
    summ << "rt_drift = " << p.drift_s << " s    # last tick's lateness (absolute deadlines: no accumulation)\n";
    summ << "rt_priority = " << (p.realtime_priority ? 1 : 0) << "     # 1: SCHED_FIFO and locked memory\n";
  }
  if (res.linked) {
    const LinkCounters& l = res.link;
    summ << "link_cycles = " << l.cycles << "     # FSW cycles over the link\n";
    summ << "link_sent = " << l.sent << "     # sensor packets sent (duplicates included)\n";
    summ << "link_lost = " << l.lost << "     # dropped by the loss injector\n";
    summ << "link_corrupted = " << l.corrupted << "     # sent with flipped bits\n";
    summ << "link_missing = " << l.missing << "     # cycles without a reply (last command held or zero applied)\n";
    summ << "link_rejected = " << l.rejected << "     # received packets the harness rejected\n";
    summ << "link_fsw_rx_crc = " << l.fsw.rx_crc << "     # FSW end: packets rejected on CRC\n";
    summ << "link_fsw_rx_stale = " << l.fsw.rx_stale << "     # FSW end: duplicate, old or out-of-order sensor packets\n";
    summ << "link_fsw_missed = " << l.fsw.missed << "     # FSW end: control cycles without a sensor packet\n";
  }
  write_text((dir / "summary.txt").string(), summ.str());
  written.push_back("summary.txt");
  // the manifest again, now saying how the run ended
  // (run.scenario(): with the events the live view added, so it replays them)
  write_text((dir / "manifest.json").string(), manifest_text(run.scenario(), opt.overrides, &st));
  rdir->commit();
  for (const std::string& n : written) res.files.push_back((rdir->target() / n).string());
  if (opt.control) opt.control->ended(run, res);
  return res;
}

}  // namespace harness
