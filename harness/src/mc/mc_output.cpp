// mc_output.cpp: a campaign's summary files (harness/monte_carlo.h):
// summary.csv, summary.h5, mc_report_data.json, mc_runs.json and the page.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "output/h5_util.h"
#include "harness/mc/monte_carlo.h"
#include "harness/mc/mc_sensitivity.h"
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

std::string csv_header(const McPlan& plan)
{
  std::string o = "index,seed,status,reason";
  for (const McColumn& c : plan.drawn) o += "," + csv_field(c.name + (c.unit.empty() ? "" : " [" + c.unit + "]"));
  for (const McMetric& m : plan.metrics)
    o += "," + csv_field(m.col.name + (m.col.unit.empty() ? "" : " [" + m.col.unit + "]"));
  return o + "\n";
}

std::string csv_row(const McRecord& r)
{
  std::string o = std::to_string(r.index) + "," + std::to_string(r.seed) + "," + status_word(r) + "," + csv_field(r.reason);
  for (double v : r.drawn) o += "," + num(v);
  for (double v : r.metrics) o += "," + num(v);
  return o + "\n";
}

// A text file written in pieces; close() throws OutputError on any failure.
class TextOut {
 public:
  explicit TextOut(const fs::path& p) : path_(p.string()), f_(p, std::ios::binary | std::ios::trunc)
  {
    if (!f_) throw OutputError(path_ + ": cannot open for writing");
  }
  void put(const std::string& s) { f_ << s; }
  void close()
  {
    f_.flush();
    if (!f_) throw OutputError(path_ + ": write failed");
    f_.close();
  }

 private:
  std::string path_;
  std::ofstream f_;
};

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

// Rows [row0, row0 + rows) of dataset `name` (cols == 0: a 1-D dataset).
void write_rows(hid_t file, const std::string& name, hid_t mem, const void* data, hsize_t row0, hsize_t rows,
                hsize_t cols, const std::string& path)
{
  if (rows == 0) return;
  H5Id ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  h5check(ds, "opening " + name, path);
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t start[2] = {row0, 0}, count[2] = {rows, cols};
  H5Id fspace(H5Dget_space(ds), H5Sclose);
  H5Id mspace(H5Screate_simple(rank, count, nullptr), H5Sclose);
  if (H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
      H5Dwrite(ds, mem, mspace, fspace, H5P_DEFAULT, data) < 0)
    throw OutputError(path + ": cannot write " + name);
}

// summary.h5 written a block of rows at a time (table order): the datasets
// are created at their full size, each block goes to its rows.
class SummaryH5 {
 public:
  SummaryH5(const McPlan& plan, hsize_t n, const fs::path& fpath)
      : plan_(plan), path_(fpath.string()), S_(plan.series_rows.size()), C_(plan.series_columns.size())
  {
    h5_setup();
    // the latest format: the per-row `reasons` attribute may exceed the 64 kB of the original one
    H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST);
    f_ = H5Id(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose);
    h5check(f_, "creating the file", path_);
    const std::vector<double> none;
    dataset(f_, "/index", H5T_NATIVE_ULLONG, H5T_STD_U64LE, none, n, 0, path_);
    dataset(f_, "/seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, none, n, 0, path_);
    dataset(f_, "/pass", H5T_NATIVE_UCHAR, H5T_STD_U8LE, none, n, 0, path_);
    dataset(f_, "/invalid", H5T_NATIVE_UCHAR, H5T_STD_U8LE, none, n, 0, path_);
    dataset(f_, "/full_results", H5T_NATIVE_UCHAR, H5T_STD_U8LE, none, n, 0, path_);
    dataset(f_, "/drawn", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, none, n, plan.drawn.size(), path_);
    dataset(f_, "/metrics", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, none, n, plan.metrics.size(), path_);
    dataset(f_, "/series/t", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, plan.series_t, plan.series_t.size(), 0, path_);
    for (size_t c = 0; c < C_; ++c)
      dataset(f_, "/series/" + plan.series_columns[c], H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, none, n, S_, path_);
    block_ = std::max<size_t>(1, (size_t(1) << 18) / ((S_ * C_ + 1) * sizeof(float)));
    series_.resize(C_);
  }

