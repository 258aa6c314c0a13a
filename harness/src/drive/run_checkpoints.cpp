// run_checkpoints.cpp: checkpoints of a kestrel run and its continuation
// (harness/drive/run_checkpoints.h, docs/checkpoint.md).
#include "harness/drive/run_checkpoints.h"

#include <algorithm>
#include <cmath>
#include <system_error>

#include <nlohmann/json.hpp>

#include "harness/core/checkpoint.h"
#include "harness/output/outputs.h"
#include "harness/output/results_dir.h"

namespace harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kOutputsFormat = 1;  // the "outputs" text of a kestrel run's checkpoint

json mark_json(const RowJournal::Mark& m)
{
  return {{"bytes", m.bytes}, {"rows", m.rows}, {"fnv1a64", m.fnv}};
}

}  // namespace

RunCheckpoints::RunCheckpoints(const fs::path& work, const Scenario& sc, const std::vector<Override>& overrides,
                               double every_s)
    : work_(work), sc_(sc), overrides_(overrides)
{
  const double ticks = std::round(every_s * 1e9 / static_cast<double>(sc.tick_ns()));
  every_ticks_ = ticks < 1.0 ? 1 : static_cast<uint64_t>(std::min(ticks, 1e18));
}

RunCheckpoints::RunCheckpoints(const fs::path& work) : work_(work), resume_(true)
{
  const std::string path = (work / kCheckpointName).string();
  const CheckpointInfo info = decode_checkpoint(read_checkpoint_file(path), state_, path);
  json o;
  try {
    o = json::parse(info.outputs);
    if (o.at("kestrel_run").get<int>() != kOutputsFormat) throw std::runtime_error("format");
    for (const json& v : o.at("overrides")) overrides_.push_back({v.at(0).get<std::string>(), v.at(1).get<std::string>()});
    every_ticks_ = o.at("every_ticks").get<uint64_t>();
    mark_ = {o.at("rows").at("bytes").get<uint64_t>(), o.at("rows").at("rows").get<uint64_t>(),
             o.at("rows").at("fnv1a64").get<uint64_t>()};
    sc_ = load_scenario_text(info.scenario_text, path);
    sc_.source_file = o.at("source").get<std::string>();
  } catch (const ScenarioError&) {
    throw CheckpointError(path + ": its scenario does not load in this kestrel; refused");
  } catch (const std::exception&) {
    throw CheckpointError(path + ": not the checkpoint of a kestrel run's results folder (written with "
                                 "--checkpoint-every); refused");
  }
  scenario_text_ = info.scenario_text;
  sink_rows_ = info.sink_rows;
  last_saved_ = info.tick;
  if (mark_.rows != sink_rows_)
    throw CheckpointError(path + ": its rows mark (" + std::to_string(mark_.rows) + ") differs from its recorder's (" +
                          std::to_string(sink_rows_) + "); refused");
}

RunCheckpoints::~RunCheckpoints() = default;

double RunCheckpoints::every_seconds() const
{
  return static_cast<double>(every_ticks_) * static_cast<double>(sc_.tick_ns()) * 1e-9;
}

void RunCheckpoints::attach(Run& run, const std::vector<RecordSink*>& sinks)
{
  const std::string why = run.checkpoint_refusal();
  if (!why.empty()) throw CheckpointError("--checkpoint-every: this run cannot be checkpointed: " + why);
  if (!resume_) {
    scenario_text_ = scenario_to_json_text(run.scenario());
    // the rows file: every value of the run, 8 bytes each (the other
    // result files were counted by RunOutputs::open)
    const uint64_t need = run.recorder().capacity() * run.recorder().num_columns() * 8 + (1u << 20);
    if (free_bytes(work_) < need)
      throw OutputError(work_.string() + ": not enough free space for the checkpoints' rows file (about " +
                        std::to_string((need >> 20) + 1) + " MiB more); nothing was simulated");
  }
  rows_ = std::make_unique<RowJournal>((work_ / kRowsName).string(), resume_);
  run.add_sink(*rows_);
  if (!resume_) return;
  rows_->replay(mark_, sinks);
  restore_run_state(run, state_);
  state_.clear();
  state_.shrink_to_fit();
  std::error_code ec;
  fs::remove(work_ / (std::string(kCheckpointName) + ".tmp"), ec);  // of a write the kill cut short
}

uint64_t RunCheckpoints::boundary(Run& run)
{
  const uint64_t k = run.tick();
  if (k > 0 && k % every_ticks_ == 0 && k != last_saved_ && !run.done() && run.failure().empty()) {
    mark_ = rows_->sync();  // the rows on disk before the checkpoint claims them
    json o;
    o["kestrel_run"] = kOutputsFormat;
    o["source"] = sc_.source_file;
    json ov = json::array();
    for (const Override& v : overrides_) ov.push_back({v.path, v.value});
    o["overrides"] = ov;
    o["every_ticks"] = every_ticks_;
    o["rows"] = mark_json(mark_);
    save_checkpoint(run, (work_ / kCheckpointName).string(), scenario_text_, o.dump());
    last_saved_ = k;
  }
  return every_ticks_ - k % every_ticks_;
}

void RunCheckpoints::discard()
{
  std::error_code ec;
  for (const std::string& n : {std::string(kCheckpointName), std::string(kCheckpointName) + ".tmp", std::string(kRowsName)})
    fs::remove(work_ / n, ec);
}

}  // namespace harness
