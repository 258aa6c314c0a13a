// h5_util: small helpers over the HDF5 C API shared by the run's results
// file (hdf5_sink.cpp) and a Monte Carlo campaign's summary (mc_output.cpp).
//
// Private to the harness library.
#ifndef HARNESS_SRC_H5_UTIL_H
#define HARNESS_SRC_H5_UTIL_H

#include <string>
#include <vector>

#include <hdf5.h>

#include "harness/output/outputs.h"

namespace harness::h5 {

// Before the library's first use: no clean-up at exit.  A file whose
// writes failed (disk full) cannot be closed, and HDF5's exit handler then
// crashes on it; the sink closes every file it opens itself (end()), and a
// failed run's files are deleted with its working folder.  Errors become
// exceptions, not stderr noise.
inline void h5_setup()
{
  static const bool once = [] {
    H5dont_atexit();
    H5open();
    return true;
  }();
  (void)once;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

// RAII for HDF5 identifiers.
struct H5Id {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  H5Id() = default;
  H5Id(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~H5Id() { reset(); }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  H5Id(H5Id&& o) noexcept : id(o.id), close(o.close) { o.id = -1; }
  H5Id& operator=(H5Id&& o) noexcept
  {
    if (this != &o) {
      reset();
      id = o.id;
      close = o.close;
      o.id = -1;
    }
    return *this;
  }
  void reset()
  {
    if (id >= 0 && close) close(id);
    id = -1;
  }
  operator hid_t() const { return id; }
};

inline void h5check(hid_t id, const std::string& what, const std::string& path)
{
  if (id < 0) throw OutputError(path + ": HDF5 error while " + what);
}

inline void attr_string(hid_t obj, const char* name, const std::string& value, const std::string& path)
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

inline void attr_strings(hid_t obj, const char* name, const std::vector<std::string>& values, const std::string& path)
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
  if (H5Aexists(obj, name) > 0) H5Adelete(obj, name);
  H5Id space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Id a(H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  h5check(a, std::string("creating attribute ") + name, path);
  if (H5Awrite(a, mem_type, &value) < 0) throw OutputError(path + ": cannot write attribute " + name);
}

inline std::string read_attr_string(hid_t obj, const char* name)
{
  if (H5Aexists(obj, name) <= 0) return "";
  H5Id a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  if (a < 0) return "";
  H5Id type(H5Aget_type(a), H5Tclose);
  const size_t n = H5Tget_size(type);
  std::string s(n, '\0');
  H5Aread(a, type, &s[0]);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

inline std::vector<std::string> read_attr_strings(hid_t obj, const char* name)
{
  if (H5Aexists(obj, name) <= 0) return {};
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

}  // namespace harness::h5

#endif  // HARNESS_SRC_H5_UTIL_H
