// scenario_events.cpp: `events` (docs/events.md): each a trigger (t, after +
// delay, or when + below/above) and a list of actions on a device.
#include <cmath>
#include <limits>

#include "core/events.h"
#include "scenario/scenario_limits.h"
#include "scenario/scenario_schema.h"

namespace harness {

namespace schema {

#define KESTREL_EV(member) [](auto& sc, size_t i) -> auto& { return sc.events[i].member; }

namespace {
// A string written only when not empty (absent: not given).
template <class F>
KeyDef optional_string(std::string name, F field)
{
  KeyDef d = string(std::move(name), field);
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    if (!field(sc, i).empty()) j[k.name] = field(sc, i);
  };
  return d;
}

// A key written only when `cond` holds for the event (delay: with after).
KeyDef written_if(KeyDef d, std::function<bool(const EventSpec&)> cond)
{
  WriteFn w = d.write;
  d.write = [w, cond](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    if (cond(sc.events[i])) w(k, j, sc, i);
  };
  return d;
}

// `action: reference` on the FSW: a whole inertial reference, written as
// sigma_R0N or one of its other forms (docs/events.md), read as the three
// component actions reference_x, _y, _z (what the manifest writes).
void read_reference_action(MapReader& a, const std::optional<std::string>& dev, bool has_value, Scenario& sc,
                           size_t i)
{
  const int form = attitude_form_given(a, "sigma_R0N");
  std::optional<Eigen::Vector3d> sigma;
  if (form >= 0) sigma = read_attitude_form(a, "sigma_R0N", form);
  a.finish();
  if (form == -1)
    a.missing("sigma_R0N", "the new reference: sigma_R0N, sigma_R0N_quaternion, sigma_R0N_euler_321_deg or "
                           "sigma_R0N_axis_angle");
  if (has_value) a.error_at("value", "action 'reference' takes sigma_R0N (or one of its forms), not a value");
  if (dev && *dev != "fsw") a.error_at("device", "action 'reference' is the FSW's (device: fsw)");
  if (!sigma || has_value || !dev || *dev != "fsw") return;
  if (sc.events[i].actions.size() + 3 > kMaxEventActions) {
    a.error_at("action", "at most " + std::to_string(kMaxEventActions) +
                             " actions per event, a reference counting as its three components");
    return;
  }
  const char* parts[3] = {"reference_x", "reference_y", "reference_z"};
  for (int c = 0; c < 3; ++c) {
    EventActionSpec spec{*dev, parts[c], (*sigma)(c)};
    std::string key;
    const std::string why = check_event_action(sc, spec, key);
    if (!why.empty()) {
      a.error_at("action", why);
      return;
    }
    sc.events[i].actions.push_back(spec);
  }
}

void read_actions(const KeyDef&, MapReader& r, Scenario& sc, size_t i)
{
  YAML::Node list = r.get("actions");
  const std::string path = r.key_path("actions");
  if (!list.IsDefined()) {
    r.missing("actions", "a list of {device, action, value}");
    return;
  }
  if (!list.IsSequence() || list.size() == 0) {
    r.error_at("actions", "expected a non-empty list of {device, action, value}, got " + kind_name(list));
    return;
  }
  if (list.size() > kMaxEventActions) {
    r.error_at("actions", "at most " + std::to_string(kMaxEventActions) + " actions per event, got " +
                              std::to_string(list.size()));
    return;
  }
  for (size_t j = 0; j < list.size(); ++j) {
    MapReader a(r.ctx(), list[j], path + "[" + std::to_string(j) + "]");
    EventActionSpec spec;
    const auto dev = a.string("device");
    const auto act = a.string("action");
    const auto val = a.real("value");
    if (act && *act == "reference") {
      read_reference_action(a, dev, a.has("value"), sc, i);
      continue;
    }
    a.finish();
    if (!dev) {
      if (!a.has("device")) a.missing("device", "a wheel or thruster name, gyro, star_tracker or css<i>");
      continue;
    }
    if (!act) {
      if (!a.has("action")) a.missing("action", "what happens to the device (docs/events.md)");
      continue;
    }
    spec.device = *dev;
    spec.action = *act;
    if (val) spec.value = *val;
    std::string key;
    const std::string why = check_event_action(sc, spec, key);
    if (!why.empty()) {
      a.error_at(key == "value" && !a.has("value") ? "action" : key, why);
      continue;
    }
    sc.events[i].actions.push_back(spec);
  }
}

void write_actions(const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i)
{
  nlohmann::json a = nlohmann::json::array();
  for (const EventActionSpec& x : sc.events[i].actions) {
    nlohmann::json o = {{"device", x.device}, {"action", x.action}};
    if (!std::isnan(x.value)) o["value"] = x.value;
    a.push_back(o);
  }
  j[k.name] = a;
}
// An action's JSON Schema: device, action, value, or (action: reference) the
// new reference in one of the forms of sigma_R0N.
nlohmann::json action_shape()
{
  nlohmann::json props = {{"device", {{"type", "string"}}}, {"action", {{"type", "string"}}}, {"value", {{"type", "number"}}}};
  const std::vector<std::string> forms = attitude_spellings("sigma_R0N");
  props[forms[0]] = json_vec3();
  for (size_t f = 1; f < forms.size(); ++f) props[forms[f]] = attitude_form_json(forms[0], forms[f]);
  return json_object_of(props, {"device", "action"});
}
}  // namespace

const Section& events_section()
{
  static const Section s = [] {
    Section e{"events",
              {
                  optional_string("name", KESTREL_EV(name)).unit("default ev<i+1>, unique"),
                  real("t", KESTREL_EV(t)).bounds(non_negative("s")).unit("s"),
                  optional_string("after", KESTREL_EV(after)).unit("name of an earlier event"),
                  written_if(real("delay", KESTREL_EV(delay)).bounds(non_negative("s")).unit("s"),
                             [](const EventSpec& e) { return !e.after.empty(); }),
                  optional_string("when", KESTREL_EV(when)).unit("a recorded column"),
                  real("below", KESTREL_EV(below)).unit("the column's unit"),
                  real("above", KESTREL_EV(above)).unit("the column's unit"),
                  custom("actions", read_actions, write_actions)
                      .json_shape(json_list_of(action_shape(), 1, kMaxEventActions))
                      .unit("a list of {device, action, value} (docs/events.md)"),
              },
              {}};
    e.list = true;
    e.capacity = kMaxScenarioEvents;
    e.count = [](const Scenario& sc) { return sc.events.size(); };
    return e;
  }();
  return s;
}
#undef KESTREL_EV

void read_events(MapReader& top, Scenario& sc)
{
  YAML::Node list = top.get("events");
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) {
    top.ctx().error(list, "events", "expected a list of events, got " + kind_name(list));
    return;
  }
  if (list.size() > kMaxScenarioEvents) {
    top.ctx().error(list, "events",
                    "at most " + std::to_string(kMaxScenarioEvents) + " events, got " + std::to_string(list.size()));
    return;
  }
  const std::vector<std::string> cols = event_watch_columns(sc);
  for (size_t i = 0; i < list.size(); ++i) {
    MapReader r(top.ctx(), list[i], "events[" + std::to_string(i) + "]");
    sc.events.emplace_back();
    sc.events.back().name = "ev" + std::to_string(i + 1);
    read_keys(r, events_section(), sc, i);
    r.finish();
    EventSpec& e = sc.events[i];
    for (size_t j = 0; j < i; ++j)
      if (sc.events[j].name == e.name) r.error_at("name", "duplicate event name '" + e.name + "'");
    // the trigger: exactly one kind
    const int kinds = (r.has("t") ? 1 : 0) + (r.has("after") ? 1 : 0) + (r.has("when") ? 1 : 0);
    if (kinds == 0) {
      r.error_self("needs a trigger: t, after (+ delay) or when (+ below or above)");
      continue;
    }
    if (kinds > 1) {
      r.error_self("give exactly one trigger: t, after (+ delay) or when (+ below or above)");
      continue;
    }
    if (e.t && sc.duration > 0.0 && *e.t > sc.duration)
      r.error_at("t", "after the end of the run (duration " + fmt(sc.duration) + " s): the event would never apply");
    if (r.has("delay") && !r.has("after")) r.error_at("delay", "only with 'after'");
    if (r.has("after") && !e.after.empty()) {
      bool earlier = false;
      for (size_t j = 0; j < i; ++j) earlier = earlier || sc.events[j].name == e.after;
      if (!earlier) r.error_at("after", "no earlier event named '" + escape_bytes(e.after) + "' (name one listed before this one)");
    }
    if ((r.has("below") || r.has("above")) && !r.has("when")) r.error_at(r.has("below") ? "below" : "above", "only with 'when'");
    if (r.has("when")) {
      bool known = false;
      for (const std::string& c : cols) known = known || c == e.when;
      if (!known) {
        std::string all;
        for (const std::string& c : cols) all += (all.empty() ? "" : ", ") + c;
        r.error_at("when", "not a column a trigger can watch (" + all + "), got '" + escape_bytes(e.when) + "'");
      }
      if (r.has("below") == r.has("above")) r.error_at("when", "give exactly one of 'below' and 'above'");
    }
  }
}

}  // namespace schema
}  // namespace harness
