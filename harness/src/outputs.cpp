// outputs.cpp: HDF5 (C API), CSV, manifest and report-data writers.
#include "harness/outputs.h"

#include <cmath>

#include <cstdio>
#include <fstream>
#include <memory>

#include <hdf5.h>
#include <nlohmann/json.hpp>

#include "json_util.h"

namespace harness {

namespace {

using nlohmann::json;

// RAII for HDF5 identifiers.
struct H5Id {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  H5Id(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~H5Id()
  {
    if (id >= 0 && close) close(id);
  }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  operator hid_t() const { return id; }
};

void h5check(hid_t id, const std::string& what, const std::string& path)
{
  if (id < 0) throw OutputError(path + ": HDF5 error while " + what);
}

void attr_string(hid_t obj, const char* name, const std::string& value, const std::string& path)
{
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  h5check(type, "creating a string type", path);
  H5Tset_size(type, value.empty() ? 1 : value.size());
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  H5Id space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Id a(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  h5check(a, std::string("creating attribute ") + name, path);
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  if (H5Awrite(a, type, v.data()) < 0) throw OutputError(path + ": cannot write attribute " + name);
}

void attr_strings(hid_t obj, const char* name, const std::vector<std::string>& values, const std::string& path)
{
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  hsize_t n = values.size();
  H5Id space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  H5Id a(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  h5check(a, std::string("creating attribute ") + name, path);
  std::vector<const char*> ptrs;
  for (const auto& s : values) ptrs.push_back(s.c_str());
  if (H5Awrite(a, type, ptrs.data()) < 0) throw OutputError(path + ": cannot write attribute " + name);
}

template <class T>
void attr_scalar(hid_t obj, const char* name, hid_t mem_type, hid_t file_type, T value, const std::string& path)
{
  H5Id space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Id a(H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  h5check(a, std::string("creating attribute ") + name, path);
  if (H5Awrite(a, mem_type, &value) < 0) throw OutputError(path + ": cannot write attribute " + name);
}

std::string read_attr_string(hid_t obj, const char* name)
{
  H5Id a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  if (a < 0) return "";
  H5Id type(H5Aget_type(a), H5Tclose);
  const size_t n = H5Tget_size(type);
  std::string s(n, '\0');
  H5Aread(a, type, &s[0]);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::vector<std::string> read_attr_strings(hid_t obj, const char* name)
{
  H5Id a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  if (a < 0) return {};
  H5Id space(H5Aget_space(a), H5Sclose);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  std::vector<char*> ptrs(static_cast<size_t>(n), nullptr);
  H5Aread(a, type, ptrs.data());
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, ptrs.data());
  return out;
}

}  // namespace

void write_hdf5(const std::string& path, const Recorder& rec, const Scenario& sc, const std::string& manifest)
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions, not stderr noise
  H5Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  h5check(file, "creating the file", path);
  const hsize_t rows = rec.rows(), cols = rec.num_columns();
  hsize_t dims[2] = {rows, cols};
  H5Id space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  H5Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  hsize_t chunk[2] = {rows < 1024 ? (rows > 0 ? rows : 1) : 1024, cols > 0 ? cols : 1};
  H5Pset_chunk(dcpl, 2, chunk);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 4);
  H5Id ds(H5Dcreate2(file, "telemetry", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose);
  h5check(ds, "creating /telemetry", path);
  if (rows > 0 && cols > 0 && H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, rec.data()) < 0)
    throw OutputError(path + ": cannot write /telemetry");
  std::vector<std::string> names, units;
  for (const Column& c : rec.columns()) {
    names.push_back(c.name);
    units.push_back(c.unit);
  }
  attr_strings(ds, "column_names", names, path);
  attr_strings(ds, "column_units", units, path);
  attr_string(file, "kestrel_version", version(), path);
  attr_string(file, "scenario", sc.name, path);
  attr_scalar<unsigned long long>(file, "seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, sc.seed, path);
  attr_scalar<double>(file, "dt", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, sc.rates.dt, path);
  attr_scalar<double>(file, "duration", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, sc.duration, path);
  attr_string(file, "manifest", manifest, path);
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) throw OutputError(path + ": cannot flush");
}

Hdf5Table read_hdf5(const std::string& path)
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Hdf5Table t;
  H5Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  h5check(file, "opening the file", path);
  H5Id ds(H5Dopen2(file, "telemetry", H5P_DEFAULT), H5Dclose);
  h5check(ds, "opening /telemetry", path);
  H5Id space(H5Dget_space(ds), H5Sclose);
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space) != 2) throw OutputError(path + ": /telemetry is not 2-D");
  H5Sget_simple_extent_dims(space, dims, nullptr);
  t.rows = dims[0];
  t.data.resize(static_cast<size_t>(dims[0] * dims[1]));
  if (!t.data.empty() && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data.data()) < 0)
    throw OutputError(path + ": cannot read /telemetry");
  H5Id dcpl(H5Dget_create_plist(ds), H5Pclose);
  t.chunked = H5Pget_layout(dcpl) == H5D_CHUNKED;
  const int nf = H5Pget_nfilters(dcpl);
  for (int i = 0; i < nf; ++i) {
    unsigned flags = 0;
    size_t n = 0;
    unsigned vals[8];
    char nm[64];
    unsigned cfg = 0;
    if (H5Pget_filter2(dcpl, static_cast<unsigned>(i), &flags, &n, vals, sizeof nm, nm, &cfg) == H5Z_FILTER_DEFLATE)
      t.deflate = true;
  }
  t.names = read_attr_strings(ds, "column_names");
  t.units = read_attr_strings(ds, "column_units");
  t.version = read_attr_string(file, "kestrel_version");
  t.scenario = read_attr_string(file, "scenario");
  t.manifest = read_attr_string(file, "manifest");
  {
    H5Id a(H5Aopen(file, "seed", H5P_DEFAULT), H5Aclose);
    unsigned long long s = 0;
    if (a >= 0) H5Aread(a, H5T_NATIVE_ULLONG, &s);
    t.seed = s;
  }
  for (auto p : {std::make_pair("dt", &t.dt), std::make_pair("duration", &t.duration)}) {
    H5Id a(H5Aopen(file, p.first, H5P_DEFAULT), H5Aclose);
    if (a >= 0) H5Aread(a, H5T_NATIVE_DOUBLE, p.second);
  }
  return t;
}

