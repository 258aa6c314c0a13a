// live_commands.cpp: the live view's commands (docs/live.md): read and
// checked when they arrive (POST /api/command), queued, applied by the sim
// thread at a tick boundary (drain), and the bounded log of them
// (/api/commands).  A save writes a checkpoint of the run into its results
// folder at the boundary (save_state).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>

#include "harness/core/checkpoint.h"
#include "harness/scenario/scenario.h"
#include "live/live_impl.h"
#include "scenario/scenario_limits.h"

namespace harness {

std::string LiveServer::Impl::read_event(const json& j, Command& c, std::string& text)
{
  if (!j.contains("device") || !j["device"].is_string() || !j.contains("action") || !j["action"].is_string())
    return "event: needs \"device\" and \"action\" (strings) and, when the action takes one, \"value\"";
  c.action.device = j["device"].get<std::string>();
  c.action.action = j["action"].get<std::string>();
  if (j.contains("value") && !j["value"].is_null()) {
    if (!j["value"].is_number()) return "event: value must be a number";
    c.action.value = j["value"].get<double>();
  }
  // the scenario event validation (events.cpp), as for a scenario file
  std::string key;
  const std::string why = check_event_action(sc, c.action, key);
  if (!why.empty()) return key + ": " + why;
  text = c.action.device + " " + c.action.action;
  if (!std::isnan(c.action.value)) {
    std::ostringstream o;
    o.precision(10);
    o << c.action.value;
    text += " " + o.str();
  }
  return "";
}

std::string LiveServer::Impl::read_command(const json& j, Command& c, std::string& text)
{
  c.op = j["op"].get<std::string>();
  text = c.op;
  if (c.op == "pause" || c.op == "resume") return "";
  if (c.op == "save") {
    text = "save state";
    return "";
  }
  if (c.op == "step") {
    const json n = j.value("ticks", json(1));
    if (!n.is_number_integer() || n.get<int64_t>() < 1 || n.get<int64_t>() > 1000000)
      return "step: ticks must be an integer in [1, 1000000]";
    c.ticks = n.get<uint64_t>();
    text += " " + std::to_string(c.ticks) + " tick" + (c.ticks == 1 ? "" : "s");
    return "";
  }
  if (c.op == "rate") {
    const json v = j.value("value", json());
    if (!v.is_number()) return "rate: value must be a number (a multiple of real time)";
    const std::string why = Pacer::check_scale(v.get<double>());
    if (!why.empty()) return "rate: value: " + why;
    c.value = v.get<double>();
    std::ostringstream o;
    o << "rate " << c.value << "x";
    text = o.str();
    return "";
  }
  if (c.op == "event") return read_event(j, c, text);
  return "unknown command '" + escape_bytes(c.op) + "' (pause, resume, step, rate, event, save)";
}

bool LiveServer::Impl::enqueue(Command& c, const std::string& text, httplib::Response& res)
{
  std::lock_guard<std::mutex> lk(cmd_mu);
  if (queue.size() >= kMaxQueued) {
    ++refused;
    res.status = 429;
    res.set_content(json{{"ok", false}, {"error", "too many commands waiting for the run"}}.dump(), "application/json");
    return false;
  }
  if (c.op == "event") {
    if (live_events >= max_live_events) {
      ++refused;
      res.status = 409;
      res.set_content(json{{"ok", false},
                           {"error", "the run holds the most events a scenario may have (" +
                                         std::to_string(kMaxScenarioEvents) + ")"}}
                          .dump(),
                      "application/json");
      return false;
    }
    ++live_events;
  }
  c.id = next_id++;
  log.push_back({c.id, text, "queued", "", 0, 0.0, "", 0});
  while (log.size() > kLogKept) {
    log.pop_front();
    ++log_base;
  }
  queue.push_back(c);
  has_cmd.store(true);
  bump();
  return true;
}

void LiveServer::Impl::post_command(const httplib::Request& req, httplib::Response& res)
{
  json j;
  try {
    j = json::parse(req.body);
  } catch (const std::exception&) {
    refuse(res, 400, "the command is not JSON");
    return;
  }
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    refuse(res, 400, "a command is {\"op\": pause|resume|step|rate|event|save, ...}");
    return;
  }
  {
    std::lock_guard<std::mutex> lk(info_mu);
    if (!info_ready) {
      refuse(res, 409, "the run has not started yet");
      return;
    }
  }
  if (state.load() == 3) {
    refuse(res, 409, "the run has ended: nothing can be applied");
    return;
  }
  Command c;
  std::string text;
  const std::string why = read_command(j, c, text);
  if (!why.empty()) {
    refuse(res, 400, why);
    return;
  }
  const std::string no_save = c.op == "save" ? save_refused_now() : "";
  if (!no_save.empty()) {
    refuse(res, 409, no_save);
    return;
  }
  if (!enqueue(c, text, res)) return;
  cmd_cv.notify_all();
  res.status = 202;
  res.set_content(json{{"ok", true}, {"id", c.id}, {"command", text}}.dump(), "application/json");
}