  void add(const McRecord& r)
  {
    index_.push_back(r.index);
    seed_.push_back(r.seed);
    pass_.push_back(r.pass ? 1 : 0);
    invalid_.push_back(r.invalid ? 1 : 0);
    full_.push_back(r.full ? 1 : 0);
    drawn_.insert(drawn_.end(), r.drawn.begin(), r.drawn.end());
    metrics_.insert(metrics_.end(), r.metrics.begin(), r.metrics.end());
    for (size_t c = 0; c < C_; ++c)
      for (size_t s = 0; s < S_; ++s) series_[c].push_back(r.series[s * C_ + c]);
    reasons_.push_back(r.reason);
    if (index_.size() >= block_) flush();
  }

  void finish(const McSummaryInfo& info)
  {
    flush();
    {
      H5Id ds(H5Dopen2(f_, "/index", H5P_DEFAULT), H5Dclose);
      attr_strings(ds, "reasons", reasons_, path_);  // per row: why the run did not pass
    }
    columns_attrs("/drawn", plan_.drawn.size(), [&](size_t i) { return plan_.drawn[i]; });
    columns_attrs("/metrics", plan_.metrics.size(), [&](size_t i) { return plan_.metrics[i].col; });
    attr_string(f_, "kestrel_version", version(), path_);
    attr_string(f_, "scenario", plan_.nominal.name, path_);
    attr_scalar<unsigned long long>(f_, "master_seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, plan_.master_seed, path_);
    attr_scalar<unsigned long long>(f_, "runs_planned", H5T_NATIVE_ULLONG, H5T_STD_U64LE, plan_.runs, path_);
    attr_scalar<unsigned char>(f_, "complete", H5T_NATIVE_UCHAR, H5T_STD_U8LE, info.complete ? 1 : 0, path_);
    if (H5Fflush(f_, H5F_SCOPE_GLOBAL) < 0) throw OutputError(path_ + ": cannot flush");
  }

 private:
  void flush()
  {
    const hsize_t k = index_.size();
    write_rows(f_, "/index", H5T_NATIVE_ULLONG, index_.data(), row_, k, 0, path_);
    write_rows(f_, "/seed", H5T_NATIVE_ULLONG, seed_.data(), row_, k, 0, path_);
    write_rows(f_, "/pass", H5T_NATIVE_UCHAR, pass_.data(), row_, k, 0, path_);
    write_rows(f_, "/invalid", H5T_NATIVE_UCHAR, invalid_.data(), row_, k, 0, path_);
    write_rows(f_, "/full_results", H5T_NATIVE_UCHAR, full_.data(), row_, k, 0, path_);
    if (!plan_.drawn.empty()) write_rows(f_, "/drawn", H5T_NATIVE_DOUBLE, drawn_.data(), row_, k, plan_.drawn.size(), path_);
    if (!plan_.metrics.empty())
      write_rows(f_, "/metrics", H5T_NATIVE_DOUBLE, metrics_.data(), row_, k, plan_.metrics.size(), path_);
    for (size_t c = 0; c < C_ && S_ > 0; ++c)
      write_rows(f_, "/series/" + plan_.series_columns[c], H5T_NATIVE_FLOAT, series_[c].data(), row_, k, S_, path_);
    row_ += k;
    index_.clear();
    seed_.clear();
    pass_.clear();
    invalid_.clear();
    full_.clear();
    drawn_.clear();
    metrics_.clear();
    for (std::vector<float>& v : series_) v.clear();
  }

  template <class F>
  void columns_attrs(const char* name, size_t n, F col)
  {
    std::vector<std::string> names, units;
    for (size_t i = 0; i < n; ++i) {
      names.push_back(col(i).name);
      units.push_back(col(i).unit);
    }
    H5Id ds(H5Dopen2(f_, name, H5P_DEFAULT), H5Dclose);
    attr_strings(ds, "columns", names, path_);
    attr_strings(ds, "units", units, path_);
  }

  const McPlan& plan_;
  const std::string path_;
  const size_t S_, C_;
  H5Id f_;
  size_t block_ = 1;
  hsize_t row_ = 0;
  std::vector<unsigned long long> index_, seed_;
  std::vector<unsigned char> pass_, invalid_, full_;
  std::vector<double> drawn_, metrics_;
  std::vector<std::vector<float>> series_;
  std::vector<std::string> reasons_;  // one per run (empty for a pass): the attribute needs them all
};

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

// One row of the report's table.
json table_row(const McRecord& r)
{
  json d = json::array(), m = json::array();
  for (double v : r.drawn) d.push_back(finite_or_null(v));
  for (double v : r.metrics) m.push_back(finite_or_null(v));
  char dir[32];
  std::snprintf(dir, sizeof dir, "runs/%06llu/report.html", static_cast<unsigned long long>(r.index));
  return {{"index", r.index},
          {"seed", std::to_string(r.seed)},
          {"pass", r.pass},
          {"invalid", r.invalid},
          {"reason", r.reason},
          {"drawn", d},
          {"metrics", m},
          {"report", r.full ? json(dir) : json(nullptr)}};
}

// Every run's thinned series transposed on disk: value (sample s, column c)
// of all runs contiguous, so that the percentiles over the runs read one
// (s, c) at a time.  Filled a block of runs at a time; the file is removed
// when this ends.
class SeriesScratch {
 public:
  SeriesScratch(const fs::path& path, size_t runs, size_t values)
      : path_(path), n_(runs), K_(values), block_(std::max<size_t>(1, (size_t(1) << 18) / ((values + 1) * sizeof(float))))
  {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd_ < 0) throw OutputError(path.string() + ": cannot open the scratch file: " + std::strerror(errno));
    buf_.assign(K_ * block_, 0.0f);
  }
  ~SeriesScratch()
  {
    ::close(fd_);
    ::unlink(path_.c_str());
  }
  SeriesScratch(const SeriesScratch&) = delete;
  SeriesScratch& operator=(const SeriesScratch&) = delete;

