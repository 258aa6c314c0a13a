// mc_branch.cpp: a campaign branched from a checkpoint (kestrel mc --from;
// docs/checkpoint.md, "Branching a campaign").
#include <cstdio>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <regex>

#include "core/build_error.h"
#include "harness/mc/monte_carlo.h"
#include "scenario/mc_draw.h"

namespace harness {

namespace {

constexpr size_t kActionsPerEvent = 16;  // an event's actions (docs/events.md)

// The event actions that set the settable key `key` to its value in `drawn`
// (docs/events.md, "Scenario parameters settable during a run"); false: the
// key is not settable during a run.
bool settable_actions(const Scenario& drawn, const std::string& key, std::vector<EventActionSpec>* acts)
{
  static const std::regex wheel(R"(^wheels\[(\d+)\]\.u_max$)");
  std::smatch m;
  const bool is_wheel = std::regex_match(key, m, wheel);
  if (!is_wheel && key != "fsw.mrp_fb.K" && key != "fsw.mrp_fb.P" && key != "fsw.inertial.sigma_R0N" &&
      key != "fsw.mode" && key != "fsw.actuation")
    return false;
  if (!acts) return true;
  const ParameterValue v = get_parameter(drawn, key);
  if (is_wheel) {
    acts->push_back({drawn.wheels[std::stoul(m[1].str())].name, "torque_limit", std::get<double>(v.value)});
  } else if (key == "fsw.mrp_fb.K" || key == "fsw.mrp_fb.P") {
    acts->push_back({"fsw", key == "fsw.mrp_fb.K" ? "gain_K" : "gain_P", std::get<double>(v.value)});
  } else if (key == "fsw.inertial.sigma_R0N") {
    const Eigen::Vector3d s = std::get<Eigen::Vector3d>(v.value);
    for (int i = 0; i < 3; ++i) acts->push_back({"fsw", std::string("reference_") + "xyz"[i], s(i)});
  } else {  // fsw.mode, fsw.actuation: the command of that value
    acts->push_back({"fsw", key.substr(4) + "_" + std::get<std::string>(v.value), NAN});
  }
  return true;
}

const char* const kSettable =
    "wheels[i].u_max, fsw.mrp_fb.K, fsw.mrp_fb.P, fsw.inertial.sigma_R0N, fsw.mode, fsw.actuation";

// "" when dispersing `target` may branch from the checkpoint at t0, else why not.
std::string branch_refusal(const Scenario& nominal, const std::string& target, double t0, bool accepts_events,
                           char& settable)
{
  char t0s[64];
  std::snprintf(t0s, sizeof t0s, "%.9g s", t0);
  static const std::regex event(R"(^events\[(\d+)\]\..*$)");
  std::smatch m;
  settable = 0;
  if (std::regex_match(target, m, event)) {
    const EventSpec& e = nominal.events[std::stoul(m[1].str())];
    if (e.t && *e.t >= t0) return "";
    return target + ": the event fires before the checkpoint (t = " + t0s +
           ") or is not a time event: what it does is part of the checkpoint's state; only time events at or after "
           "the checkpoint may be dispersed";
  }
  if (settable_actions(nominal, target, nullptr)) {
    settable = 1;
    if (accepts_events) return "";
    return target + ": set by an event action at the checkpoint, but the checkpoint's run was built without "
                    "RunConfig::accept_events (save it from a run that accepts events, e.g. Python's Run)";
  }
  return target + ": fixed before the checkpoint (t = " + t0s +
         "): its value is in the checkpoint's state, every run starts from it; with --from only time events at or "
         "after the checkpoint, keys settable during a run (" + kSettable + ") and the sensor noise (each run's seed) "
         "are dispersed";
}

}  // namespace

void branch_mc_plan(McPlan& plan, const std::string& checkpoint)
{
  const std::shared_ptr<const Branch> b = read_branch(checkpoint);
  Scenario nominal = plan.nominal, saved = b->scenario;
  nominal.monte_carlo.reset();
  saved.monte_carlo.reset();
  const std::string diff = first_difference(scenario_to_json_text(saved), scenario_to_json_text(nominal));
  if (!diff.empty())
    throw CheckpointError(b->path + ": a checkpoint of scenario '" + b->info.scenario_name +
                          "', not of this campaign's nominal scenario ('" + plan.nominal.name + "'): refused (" + diff +
                          ")");
  std::vector<char> settable(plan.bound->targets.size(), 0);
  for (size_t i = 0; i < settable.size(); ++i) {
    const McTarget& t = plan.bound->targets[i];
    const std::string why = branch_refusal(plan.nominal, t.name, b->t(), b->info.accepts_events, settable[i]);
    if (!why.empty())
      throw config_error(plan.nominal, "monte_carlo.dispersions[" + std::to_string(t.dispersion) + "].key",
                         why + " (kestrel mc --from " + b->path + ")");
  }
  plan.from = b;
  plan.from_settable = std::move(settable);
}

std::string branch_draw(const McPlan& plan, Scenario& sc)
{
  const Branch& b = *plan.from;
  const double t0 = b.t();
  for (size_t i = 0; i < b.scenario.events.size(); ++i)
    if (b.scenario.events[i].t && *b.scenario.events[i].t >= t0 && !(sc.events[i].t && *sc.events[i].t >= t0)) {
      char w[160];
      std::snprintf(w, sizeof w, "events[%zu].t: drawn %.9g s, before the checkpoint (t = %.9g s)", i,
                    sc.events[i].t ? *sc.events[i].t : NAN, t0);
      return w;
    }
  std::vector<EventActionSpec> acts;
  for (size_t i = 0; i < plan.from_settable.size(); ++i) {
    if (!plan.from_settable[i]) continue;
    const std::string& key = plan.bound->targets[i].name;
    settable_actions(sc, key, &acts);
    set_parameter(sc, key, get_parameter(plan.nominal, key));
  }
  for (size_t j = 0; j < acts.size(); j += kActionsPerEvent) {
    EventSpec e;
    e.name = "from_checkpoint";
    if (j > 0) e.name += "_" + std::to_string(j / kActionsPerEvent + 1);
    for (bool taken = true; taken;) {  // unique among the scenario's names
      taken = false;
      for (const EventSpec& x : sc.events) taken = taken || x.name == e.name;
      if (taken) e.name += "_";
    }
    e.t = t0;
    e.actions.assign(acts.begin() + static_cast<std::ptrdiff_t>(j),
                     acts.begin() + static_cast<std::ptrdiff_t>(std::min(acts.size(), j + kActionsPerEvent)));
    sc.events.push_back(std::move(e));
  }
  // the run is its reloaded canonical form, exactly what its manifest gives kestrel run
  const std::string src = sc.source_file;
  try {
    sc = load_scenario_text(scenario_to_json_text(sc), "(drawn scenario)");
  } catch (const ScenarioError& e) {
    return e.issues().front().key + ": " + e.issues().front().message;
  }
  sc.source_file = src;
  sc.key_lines.clear();
  sc.from_checkpoint = b.ref();
  return branch_difference(b, sc);
}

}  // namespace harness
