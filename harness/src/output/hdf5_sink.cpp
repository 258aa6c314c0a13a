// hdf5_sink.cpp: results.h5 streamed in chunks (HDF5 C API), and its reader.
#include <algorithm>
#include <cstring>

#include <hdf5.h>

#include "harness/output/outputs.h"
#include "output/h5_util.h"

namespace harness {

namespace {

using namespace h5;

std::string dataset_path(const QuantityInfo& q) { return q.group.empty() ? "/" + q.name : "/" + q.group + "/" + q.name; }

}  // namespace

struct Hdf5Sink::File {
  H5Id file;
  struct Ds {
    H5Id id;
    size_t first_col = 0, n = 0;
  };
  std::vector<Ds> ds;
  std::vector<double> scratch;  // chunk rows x widest quantity
  uint64_t rows = 0;
};

namespace {
// /events: one row per applied event (tick, t [s]), its name and actions as attributes.
void write_events(hid_t file, const std::vector<AppliedEvent>& log, const std::string& path)
{
  hsize_t dims[2] = {log.size(), 2};
  H5Id space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  H5Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(dcpl, 0);  // no wall-clock times: the same run gives the same bytes
  H5Id d(H5Dcreate2(file, "/events", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose);
  h5check(d, "creating /events", path);
  std::vector<double> v;
  std::vector<std::string> names, what;
  for (const AppliedEvent& e : log) {
    v.push_back(static_cast<double>(e.tick));
    v.push_back(e.t);
    names.push_back(e.name);
    what.push_back(e.what);
  }
  if (!v.empty() && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw OutputError(path + ": cannot write /events");
  attr_strings(d, "columns", {"tick", "t"}, path);
  attr_string(d, "unit", "-, s", path);
  if (!log.empty()) {
    attr_strings(d, "names", names, path);
    attr_strings(d, "actions", what, path);
  }
}
}  // namespace

Hdf5Sink::Hdf5Sink(std::string path, const Scenario& sc, std::string manifest_text)
    : path_(std::move(path)), sc_(sc), manifest_(std::move(manifest_text))
{
}

Hdf5Sink::~Hdf5Sink() = default;

void Hdf5Sink::begin(const RecordLayout& layout, uint64_t expected_rows)
{
  h5_setup();
  f_ = std::make_unique<File>();
  // no object has its wall-clock creation and change times (HDF5 stores
  // them by default): the same run gives the same bytes, and a run
  // continued from a checkpoint the bytes of an uninterrupted one
  H5Id fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_obj_track_times(fcpl, 0);
  H5Id gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  H5Pset_obj_track_times(gcpl, 0);
  f_->file = H5Id(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT), H5Fclose);
  h5check(f_->file, "creating the file", path_);
  const hid_t file = f_->file;
  std::vector<std::string> groups;
  // chunk: up to 1024 samples, never more than the run has
  const hsize_t chunk_rows = std::max<hsize_t>(1, std::min<hsize_t>(1024, expected_rows));
  for (const QuantityInfo& q : layout.quantities) {
    if (!q.group.empty() && std::find(groups.begin(), groups.end(), q.group) == groups.end()) {
      H5Id g(H5Gcreate2(file, ("/" + q.group).c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose);
      h5check(g, "creating group /" + q.group, path_);
      groups.push_back(q.group);
    }
    hsize_t dims[2] = {0, q.num_cols}, maxdims[2] = {H5S_UNLIMITED, q.num_cols};
    H5Id space(H5Screate_simple(2, dims, maxdims), H5Sclose);
    H5Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(dcpl, 0);
    hsize_t chunk[2] = {chunk_rows, q.num_cols};
    H5Pset_chunk(dcpl, 2, chunk);
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 1);
    const std::string p = dataset_path(q);
    File::Ds d;
    // rows arrive in whole chunks: no raw-data chunk cache (it would hold up
    // to 1 MiB per dataset, growing with the run until full)
    H5Id dapl(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose);
    H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, 1.0);
    d.id = H5Id(H5Dcreate2(file, p.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, dapl), H5Dclose);
    h5check(d.id, "creating " + p, path_);
    attr_string(d.id, "unit", q.unit, path_);
    attr_string(d.id, "frame", q.frame, path_);
    std::vector<std::string> cols;
    for (size_t c = 0; c < q.num_cols; ++c) cols.push_back(layout.columns[q.first_col + c].name);
    attr_strings(d.id, "columns", cols, path_);
    d.first_col = q.first_col;
    d.n = q.num_cols;
    f_->ds.push_back(std::move(d));
  }
  std::vector<std::string> names, units, dsets;
  for (const Column& c : layout.columns) {
    names.push_back(c.name);
    units.push_back(c.unit);
    dsets.push_back(c.group.empty() ? "/" + c.quantity : "/" + c.group + "/" + c.quantity);
  }
  attr_strings(file, "column_names", names, path_);
  attr_strings(file, "column_units", units, path_);
  attr_strings(file, "column_datasets", dsets, path_);
  attr_string(file, "kestrel_version", version(), path_);
  attr_string(file, "scenario", sc_.name, path_);
  attr_scalar<unsigned long long>(file, "seed", H5T_NATIVE_ULLONG, H5T_STD_U64LE, sc_.seed, path_);
  attr_scalar<double>(file, "dt", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, sc_.rates.dt, path_);
  attr_scalar<double>(file, "duration", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, sc_.duration, path_);
  attr_string(file, "manifest", manifest_, path_);
  attr_scalar<unsigned long long>(file, "rows", H5T_NATIVE_ULLONG, H5T_STD_U64LE, 0ull, path_);
  attr_scalar<int>(file, "complete", H5T_NATIVE_INT, H5T_STD_I32LE, 0, path_);
  size_t widest = 1;
  for (const QuantityInfo& q : layout.quantities) widest = std::max(widest, q.num_cols);
  f_->scratch.resize(1024 * widest);
  nc_total_ = layout.columns.size();
}

void Hdf5Sink::write(const double* rows, size_t n)
{
  if (!f_ || n == 0) return;
  const size_t nc = nc_total_;
  for (File::Ds& d : f_->ds) {
    if (f_->scratch.size() < n * d.n) f_->scratch.resize(n * d.n);
    double* s = f_->scratch.data();
    for (size_t r = 0; r < n; ++r)
      for (size_t c = 0; c < d.n; ++c) s[r * d.n + c] = rows[r * nc + d.first_col + c];
    hsize_t newdims[2] = {f_->rows + n, d.n};
    if (H5Dset_extent(d.id, newdims) < 0) throw OutputError(path_ + ": cannot extend a dataset");
    H5Id fspace(H5Dget_space(d.id), H5Sclose);
    hsize_t start[2] = {f_->rows, 0}, count[2] = {n, d.n};
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
    H5Id mspace(H5Screate_simple(2, count, nullptr), H5Sclose);
    if (H5Dwrite(d.id, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, s) < 0)
      throw OutputError(path_ + ": cannot write (disk full?)");
  }
  f_->rows += n;
}

void Hdf5Sink::end(bool complete)
{
  if (!f_) return;
  attr_scalar<unsigned long long>(f_->file, "rows", H5T_NATIVE_ULLONG, H5T_STD_U64LE, f_->rows, path_);
  attr_scalar<int>(f_->file, "complete", H5T_NATIVE_INT, H5T_STD_I32LE, complete ? 1 : 0, path_);
  if (events_ && !sc_.events.empty()) write_events(f_->file, *events_, path_);
  const bool flushed = H5Fflush(f_->file, H5F_SCOPE_GLOBAL) >= 0;
  f_->ds.clear();
  const bool closed = H5Fclose(f_->file.id) >= 0;
  f_->file.id = -1;
  f_.reset();
  if (!flushed || !closed) throw OutputError(path_ + ": cannot flush and close (disk full?)");
}

namespace {

// Storage of the first dataset: chunked, deflated.
void read_layout(hid_t ds, Hdf5Table& t)
{
  H5Id dcpl(H5Dget_create_plist(ds), H5Pclose);
  t.chunked = H5Pget_layout(dcpl) == H5D_CHUNKED;
  const int nf = H5Pget_nfilters(dcpl);
  for (int i = 0; i < nf; ++i) {
    unsigned flags = 0, vals[8], cfg = 0;
    size_t n = 8;
    char nm[64];
    if (H5Pget_filter2(dcpl, static_cast<unsigned>(i), &flags, &n, vals, sizeof nm, nm, &cfg) == H5Z_FILTER_DEFLATE)
      t.deflate = true;
  }
}

// The file's attributes: version, scenario, manifest, seed, dt, duration, complete.
void read_run_attributes(hid_t file, Hdf5Table& t)
{
  t.version = read_attr_string(file, "kestrel_version");
  t.scenario = read_attr_string(file, "scenario");
  t.manifest = read_attr_string(file, "manifest");
  auto read_scalar = [file](const char* name, hid_t type, void* out) {
    if (H5Aexists(file, name) <= 0) return;
    H5Id a(H5Aopen(file, name, H5P_DEFAULT), H5Aclose);
    if (a >= 0) H5Aread(a, type, out);
  };
  unsigned long long seed = 0;
  int complete = 0;
  read_scalar("seed", H5T_NATIVE_ULLONG, &seed);
  read_scalar("dt", H5T_NATIVE_DOUBLE, &t.dt);
  read_scalar("duration", H5T_NATIVE_DOUBLE, &t.duration);
  read_scalar("complete", H5T_NATIVE_INT, &complete);
  t.seed = seed;
  t.complete = complete != 0;
}

// The /events dataset: (tick, t) per applied event, names and actions as attributes.
void read_events(hid_t file, const std::string& path, Hdf5Table& t)
{
  H5Id ds(H5Dopen2(file, "/events", H5P_DEFAULT), H5Dclose);
  h5check(ds, "opening /events", path);
  H5Id space(H5Dget_space(ds), H5Sclose);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  std::vector<double> buf(static_cast<size_t>(dims[0] * dims[1]));
  if (!buf.empty() && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    throw OutputError(path + ": cannot read /events");
  if (dims[0] > 0) {
    const std::vector<std::string> names = read_attr_strings(ds, "names"), what = read_attr_strings(ds, "actions");
    for (size_t i = 0; i < dims[0] && i < names.size() && i < what.size(); ++i)
      t.events.push_back({names[i], static_cast<uint64_t>(buf[2 * i]), buf[2 * i + 1], what[i]});
  }
}

}  // namespace

Hdf5Table read_hdf5(const std::string& path)
{
  h5_setup();
  Hdf5Table t;
  H5Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  h5check(file, "opening the file", path);
  t.names = read_attr_strings(file, "column_names");
  t.units = read_attr_strings(file, "column_units");
  t.datasets = read_attr_strings(file, "column_datasets");
  if (t.names.size() != t.datasets.size()) throw OutputError(path + ": column attributes disagree");
  // read each dataset once, then place its components in the flat table
  std::vector<std::string> seen;
  for (size_t c = 0; c < t.names.size(); ++c) {
    const std::string& dp = t.datasets[c];
    if (std::find(seen.begin(), seen.end(), dp) != seen.end()) continue;
    seen.push_back(dp);
    H5Id ds(H5Dopen2(file, dp.c_str(), H5P_DEFAULT), H5Dclose);
    h5check(ds, "opening " + dp, path);
    H5Id space(H5Dget_space(ds), H5Sclose);
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(space) != 2) throw OutputError(path + ": " + dp + " is not 2-D");
    H5Sget_simple_extent_dims(space, dims, nullptr);
    if (seen.size() == 1) {
      t.rows = dims[0];
      t.data.assign(static_cast<size_t>(t.rows) * t.names.size(), 0.0);
      read_layout(ds, t);
    }
    if (dims[0] != t.rows) throw OutputError(path + ": " + dp + " has a different number of samples");
    std::vector<double> buf(static_cast<size_t>(dims[0] * dims[1]));
    if (!buf.empty() && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
      throw OutputError(path + ": cannot read " + dp);
    const std::vector<std::string> comps = read_attr_strings(ds, "columns");
    for (size_t k = 0; k < comps.size() && k < dims[1]; ++k) {
      const auto it = std::find(t.names.begin(), t.names.end(), comps[k]);
      if (it == t.names.end()) continue;
      const size_t col = static_cast<size_t>(it - t.names.begin());
      for (uint64_t r = 0; r < t.rows; ++r) t.data[r * t.names.size() + col] = buf[r * dims[1] + k];
    }
  }
  read_run_attributes(file, t);
  if (H5Lexists(file, "/events", H5P_DEFAULT) > 0) read_events(file, path, t);
  return t;
}

}  // namespace harness