  // The next run's series (NaN for an invalid draw: not in the percentiles).
  void add(const McRecord& r)
  {
    for (size_t k = 0; k < K_; ++k) buf_[k * block_ + held_] = r.invalid || k >= r.series.size() ? std::nanf("") : r.series[k];
    if (++held_ == block_) flush();
  }
  void flush()
  {
    for (size_t k = 0; k < K_ && held_ > 0; ++k)
      io(::pwrite(fd_, &buf_[k * block_], held_ * sizeof(float), offset(k, row_)), held_, "write");
    row_ += held_;
    held_ = 0;
  }
  // Value k of every run.
  void read(size_t k, std::vector<float>& out) const
  {
    out.resize(n_);
    if (n_ > 0) io(::pread(fd_, out.data(), n_ * sizeof(float), offset(k, 0)), n_, "read");
  }

 private:
  off_t offset(size_t k, size_t row) const { return static_cast<off_t>((k * n_ + row) * sizeof(float)); }
  void io(ssize_t got, size_t want, const char* what) const
  {
    if (got != static_cast<ssize_t>(want * sizeof(float)))
      throw OutputError(path_.string() + ": cannot " + what + " the scratch file (disk full?)");
  }
  fs::path path_;
  size_t n_, K_, block_, held_ = 0, row_ = 0;
  int fd_ = -1;
  std::vector<float> buf_;
};

// The percentiles (kLevels) of every thinned column over the valid runs.
json percentiles_json(const McPlan& plan, const SeriesScratch& scratch)
{
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  json pct;
  pct["levels"] = json::array();
  for (double l : kLevels) pct["levels"].push_back(l);
  json pcols = json::object();
  std::vector<double> vals;
  std::vector<float> all;
  for (size_t c = 0; c < C; ++c) {
    std::vector<json> lv(std::size(kLevels), json::array());
    for (size_t s = 0; s < S; ++s) {
      scratch.read(s * C + c, all);
      vals.clear();
      for (float x : all)
        if (std::isfinite(x)) vals.push_back(x);
      std::sort(vals.begin(), vals.end());
      for (size_t l = 0; l < std::size(kLevels); ++l) lv[l].push_back(finite_or_null(percentile(vals, kLevels[l])));
    }
    pcols[plan.series_columns[c]] = lv;
  }
  pct["columns"] = pcols;
  return pct;
}

