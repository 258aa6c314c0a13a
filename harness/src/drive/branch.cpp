// branch.cpp: runs started from a checkpoint (harness/drive/branch.h).
#include "harness/drive/branch.h"

#include <filesystem>

namespace harness {

double Branch::t() const { return static_cast<double>(info.tick * scenario.tick_ns()) / 1e9; }

CheckpointRef Branch::ref() const
{
  CheckpointRef r;
  r.path = path;
  r.fnv1a64 = fnv1a64;
  r.tick = info.tick;
  return r;
}

std::shared_ptr<const Branch> read_branch(const std::string& path)
{
  auto b = std::make_shared<Branch>();
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec);
  b->path = ec ? path : abs.lexically_normal().string();
  if (!std::filesystem::is_regular_file(b->path, ec))
    throw CheckpointError(b->path + ": no such checkpoint file");
  const std::vector<uint8_t> file = read_checkpoint_file(b->path);
  b->fnv1a64 = checkpoint_checksum(file, b->path);
  b->info = decode_checkpoint(file, b->state, b->path);
  if (b->info.tick >= b->info.total_ticks)
    throw CheckpointError(b->path + ": the run it was saved from had ended (tick " + std::to_string(b->info.tick) +
                          " of " + std::to_string(b->info.total_ticks) + "): there is nothing to start from");
  try {
    b->scenario = load_scenario_text(b->info.scenario_text, b->path + " (its scenario)");
  } catch (const ScenarioError& e) {
    throw CheckpointError(b->path + ": its scenario does not read back: " + e.what());
  }
  return b;
}

std::string branch_difference(const Branch& b, const Scenario& sc)
{
  const Scenario& c = b.scenario;
  const double t0 = b.t();
  auto to_come = [t0](const EventSpec& e) { return e.t.has_value() && *e.t >= t0; };
  if (sc.events.size() < c.events.size())
    return "it has " + std::to_string(sc.events.size()) + " events, the checkpoint's scenario " +
           std::to_string(c.events.size());
  Scenario x = sc;  // sc with what may differ taken from the checkpoint's scenario
  x.seed = c.seed;
  x.monte_carlo.reset();
  for (size_t i = 0; i < c.events.size(); ++i)
    if (to_come(c.events[i]) && to_come(sc.events[i])) x.events[i] = c.events[i];
  for (size_t i = c.events.size(); i < sc.events.size(); ++i)
    if (!to_come(sc.events[i]))
      return "events[" + std::to_string(i) + "] ('" + sc.events[i].name +
             "') is added to the checkpoint's scenario but is not a time event at or after the checkpoint's t = " +
             std::to_string(t0) + " s";
  x.events.resize(c.events.size());
  Scenario y = c;
  y.monte_carlo.reset();
  const std::string d = first_difference(scenario_to_json_text(y), scenario_to_json_text(x));
  if (d.empty()) return "";
  return "it differs from the checkpoint's scenario '" + c.name +
         "' in what is fixed before the checkpoint (" + d + ")";
}

std::shared_ptr<const Branch> open_branch(const Scenario& sc)
{
  const CheckpointRef& ref = *sc.from_checkpoint;
  std::shared_ptr<const Branch> b;
  try {
    b = read_branch(ref.path);
  } catch (const CheckpointError& e) {
    throw CheckpointError(std::string("the run starts from a checkpoint (from_checkpoint): ") + e.what());
  }
  if (b->fnv1a64 != ref.fnv1a64) {
    throw CheckpointError(b->path + ": checksum " + hex64(b->fnv1a64) + ", the run was made from " + hex64(ref.fnv1a64) +
                          ": the checkpoint has changed since; refused");
  }
  if (b->info.tick != ref.tick)
    throw CheckpointError(b->path + ": saved before tick " + std::to_string(b->info.tick) + ", the run starts at " +
                          std::to_string(ref.tick) + "; refused");
  const std::string why = branch_difference(*b, sc);
  if (!why.empty()) throw CheckpointError(b->path + ": the run cannot start from this checkpoint: " + why);
  return b;
}

bool branch_accepts_events(const Branch& b) { return b.info.accepts_events; }

void start_branch(Run& run, const Branch& b) { restore_branch_state(run, b.state); }

}  // namespace harness
