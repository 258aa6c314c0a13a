// Internal helpers for configuration checks: every failure names the field and
// the offending value (std::invalid_argument).
#ifndef SIM_VALIDATE_UTIL_H
#define SIM_VALIDATE_UTIL_H

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace sim {
namespace detail {

[[noreturn]] inline void fail(const std::string& field, double value, const char* rule)
{
  std::ostringstream os;
  os.precision(17);
  os << "sim: invalid configuration: " << field << " = " << value << " (" << rule << ")";
  throw std::invalid_argument(os.str());
}

[[noreturn]] inline void fail_vec(const std::string& field, const Eigen::Vector3d& v, const char* rule)
{
  std::ostringstream os;
  os.precision(17);
  os << "sim: invalid configuration: " << field << " = [" << v.x() << ", " << v.y() << ", "
     << v.z() << "] (" << rule << ")";
  throw std::invalid_argument(os.str());
}

inline void require_finite(const std::string& field, double v)
{
  if (!std::isfinite(v)) fail(field, v, "must be finite");
}

inline void require_finite(const std::string& field, const Eigen::Vector3d& v)
{
  if (!v.allFinite()) fail_vec(field, v, "must be finite");
}

inline void require_positive(const std::string& field, double v)
{
  require_finite(field, v);
  if (!(v > 0.0)) fail(field, v, "must be > 0");
}

inline void require_non_negative(const std::string& field, double v)
{
  require_finite(field, v);
  if (!(v >= 0.0)) fail(field, v, "must be >= 0");
}

}  // namespace detail
}  // namespace sim

#endif  // SIM_VALIDATE_UTIL_H
