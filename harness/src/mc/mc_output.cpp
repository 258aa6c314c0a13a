// mc_output.cpp: a campaign's summary files (harness/monte_carlo.h):
// summary.csv, summary.h5, mc_report_data.json, mc_runs.json and the page.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "output/h5_util.h"
#include "harness/mc/monte_carlo.h"
#include "harness/drive/run_scenario.h"
#include "harness/core/run.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace h5;

namespace {

constexpr size_t kReportRuns = 200;                       // runs overlaid on the page (failing first)
constexpr double kLevels[] = {0.0, 5.0, 50.0, 95.0, 100.0};  // [%] envelope levels over all runs

std::string csv_field(const std::string& s)
{
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return o + "\"";
}

std::string num(double v)
{
  if (std::isnan(v)) return "";
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

const char* status_word(const McRecord& r) { return r.invalid ? "INVALID" : r.pass ? "pass" : "FAIL"; }

void write_csv(const McPlan& plan, const std::vector<McRecord>& recs, const std::vector<size_t>& order,
               const fs::path& path)
{
  std::string o = "index,seed,status,reason";
  for (const McColumn& c : plan.drawn) o += "," + csv_field(c.name + (c.unit.empty() ? "" : " [" + c.unit + "]"));
  for (const McMetric& m : plan.metrics)
    o += "," + csv_field(m.col.name + (m.col.unit.empty() ? "" : " [" + m.col.unit + "]"));
  o += "\n";
  for (size_t i : order) {
    const McRecord& r = recs[i];
    o += std::to_string(r.index) + "," + std::to_string(r.seed) + "," + status_word(r) + "," + csv_field(r.reason);
    for (double v : r.drawn) o += "," + num(v);
    for (double v : r.metrics) o += "," + num(v);
    o += "\n";
  }
  write_text(path.string(), o);
}

template <class T>
void dataset(hid_t file, const std::string& name, hid_t mem, hid_t ftype, const std::vector<T>& data, hsize_t rows,
             hsize_t cols, const std::string& path)
{
  const hsize_t dims[2] = {rows, cols};
  H5Id space(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), H5Sclose);
  H5Id lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl, 1);
  H5Id ds(H5Dcreate2(file, name.c_str(), ftype, space, lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  h5check(ds, "creating " + name, path);
  if (!data.empty() && H5Dwrite(ds, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw OutputError(path + ": cannot write " + name);
}

void write_h5(const McPlan& plan, const std::vector<McRecord>& recs, const std::vector<size_t>& order,
              const McSummaryInfo& info, const fs::path& fpath)
{
  h5_setup();
  const std::string path = fpath.string();
  H5Id f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  h5check(f, "creating the file", path);
  const hsize_t n = order.size();
  std::vector<unsigned long long> index, seed;
  std::vector<unsigned char> pass, invalid, full;
  std::vector<double> drawn, metrics;
  std::vector<std::string> reasons;
  for (size_t i : order) {
    const McRecord& r = recs[i];
    index.push_back(r.index);
    seed.push_back(r.seed);
    pass.push_back(r.pass ? 1 : 0);
    invalid.push_back(r.invalid ? 1 : 0);
    full.push_back(r.full ? 1 : 0);
    drawn.insert(drawn.end(), r.drawn.begin(), r.drawn.end());
    metrics.insert(metrics.end(), r.metrics.begin(), r.metrics.end());
    reasons.push_back(r.reason);
  }
  dataset(f, "/index", H5T_NATIVE_ULLONG, H5T_STD_U64LE, index, n, 0, path);
  dataset(f, "/seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, seed, n, 0, path);
  dataset(f, "/pass", H5T_NATIVE_UCHAR, H5T_STD_U8LE, pass, n, 0, path);
  dataset(f, "/invalid", H5T_NATIVE_UCHAR, H5T_STD_U8LE, invalid, n, 0, path);
  dataset(f, "/full_results", H5T_NATIVE_UCHAR, H5T_STD_U8LE, full, n, 0, path);
  {
    H5Id ds(H5Dopen2(f, "/index", H5P_DEFAULT), H5Dclose);
    attr_strings(ds, "reasons", reasons, path);  // per row: why the run did not pass
  }
  std::vector<std::string> names, units;
  for (const McColumn& c : plan.drawn) {
    names.push_back(c.name);
    units.push_back(c.unit);
  }
  dataset(f, "/drawn", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, drawn, n, plan.drawn.size(), path);
  {
    H5Id ds(H5Dopen2(f, "/drawn", H5P_DEFAULT), H5Dclose);
    attr_strings(ds, "columns", names, path);
    attr_strings(ds, "units", units, path);
  }
  names.clear();
  units.clear();
  for (const McMetric& m : plan.metrics) {
    names.push_back(m.col.name);
    units.push_back(m.col.unit);
  }
  dataset(f, "/metrics", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, metrics, n, plan.metrics.size(), path);
  {
    H5Id ds(H5Dopen2(f, "/metrics", H5P_DEFAULT), H5Dclose);
    attr_strings(ds, "columns", names, path);
    attr_strings(ds, "units", units, path);
  }
  dataset(f, "/series/t", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, plan.series_t, plan.series_t.size(), 0, path);
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  for (size_t c = 0; c < C; ++c) {
    std::vector<float> v;
    v.reserve(n * S);
    for (size_t i : order)
      for (size_t s = 0; s < S; ++s) v.push_back(recs[i].series[s * C + c]);
    dataset(f, "/series/" + plan.series_columns[c], H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, v, n, S, path);
  }
  attr_string(f, "kestrel_version", version(), path);
  attr_string(f, "scenario", plan.nominal.name, path);
  attr_scalar<unsigned long long>(f, "master_seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, plan.master_seed, path);
  attr_scalar<unsigned long long>(f, "runs_planned", H5T_NATIVE_ULLONG, H5T_STD_U64LE, plan.runs, path);
  attr_scalar<unsigned char>(f, "complete", H5T_NATIVE_UCHAR, H5T_STD_U8LE, info.complete ? 1 : 0, path);
  if (H5Fflush(f, H5F_SCOPE_GLOBAL) < 0) throw OutputError(path + ": cannot flush");
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Linear-interpolated percentile of sorted values.
double percentile(const std::vector<double>& s, double p)
{
  if (s.empty()) return NAN;
  const double x = p / 100.0 * static_cast<double>(s.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(x));
  const size_t hi = std::min(lo + 1, s.size() - 1);
  return s[lo] + (x - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

// The report's metrics, criteria and drawn values (names, units, what).
void add_columns(const McPlan& plan, json& j)
{
  json crit = json::array(), metrics = json::array(), drawn = json::array();
  for (const McMetric& m : plan.metrics) {
    metrics.push_back({{"name", m.col.name}, {"unit", m.col.unit}, {"what", m.col.what}});
    if (m.criterion >= 0)
      crit.push_back({{"name", m.col.name},
                      {"metric", m.col.name},
                      {"op", m.below ? "below" : "above"},
                      {"threshold", m.threshold},
                      {"unit", m.col.unit},
                      {"what", m.col.what}});
  }
  for (const McColumn& c : plan.drawn) drawn.push_back({{"name", c.name}, {"unit", c.unit}});
  j["criteria"] = crit;
  j["metrics"] = metrics;
  j["drawn"] = drawn;
}

// One row per run, in table order.
json table_json(const std::vector<McRecord>& recs, const std::vector<size_t>& order)
{
  json table = json::array();
  for (size_t i : order) {
    const McRecord& r = recs[i];
    json d = json::array(), m = json::array();
    for (double v : r.drawn) d.push_back(finite_or_null(v));
    for (double v : r.metrics) m.push_back(finite_or_null(v));
    char dir[32];
    std::snprintf(dir, sizeof dir, "runs/%06llu/report.html", static_cast<unsigned long long>(r.index));
    table.push_back({{"index", r.index},
                     {"seed", std::to_string(r.seed)},
                     {"pass", r.pass},
                     {"invalid", r.invalid},
                     {"reason", r.reason},
                     {"drawn", d},
                     {"metrics", m},
                     {"report", r.full ? json(dir) : json(nullptr)}});
  }
  return table;
}

// The percentiles (kLevels) of every thinned column over the valid runs.
json percentiles_json(const McPlan& plan, const std::vector<McRecord>& recs)
{
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  json pct;
  pct["levels"] = json::array();
  for (double l : kLevels) pct["levels"].push_back(l);
  json pcols = json::object();
  std::vector<double> vals;
  for (size_t c = 0; c < C; ++c) {
    std::vector<json> lv(std::size(kLevels), json::array());
    for (size_t s = 0; s < S; ++s) {
      vals.clear();
      for (const McRecord& r : recs)
        if (!r.invalid && std::isfinite(r.series[s * C + c])) vals.push_back(r.series[s * C + c]);
      std::sort(vals.begin(), vals.end());
      for (size_t l = 0; l < std::size(kLevels); ++l) lv[l].push_back(finite_or_null(percentile(vals, kLevels[l])));
    }
    pcols[plan.series_columns[c]] = lv;
  }
  pct["columns"] = pcols;
  return pct;
}

// The thinned series: times, channels, percentiles and the first
// kReportRuns valid runs in table order.
json series_json(const McPlan& plan, const std::vector<McRecord>& recs, const std::vector<size_t>& order)
{
  json series;
  json t = json::array();
  for (double x : plan.series_t) t.push_back(x);
  series["t"] = t;
  json ch = json::array();
  for (size_t c = 0; c < plan.channels.size(); ++c)
    ch.push_back({{"name", plan.channels[c].first}, {"unit", plan.channel_units[c]}, {"columns", plan.channels[c].second}});
  series["channels"] = ch;
  series["percentiles"] = percentiles_json(plan, recs);
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  json runs = json::array();
  for (size_t i : order) {
    const McRecord& r = recs[i];
    if (r.invalid) continue;
    if (runs.size() >= kReportRuns) break;
    json cols = json::object();
    for (size_t c = 0; c < C; ++c) {
      json v = json::array();
      for (size_t s = 0; s < S; ++s) v.push_back(finite_or_null(r.series[s * C + c]));
      cols[plan.series_columns[c]] = v;
    }
    runs.push_back({{"index", r.index}, {"pass", r.pass}, {"columns", cols}});
  }
  series["runs"] = runs;
  return series;
}

std::string report_json(const McPlan& plan, const std::vector<McRecord>& recs, const std::vector<size_t>& order,
                        const McSummaryInfo& info)
{
  json j;
  j["kind"] = "kestrel_mc_report";
  j["schema"] = 1;
  j["kestrel_version"] = version();
  j["scenario"] = plan.nominal.name;
  j["master_seed"] = plan.master_seed;
  size_t failed = 0, invalid = 0;
  for (const McRecord& r : recs) {
    failed += r.pass ? 0 : 1;
    invalid += r.invalid ? 1 : 0;
  }
  j["runs"] = recs.size();
  j["runs_planned"] = plan.runs;
  j["complete"] = info.complete;
  j["failed"] = failed;
  j["invalid"] = invalid;
  j["wall_seconds"] = info.wall_seconds;
  add_columns(plan, j);
  j["table"] = table_json(recs, order);
  j["series"] = series_json(plan, recs, order);
  return j.dump();
}

json vec_json(const std::vector<double>& v)
{
  json a = json::array();
  for (double x : v) a.push_back(finite_or_null(x));
  return a;
}

std::vector<double> vec_from(const json& a)
{
  std::vector<double> v;
  for (const json& x : a) v.push_back(x.is_null() ? NAN : x.get<double>());
  return v;
}

}  // namespace

std::string mc_records_json(const std::vector<McRecord>& records)
{
  json a = json::array();
  for (const McRecord& r : records) {
    json s = json::array();
    for (float x : r.series) s.push_back(std::isfinite(x) ? json(static_cast<double>(x)) : json(nullptr));
    a.push_back({{"index", r.index},
                 {"seed", r.seed},
                 {"invalid", r.invalid},
                 {"complete", r.complete},
                 {"pass", r.pass},
                 {"reason", r.reason},
                 {"drawn", vec_json(r.drawn)},
                 {"metrics", vec_json(r.metrics)},
                 {"series", s},
                 {"full", r.full},
                 {"wall_seconds", r.wall_seconds}});
  }
  return json({{"kestrel_mc_runs", 1}, {"records", a}}).dump() + "\n";
}

std::vector<McRecord> mc_records_from_json(const std::string& text)
{
  const json j = json::parse(text);
  if (!j.contains("kestrel_mc_runs")) throw std::runtime_error("not a Kestrel mc_runs.json");
  std::vector<McRecord> out;
  for (const json& x : j.at("records")) {
    McRecord r;
    r.index = x.at("index").get<uint64_t>();
    r.seed = x.at("seed").get<uint64_t>();
    r.invalid = x.at("invalid").get<bool>();
    r.complete = x.at("complete").get<bool>();
    r.pass = x.at("pass").get<bool>();
    r.reason = x.at("reason").get<std::string>();
    r.drawn = vec_from(x.at("drawn"));
    r.metrics = vec_from(x.at("metrics"));
    for (const json& v : x.at("series")) r.series.push_back(v.is_null() ? std::nanf("") : v.get<float>());
    r.full = x.at("full").get<bool>();
    r.wall_seconds = x.at("wall_seconds").get<double>();
    out.push_back(std::move(r));
  }
  return out;
}

void write_mc_outputs(const McPlan& plan, const std::vector<McRecord>& records, const McSummaryInfo& info,
                      const fs::path& dir)
{
  const std::vector<size_t> order = mc_table_order(records);
  write_text((dir / "mc_runs.json").string(), mc_records_json(records));
  write_csv(plan, records, order, dir / "summary.csv");
  write_h5(plan, records, order, info, dir / "summary.h5");
  const std::string data = report_json(plan, records, order, info);
  write_text((dir / "mc_report_data.json").string(), data);
#ifdef KESTREL_HAVE_REPORT
  try {
    report::write_mc_html(data, (dir / "mc_report.html").string());
  } catch (const std::exception& e) {
    throw OutputError(e.what());
  }
#endif
}

}  // namespace harness