// The thinned series but its runs: times, channels, percentiles.
json series_json(const McPlan& plan, const SeriesScratch& scratch)
{
  json series;
  json t = json::array();
  for (double x : plan.series_t) t.push_back(x);
  series["t"] = t;
  json ch = json::array();
  for (size_t c = 0; c < plan.channels.size(); ++c)
    ch.push_back({{"name", plan.channels[c].first}, {"unit", plan.channel_units[c]}, {"columns", plan.channels[c].second}});
  series["channels"] = ch;
  series["percentiles"] = percentiles_json(plan, scratch);
  return series;
}

// The series of one run as the report overlays it.
json series_run_json(const McPlan& plan, const McRecord& r)
{
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  json cols = json::object();
  for (size_t c = 0; c < C; ++c) {
    json v = json::array();
    for (size_t s = 0; s < S; ++s) v.push_back(finite_or_null(r.series[s * C + c]));
    cols[plan.series_columns[c]] = v;
  }
  return {{"index", r.index}, {"pass", r.pass}, {"columns", cols}};
}

// What drives each criterion's failures (mc_sensitivity.h): per criterion,
// the failing runs and the drawn values ranked.
json drivers_json(const McPlan& plan, const McRecordSource& src)
{
  json out = json::array();
  for (const McCriterionDrivers& c : mc_sensitivity(plan, src)) {
    json ranked = json::array();
    for (const McDriver& d : c.ranked)
      ranked.push_back({{"drawn", plan.drawn[d.drawn].name},
                        {"unit", plan.drawn[d.drawn].unit},
                        {"n", d.n},
                        {"auc", finite_or_null(d.auc)},
                        {"delta", finite_or_null(d.delta)},
                        {"p", finite_or_null(d.p)},
                        {"rho", finite_or_null(d.rho)}});
    out.push_back({{"criterion", plan.metrics[c.metric].col.name},
                   {"runs", c.runs},
                   {"failed", c.failed},
                   {"failing", c.failing},
                   {"ranked_by", c.failed > 0 && c.failed < c.runs ? "delta" : "rho"},
                   {"ranked", ranked}});
  }
  return out;
}

