// kestrel.fsw: element access of the field tables (fsw_field.h).
#include "fsw_field.h"

namespace kpy {

size_t kind_bytes(Kind k)
{
  switch (k) {
    case Kind::Real: return sizeof(fsw_real);
    case Kind::Int: return sizeof(int);
    case Kind::U8: return 1;
    case Kind::U32: return sizeof(uint32_t);
    case Kind::U64: return sizeof(uint64_t);
  }
  return 1;
}

double element(const void* p, Kind k, size_t i)
{
  switch (k) {
    case Kind::Real: return static_cast<double>(static_cast<const fsw_real*>(p)[i]);
    case Kind::Int: return static_cast<double>(static_cast<const int*>(p)[i]);
    case Kind::U8: return static_cast<double>(static_cast<const uint8_t*>(p)[i]);
    case Kind::U32: return static_cast<double>(static_cast<const uint32_t*>(p)[i]);
    case Kind::U64: return static_cast<double>(static_cast<const uint64_t*>(p)[i]);
  }
  return 0.0;
}

void put(void* p, Kind k, size_t i, const py::handle& h, const std::string& name)
{
  if (k == Kind::Real) {
    static_cast<fsw_real*>(p)[i] = static_cast<fsw_real>(py::float_(py::reinterpret_borrow<py::object>(h)).cast<double>());
    return;
  }
  py::object o = py::reinterpret_borrow<py::object>(h);
  if (py::isinstance<py::float_>(o)) {
    const double d = o.cast<double>();
    if (!(std::isfinite(d) && d == std::floor(d))) throw py::value_error(name + ": an integer");
    o = py::int_(o);
  }
  if (k == Kind::U64) {
    const py::int_ n(o);
    if (n < py::int_(0)) throw py::value_error(name + ": >= 0");
    const unsigned long long u = PyLong_AsUnsignedLongLong(n.ptr());
    if (PyErr_Occurred()) {
      PyErr_Clear();
      throw py::value_error(name + ": out of the range of uint64");
    }
    static_cast<uint64_t*>(p)[i] = static_cast<uint64_t>(u);
    return;
  }
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(py::int_(o).ptr(), &overflow);
  if (overflow != 0) throw py::value_error(name + ": out of range");
  if (k == Kind::Int) {
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      throw py::value_error(name + ": out of the range of a C int");
    static_cast<int*>(p)[i] = static_cast<int>(v);
  } else if (k == Kind::U32) {
    if (v < 0 || v > static_cast<long long>(UINT32_MAX)) throw py::value_error(name + ": 0..2**32-1");
    static_cast<uint32_t*>(p)[i] = static_cast<uint32_t>(v);
  } else {
    if (v < 0 || v > 255) throw py::value_error(name + ": 0..255");
    static_cast<uint8_t*>(p)[i] = static_cast<uint8_t>(v);
  }
}

py::object get_raw(const void* p, Kind k, int rows, int cols)
{
  if (rows == 0) {
    if (k == Kind::Real) return py::float_(element(p, k, 0));
    if (k == Kind::U64) return py::int_(static_cast<unsigned long long>(*static_cast<const uint64_t*>(p)));
    return py::int_(static_cast<long long>(element(p, k, 0)));
  }
  if (cols == 0) {
    py::array_t<double> a(rows);
    for (int i = 0; i < rows; ++i) a.mutable_at(i) = element(p, k, static_cast<size_t>(i));
    return std::move(a);
  }
  py::array_t<double> a({rows, cols});
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) a.mutable_at(i, j) = element(p, k, static_cast<size_t>(i * cols + j));
  return std::move(a);
}

void set_raw(void* p, Kind k, int rows, int cols, bool capacity, const py::handle& h, const std::string& name)
{
  if (rows == 0) {
    if (!(py::isinstance<py::int_>(h) || py::isinstance<py::float_>(h) ||
          py::isinstance(h, py::module_::import("numpy").attr("number"))))
      throw py::type_error(name + ": a number");
    put(p, k, 0, h, name);
    return;
  }
  if (py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h) || h.is_none())
    throw py::type_error(name + ": an array");
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
    throw py::type_error(name + ": an array of numbers");
  }
  if (!a) {
    PyErr_Clear();
    throw py::type_error(name + ": an array of numbers");
  }
  const int want_nd = cols == 0 ? 1 : 2;
  const std::string shape =
      cols == 0 ? "(" + std::to_string(rows) + ",)" : "(" + std::to_string(rows) + ", " + std::to_string(cols) + ")";
  const bool rows_ok = a.ndim() == want_nd && (capacity ? a.shape(0) <= rows : a.shape(0) == rows);
  const bool cols_ok = want_nd == 1 || (a.ndim() == 2 && a.shape(1) == cols);
  if (!rows_ok || !cols_ok)
    throw py::value_error(name + ": shape " + shape + (capacity ? " (at most that many rows)" : ""));
  const size_t width = static_cast<size_t>(cols == 0 ? 1 : cols);
  const size_t n = static_cast<size_t>(a.shape(0)) * width;
  const size_t total = static_cast<size_t>(rows) * width;
  // checked first, written after: a bad element leaves the field unchanged
  std::vector<unsigned char> backup(total * kind_bytes(k));
  std::memcpy(backup.data(), p, backup.size());
  try {
    const double* d = a.data();
    for (size_t i = 0; i < total; ++i) put(p, k, i, py::float_(i < n ? d[i] : 0.0), name);
  } catch (...) {
    std::memcpy(p, backup.data(), backup.size());
    throw;
  }
}

py::object status_obj(int s)
{
  return py::module_::import("kestrel.fsw").attr("Status")(s);
}

void raise_config_error(const std::string& who, int status, const std::string& field, const std::string& how)
{
  const std::string name = fsw_status_name(static_cast<FswStatus>(status));
  const std::string msg = who + ": " + name + (field.empty() ? "" : " in field '" + field + "'") + how;
  py::object cls = py::module_::import("kestrel.fsw").attr("ConfigError");
  py::object e = cls(msg);
  e.attr("status") = status_obj(status);
  e.attr("field") = field.empty() ? py::object(py::none()) : py::object(py::str(field));
  PyErr_SetObject(cls.ptr(), e.ptr());
  throw py::error_already_set();
}

}  // namespace kpy
