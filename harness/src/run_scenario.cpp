// run_scenario.cpp: a whole run into a results directory, streamed.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

#include "harness/outputs.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

namespace fs = std::filesystem;

RunResult run_scenario(const Scenario& sc, const RunOptions& opt)
{
  RunResult res;
  const bool files = !opt.out_dir.empty();
  const fs::path dir(opt.out_dir);
  if (files) {
    std::error_code ec;
    fs::create_directories(opt.out_dir, ec);
    if (ec || !fs::is_directory(opt.out_dir))
      throw OutputError(opt.out_dir + ": cannot create the results directory" + (ec ? ": " + ec.message() : ""));
  }
  RunConfig cfg;
  cfg.keep_in_memory = false;  // streamed: memory does not grow with the duration
  Run run(sc, std::move(cfg));
  const std::string manifest = files ? manifest_text(sc, opt.overrides) : std::string();
  auto put = [&res](const fs::path& p) { res.files.push_back(p.string()); };
  if (files) {
    write_text((dir / "manifest.json").string(), manifest);
    put(dir / "manifest.json");
  }
  std::optional<Hdf5Sink> h5;
  std::optional<CsvSink> csv;
  std::optional<ReportSink> report;
  if (files && sc.outputs.hdf5) {
    h5.emplace((dir / "results.h5").string(), sc, manifest);
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
  const uint64_t total = run.total_ticks();
  const uint64_t chunk = std::max<uint64_t>(1, total / 200);
  const auto t0 = std::chrono::steady_clock::now();
  while (!run.done()) {
    if (!run.step_ticks(chunk)) break;
    if (opt.progress) opt.progress(static_cast<double>(run.tick()) / static_cast<double>(total));
  }
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.ticks = run.tick();
  res.sim_seconds = sc.duration;
  res.failure = run.failure();
  res.ok = res.failure.empty();
  // Results are written also for a failed run (never lose data): the rows
  // recorded up to the failure are in the files, marked incomplete.
  run.finish();
  res.final_pointing_error_deg = run.final_pointing_error_deg();
  if (!files) return res;
  if (h5) put(dir / "results.h5");
  if (csv) put(dir / "telemetry.csv");
  if (report) {
    const std::string data = report_data_text(run, *report);
    write_text((dir / "report_data.json").string(), data);
    put(dir / "report_data.json");
#ifdef KESTREL_HAVE_REPORT
    try {
      report::write_html(data, (dir / "report.html").string());
    } catch (const std::exception& e) {
      throw OutputError(e.what());
    }
    put(dir / "report.html");
#endif
  }
  write_text((dir / "dataflow.dot").string(), run.dataflow().to_dot(sc.name));
  put(dir / "dataflow.dot");
  std::ostringstream health;
  for (const std::string& l : run.fsw_health_lines()) health << l << "\n";
  write_text((dir / "fsw_health.txt").string(), health.str());
  put(dir / "fsw_health.txt");
  std::ostringstream summ;
  summ << std::setprecision(10);
  for (const SummaryItem& it : run.summary())
    summ << it.key << " = " << it.value << " " << it.unit << "    # " << it.what << "\n";
  write_text((dir / "summary.txt").string(), summ.str());
  put(dir / "summary.txt");
  return res;
}

}  // namespace harness