std::string LiveServer::Impl::commands_text(const httplib::Request& req)
{
  auto number = [&req](const char* key, uint64_t dflt, uint64_t& out) {
    if (!req.has_param(key)) {
      out = dflt;
      return true;
    }
    const std::string v = req.get_param_value(key);
    if (v.empty() || v.size() > 19 || v.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stoull(v);
    return true;
  };
  uint64_t before = 0, limit = 0;
  if (!number("before", UINT64_MAX, before) || !number("limit", kLogPage, limit) || limit < 1 || limit > kLogPage)
    return "";
  json cmds = json::array();
  std::lock_guard<std::mutex> lk(cmd_mu);
  size_t end = log.size();  // entries with id < before
  if (before < log_base + log.size()) end = before > log_base ? static_cast<size_t>(before - log_base) : 0;
  const size_t begin = end > limit ? end - static_cast<size_t>(limit) : 0;
  for (size_t i = begin; i < end; ++i) cmds.push_back(log_json(log[i]));
  return json{{"commands", std::move(cmds)},
              {"more", begin > 0},
              {"first_kept", log_base},
              {"total", next_id - 1}}
      .dump();
}

void LiveServer::Impl::drain(Run& run, double& pace)
{
  std::deque<Command> cmds;
  {
    std::lock_guard<std::mutex> lk(cmd_mu);
    cmds.swap(queue);
    has_cmd.store(false);
  }
  const uint64_t k = run.tick();
  const double t_k = static_cast<double>(k * tick_ns) / 1e9;  // as the recorded t (correctly rounded: k dt)
  for (const Command& c : cmds) {
    if (c.op == "pause") {
      paused = true;
      step_until = 0;  // a step under way ends here
    } else if (c.op == "resume") {
      if (paused && paced) pace = rate;  // deadlines restart from now
      paused = false;
    } else if (c.op == "step") {
      paused = true;  // from a running run: pause after the steps
      step_until = (step_until > k ? step_until : k) + c.ticks;
      if (paced) pace = rate;
    } else if (c.op == "rate") {
      rate = c.value;
      paced = true;
      rate_shown.store(rate);
      if (!paused) pace = rate;
    } else if (c.op == "save") {
      save_state(run, c.id, k, t_k);
      continue;
    } else if (c.op == "event") {
      if (k + 1 >= total_ticks) {  // t_k would be the run's end: the manifest would not take it
        ++refused;
        set_log(c.id, "refused", "the run is at its last tick", k, t_k);
        continue;
      }
      EventSpec e;
      e.name = "live" + std::to_string(c.id);
      for (bool taken = true; taken;) {  // unique among the scenario's names
        taken = false;
        for (const EventSpec& x : run.scenario().events) taken = taken || x.name == e.name;
        if (taken) e.name += "_";
      }
      e.t = t_k;
      e.actions.push_back(c.action);
      try {
        run.add_event(e);
      } catch (const std::exception& ex) {
        ++refused;
        set_log(c.id, "refused", ex.what(), k, t_k);
        continue;
      }
      ++applied;
      set_log(c.id, "applied", "event " + e.name, k, t_k);
      continue;
    }
    ++applied;
    set_log(c.id, "applied", "", k, t_k);
  }
}

std::string LiveServer::Impl::save_refused_now()
{
  std::lock_guard<std::mutex> lk(info_mu);
  if (save_dir.empty()) return "save: the run writes no results folder (-o): there is nowhere to save its state";
  if (!save_refusal.empty()) return "save: cannot save the state: " + save_refusal;
  return "";
}

void LiveServer::Impl::save_state(Run& run, uint64_t id, uint64_t k, double t_k)
{
  const std::string why = run.checkpoint_refusal();  // a failed or ended run, and what started() saw
  if (!why.empty()) {
    ++refused;
    set_log(id, "refused", "cannot save the state: " + why, k, t_k);
    return;
  }
  const std::string name = "checkpoint-" + std::to_string(k) + ".kckp";
  const std::filesystem::path path = std::filesystem::path(save_dir) / name;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    // the scenario with the events added so far (live commands): the one
    // a restored run is built from
    save_checkpoint(run, path.string(), scenario_to_json_text(run.scenario()));
  } catch (const std::exception& ex) {
    ++refused;
    set_log(id, "refused", std::string("cannot save the state: ") + ex.what(), k, t_k);
    return;
  }
  std::ostringstream ms;  // what the run waited for it
  ms.precision(3);
  ms << seconds_since(t0) * 1e3;
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  const uint64_t bytes = ec ? 0 : static_cast<uint64_t>(size);
  ++applied;
  set_log(id, "applied",
          "saved " + name + " (" + std::to_string(bytes) + " bytes, written in " + ms.str() + " ms) into " + save_target,
          k, t_k, name, bytes);
}

}  // namespace harness