void write_text(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError(path + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw OutputError(path + ": write failed");
}

void write_csv(const std::string& path, const Recorder& rec)
{
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!f) throw OutputError(path + ": cannot open for writing");
  const size_t nc = rec.num_columns();
  for (size_t c = 0; c < nc; ++c)
    std::fprintf(f.get(), "%s%s [%s]", c ? "," : "", rec.columns()[c].name.c_str(), rec.columns()[c].unit.c_str());
  std::fputc('\n', f.get());
  for (uint64_t r = 0; r < rec.rows(); ++r) {
    for (size_t c = 0; c < nc; ++c) std::fprintf(f.get(), "%s%.17g", c ? "," : "", rec.at(r, c));
    std::fputc('\n', f.get());
  }
  if (std::ferror(f.get())) throw OutputError(path + ": write failed");
}

std::string manifest_text(const Scenario& sc, const std::vector<Override>& overrides)
{
  json j;
  j["kestrel_manifest"] = 1;
  j["kestrel_version"] = version();
  j["source"] = sc.source_file;
  json ov = json::array();
  for (const Override& o : overrides) ov.push_back(o.path + "=" + o.value);
  j["overrides"] = ov;
  j["scenario"] = scenario_to_json(sc);
  return j.dump(2) + "\n";
}

std::string report_data_text(const Run& run)
{
  const Scenario& sc = run.scenario();
  const Recorder& rec = run.recorder();
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
               {"num_thrusters", sc.thrusters.size()}};
  json series = json::object(), units = json::object();
  for (size_t c = 0; c < rec.num_columns(); ++c) {
    const Column& col = rec.columns()[c];
    if (col.name.rfind("q_BN_", 0) == 0) continue;  // in `attitude`
    series[col.name] = rec.column(col.name);
    units[col.name] = col.unit;
  }
  j["series"] = series;
  j["units"] = units;
  json q = json::array();
  const size_t q0 = rec.column_index("q_BN_0");
  for (uint64_t r = 0; r < rec.rows(); ++r)
    q.push_back({rec.at(r, q0), rec.at(r, q0 + 1), rec.at(r, q0 + 2), rec.at(r, q0 + 3)});
  j["attitude"] = {{"t", rec.column("t")}, {"q_BN", q}};
  json axes = json::array();
  for (const auto& a : run.wheel_axes_B()) axes.push_back({a[0], a[1], a[2]});
  json thr = json::array();
  for (const ThrusterSpec& t : sc.thrusters)
    thr.push_back({{"name", t.name},
                   {"r_B", {t.r_B(0), t.r_B(1), t.r_B(2)}},
                   {"dir_B", {t.dir_B(0), t.dir_B(1), t.dir_B(2)}}});
  json wpos = json::array();
  for (const WheelSpec& w : sc.wheels) wpos.push_back({w.params.r_WB_B(0), w.params.r_WB_B(1), w.params.r_WB_B(2)});
  j["geometry"] = {{"wheel_axes_B", axes}, {"wheel_positions_B", wpos}, {"thrusters", thr}};
  j["dataflow_dot"] = run.dataflow().to_dot(sc.name);
  json summ = json::object();
  for (const SummaryItem& it : run.summary())
    summ[it.key] = {{"value", std::isfinite(it.value) ? json(it.value) : json(nullptr)}, {"unit", it.unit}, {"what", it.what}};
  j["summary"] = summ;
  return j.dump() + "\n";
}

}  // namespace harness
