// convert: copies across the FSW boundary (fsw_real may be float or double)
// and between plain arrays and Eigen, for the harness's own files.
#ifndef HARNESS_CONVERT_H
#define HARNESS_CONVERT_H

#include <Eigen/Dense>

namespace harness {

inline Eigen::Vector3d ev(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

template <class Out, class In>
void copy3(Out* out, const In* in)
{
  for (int i = 0; i < 3; ++i) out[i] = static_cast<Out>(in[i]);
}

template <class Out>
void put3(Out* out, const Eigen::Vector3d& v)
{
  for (int i = 0; i < 3; ++i) out[i] = static_cast<Out>(v(i));
}

}  // namespace harness

#endif  // HARNESS_CONVERT_H