// mc_report_data.json in three pieces around its two long arrays: before
// series.runs (the first kReportRuns valid runs in table order), between
// it and the table (every run), after the table.  The arrays are written
// a run at a time between them.
std::vector<std::string> report_json_pieces(const McPlan& plan, const McRecordSource& src,
                                            const SeriesScratch& scratch, const McSummaryInfo& info)
{
  static const std::string kRuns = "\x01kestrel runs\x01", kTable = "\x01kestrel table\x01";
  json j;
  j["kind"] = "kestrel_mc_report";
  j["schema"] = 1;
  j["kestrel_version"] = version();
  j["scenario"] = plan.nominal.name;
  j["master_seed"] = plan.master_seed;
  size_t failed = 0, invalid = 0;
  for (size_t i = 0; i < src.size(); ++i) {
    failed += src.state(i).pass ? 0 : 1;
    invalid += src.state(i).invalid ? 1 : 0;
  }
  j["runs"] = src.size();
  j["runs_planned"] = plan.runs;
  j["complete"] = info.complete;
  j["failed"] = failed;
  j["invalid"] = invalid;
  j["wall_seconds"] = info.wall_seconds;
  add_columns(plan, j);
  j["drivers"] = drivers_json(plan, src);
  j["drivers_method"] = {{"runs_used_max", kSensitivityMaxRuns},
                         {"doc", "docs/monte-carlo.md, What drives the failures"}};
  j["table"] = kTable;
  j["series"] = series_json(plan, scratch);
  j["series"]["runs"] = kRuns;
  const std::string text = j.dump();
  std::vector<std::string> out;
  size_t from = 0;
  for (const std::string& m : {"\"runs\":" + json(kRuns).dump(), "\"table\":" + json(kTable).dump()}) {
    const size_t at = text.find(m, from);
    const size_t key = m.find(':') + 1;  // the key stays, its value goes
    out.push_back(text.substr(from, at + key - from));
    from = at + m.size();
  }
  out.push_back(text.substr(from));
  return out;
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

namespace {

json record_json(const McRecord& r)
{
  json s = json::array();
  for (float x : r.series) s.push_back(std::isfinite(x) ? json(static_cast<double>(x)) : json(nullptr));
  return {{"index", r.index},
          {"seed", r.seed},
          {"invalid", r.invalid},
          {"complete", r.complete},
          {"pass", r.pass},
          {"reason", r.reason},
          {"drawn", vec_json(r.drawn)},
          {"metrics", vec_json(r.metrics)},
          {"series", s},
          {"full", r.full},
          {"wall_seconds", r.wall_seconds}};
}

// The text of mc_runs.json around its records: {"kestrel_mc_runs":1,"records":[ ... ]}
const char kRunsHead[] = "{\"kestrel_mc_runs\":1,\"records\":[";
const char kRunsTail[] = "]}\n";

}  // namespace

std::string mc_record_json(const McRecord& r) { return record_json(r).dump(); }

std::string mc_records_json(const std::vector<McRecord>& records)
{
  std::string o = kRunsHead;
  for (size_t i = 0; i < records.size(); ++i) o += (i ? "," : "") + mc_record_json(records[i]);
  return o + kRunsTail;
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

namespace {

// Index order: mc_runs.json, and every run's series into the scratch file.
void write_runs_json(const McRecordSource& src, SeriesScratch& scratch, const fs::path& path)
{
  TextOut runs(path);
  runs.put(kRunsHead);
  for (size_t i = 0; i < src.size(); ++i) {
    const McRecord r = src.record(i);
    runs.put((i ? "," : "") + mc_record_json(r));
    scratch.add(r);
  }
  runs.put(kRunsTail);
  runs.close();
  scratch.flush();
}

// The report data's series.runs: the first kReportRuns valid runs in table order.
void write_series_runs(const McPlan& plan, const McRecordSource& src, const std::vector<size_t>& order, TextOut& data)
{
  data.put("[");
  size_t n = 0;
  for (size_t i : order) {
    if (src.state(i).invalid) continue;
    if (n >= kReportRuns) break;
    data.put((n++ ? "," : "") + series_run_json(plan, src.record(i)).dump());
  }
  data.put("]");
}

// Table order: summary.csv, summary.h5 and mc_report_data.json.
void write_tables(const McPlan& plan, const McRecordSource& src, const std::vector<size_t>& order,
                  const std::vector<std::string>& pieces, const McSummaryInfo& info, const fs::path& dir)
{
  TextOut csv(dir / "summary.csv"), data(dir / "mc_report_data.json");
  SummaryH5 h5(plan, order.size(), dir / "summary.h5");
  csv.put(csv_header(plan));
  data.put(pieces[0]);
  write_series_runs(plan, src, order, data);
  data.put(pieces[1] + "[");
  for (size_t j = 0; j < order.size(); ++j) {
    const McRecord r = src.record(order[j]);
    csv.put(csv_row(r));
    data.put((j ? "," : "") + table_row(r).dump());
    h5.add(r);
  }
  data.put("]" + pieces[2]);
  csv.close();
  data.close();
  h5.finish(info);
}

}  // namespace

void write_mc_outputs(const McPlan& plan, const McRecordSource& records, const McSummaryInfo& info, const fs::path& dir)
{
  const std::vector<size_t> order = mc_table_order(records);
  SeriesScratch scratch(dir / ".mc_series.scratch", records.size(),
                        plan.series_rows.size() * plan.series_columns.size());
  write_runs_json(records, scratch, dir / "mc_runs.json");
  write_tables(plan, records, order, report_json_pieces(plan, records, scratch, info), info, dir);
#ifdef KESTREL_HAVE_REPORT
  try {
    report::write_mc_html_file((dir / "mc_report_data.json").string(), (dir / "mc_report.html").string());
  } catch (const std::exception& e) {
    throw OutputError(e.what());
  }
#endif
}

void write_mc_outputs(const McPlan& plan, const std::vector<McRecord>& records, const McSummaryInfo& info,
                      const fs::path& dir)
{
  write_mc_outputs(plan, McMemoryRecords(records), info, dir);
}

}  // namespace harness
