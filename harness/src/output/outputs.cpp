// outputs.cpp: CSV sink, manifest, report data and text files.
#include "harness/output/outputs.h"
#include "harness/core/checkpoint.h"
#include "harness/core/pacer.h"

#include <cstdio>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/sun_source.h"
#include "scenario/json_util.h"
#include "sim/environment.h"

namespace harness {

using nlohmann::json;

CsvSink::~CsvSink()
{
  if (f_) std::fclose(f_);
}

void CsvSink::begin(const RecordLayout& layout, uint64_t)
{
  f_ = std::fopen(path_.c_str(), "wb");
  if (!f_) throw OutputError(path_ + ": cannot open for writing");
  nc_ = layout.columns.size();
  for (size_t c = 0; c < nc_; ++c)
    std::fprintf(f_, "%s%s [%s]", c ? "," : "", layout.columns[c].name.c_str(), layout.columns[c].unit.c_str());
  std::fputc('\n', f_);
  if (std::ferror(f_)) throw OutputError(path_ + ": write failed");
}

void CsvSink::write(const double* rows, size_t n)
{
  for (size_t r = 0; r < n; ++r) {
    for (size_t c = 0; c < nc_; ++c) std::fprintf(f_, "%s%.17g", c ? "," : "", rows[r * nc_ + c]);
    std::fputc('\n', f_);
  }
  if (std::ferror(f_)) throw OutputError(path_ + ": write failed (disk full?)");
}

void CsvSink::end(bool)
{
  if (!f_) return;
  const bool bad = std::ferror(f_) != 0;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (bad || !closed) throw OutputError(path_ + ": write failed (disk full?)");
}

void write_text(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError(path + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw OutputError(path + ": write failed");
}

std::string manifest_text(const Scenario& sc, const std::vector<Override>& overrides, const RunStatus* status)
{
  json j;
  j["kestrel_manifest"] = 1;
  j["kestrel_version"] = version();
  j["source"] = sc.source_file;
  json ov = json::array();
  for (const Override& o : overrides) ov.push_back(o.path + "=" + o.value);
  j["overrides"] = ov;
  j["scenario"] = scenario_to_json(sc);
  if (sc.from_checkpoint) {
    j["from_checkpoint"] = {
        {"path", sc.from_checkpoint->path}, {"fnv1a64", hex64(sc.from_checkpoint->fnv1a64)}, {"tick", sc.from_checkpoint->tick}};
  }
  if (status)
    j["result"] = {{"complete", status->complete},
                   {"ticks", status->ticks},
                   {"t_reached", status->t_reached},
                   {"duration", sc.duration},
                   {"stopped_by", status->stopped_by}};
  if (status && !sc.events.empty()) {
    json ev = json::array();
    for (const AppliedEvent& e : status->events)
      ev.push_back({{"name", e.name}, {"tick", e.tick}, {"t", e.t}, {"actions", e.what}});
    j["result"]["events_applied"] = ev;
  }
  return j.dump(2) + "\n";
}

namespace {

json vec_json(const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); }

// What the 3D view draws besides the devices: the sensors' fields of view,
// the central body, the Sun's position over the run (a dated run's Sun
// moves: 65 samples from t = 0 to the end) and the main-engine burn.
void add_scene_json(const Scenario& sc, json& g)
{
  json sensors = json::object();
  if (!sc.sensors.css.normals_B.empty()) {
    json n = json::array();
    for (const Eigen::Vector3d& v : sc.sensors.css.normals_B) n.push_back(vec_json(v));
    sensors["css"] = {{"normals_B", n}, {"fov_deg", sc.sensors.css.fov * 180.0 / 3.14159265358979323846}};
  }
  if (sc.sensors.star_tracker.enabled)  // the case z axis is +z_B (sim::StarTracker)
    sensors["star_tracker"] = {{"boresight_B", {0.0, 0.0, 1.0}},
                               {"sun_exclusion_deg", sc.sensors.star_tracker.sun_exclusion * 180.0 / 3.14159265358979323846}};
  g["sensors"] = sensors;
  const double mu = sc.environment.mu;
  if (mu > 0.0) {
    const sim::CentralBody earth = sim::earth();
    const sim::CentralBody mars = sim::mars();
    const bool is_earth = std::abs(mu - earth.mu) <= 1e-6 * earth.mu;
    const bool is_mars = std::abs(mu - mars.mu) <= 1e-6 * mars.mu;
    g["central_body"] = {{"name", is_earth ? "Earth" : is_mars ? "Mars" : "central body"},
                         {"mu", mu},
                         {"radius", is_earth ? earth.radius : is_mars ? mars.radius : 0.0}};
  }
  const SunSource sun(sc);
  json st = json::array();
  json sr = json::array();
  const int n = sun.dated() ? 65 : 1;
  for (int i = 0; i < n; ++i) {
    const double t = n > 1 ? sc.duration * i / (n - 1) : 0.0;
    st.push_back(t);
    sr.push_back(vec_json(sun.position_N(static_cast<int64_t>(std::llround(t * 1e9)))));
  }
  g["sun"] = {{"t", st}, {"r_N", sr}};
  if (sc.burn) g["burn"] = {{"thruster", sc.burn->thruster}, {"start", sc.burn->start}, {"duration", sc.burn->duration}};
}

}  // namespace

std::string geometry_json_text(const Run& run)
{
  const Scenario& sc = run.scenario();
  json axes = json::array();
  for (const auto& a : run.wheel_axes_B()) axes.push_back({a[0], a[1], a[2]});
  json thr = json::array();
  for (const ThrusterSpec& t : sc.thrusters)
    thr.push_back({{"name", t.name},
                   {"r_B", {t.r_TjB_B(0), t.r_TjB_B(1), t.r_TjB_B(2)}},
                   {"dir_B", {t.t_hat_B(0), t.t_hat_B(1), t.t_hat_B(2)}}});
  json wpos = json::array();
  json wnames = json::array();
  for (const WheelSpec& w : sc.wheels) {
    wpos.push_back({w.params.r_WB_B(0), w.params.r_WB_B(1), w.params.r_WB_B(2)});
    wnames.push_back(w.name);
  }
  json mnames = json::array();
  for (const MagnetorquerSpec& m : sc.magnetorquers) mnames.push_back(m.name);
  json g{{"wheel_axes_B", axes}, {"wheel_positions_B", wpos}, {"wheel_names", wnames}, {"thrusters", thr},
         {"magnetorquer_names", mnames}};
  add_scene_json(sc, g);
  return g.dump();
}

std::string report_data_text(const Run& run, const ReportSink& report, const RunStatus* status,
                             const PacingStats* pacing, const RunStory* story)
{
  const Scenario& sc = run.scenario();
  json j;
  j["meta"] = {{"scenario", sc.name},
               {"description", sc.description},
               {"seed", sc.seed},
               {"version", version()},
               {"dt", sc.rates.dt},
               {"duration", sc.duration},
               {"record_period", sc.rates.dt * sc.rates.record_divisor},
               {"fsw_period", sc.rates.dt * sc.rates.fsw_divisor},
               {"fsw_mode", to_string(sc.fsw.mode)},
               {"num_wheels", sc.wheels.size()},
               {"num_thrusters", sc.thrusters.size()},
               {"rows", run.recorder().rows()},
               {"complete", run.done() && run.failure().empty()},
               {"decimated", report.decimated()}};
  if (status) {
    j["meta"]["t_reached"] = status->t_reached;
    j["meta"]["stopped_by"] = status->stopped_by;
  }
  if (pacing) {
    j["meta"]["rt_scale"] = pacing->scale;
    j["meta"]["rt_lateness_p50_s"] = pacing->lateness_p50_s;
    j["meta"]["rt_lateness_p99_s"] = pacing->lateness_p99_s;
    j["meta"]["rt_lateness_max_s"] = pacing->lateness_max_s;
    j["meta"]["rt_overruns"] = pacing->overruns;
    j["meta"]["rt_drift_s"] = pacing->drift_s;
  }
  j["geometry"] = json::parse(geometry_json_text(run));
  j["dataflow_dot"] = run.dataflow().to_dot(sc.name);
  if (!sc.events.empty()) {
    json ev = json::array();
    for (const AppliedEvent& e : run.events_applied())
      ev.push_back({{"name", e.name}, {"tick", e.tick}, {"t", e.t}, {"actions", e.what}});
    j["events"] = ev;
  }
  const auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json summ = json::object();
  for (const SummaryItem& it : story ? story->summary : run.summary())
    summ[it.key] = {{"value", num(it.value)}, {"unit", it.unit}, {"what", it.what}};
  j["summary"] = summ;
  if (story) {
    // the order of summary.txt (a JSON object's keys are not ordered)
    json order = json::array();
    for (const SummaryItem& it : story->summary) order.push_back(it.key);
    j["summary_order"] = order;
    j["warnings"] = story->warnings;
    json req = json::array();
    for (const RequirementResult& r : story->requirements)
      req.push_back({{"name", r.name}, {"what", r.what}, {"unit", r.unit}, {"below", r.below},
                     {"threshold", num(r.threshold)}, {"value", num(r.value)}, {"pass", r.pass}});
    j["requirements"] = req;
  }
  // the (large) series are written by the sink directly, not through a JSON tree
  std::string text = j.dump();
  text.pop_back();  // the closing brace
  text += ',';
  text += report.series_json();
  text += "}\n";
  return text;
}

}  // namespace harness
