// Test helpers shared by the magnetorquer module tests (mtq_map,
// mtq_desat): plain double 3-vector algebra, independent of fsw_vec.
#ifndef KESTREL_MTQ_TEST_UTIL_H
#define KESTREL_MTQ_TEST_UTIL_H

#include <cmath>

namespace mtqt {

inline void cross(double o[3], const double a[3], const double b[3])
{
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const double a[3]) { return std::sqrt(dot(a, a)); }
// Copy an array of any real type into doubles.
template <class R>
void to_d(double o[3], const R* a)
{
  for (int k = 0; k < 3; k++) o[k] = static_cast<double>(a[k]);
}

}  // namespace mtqt

#endif  // KESTREL_MTQ_TEST_UTIL_H
