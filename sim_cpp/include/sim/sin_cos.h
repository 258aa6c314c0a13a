// sin_cos: sine and cosine of one angle together, for the plant's rotor
// angles (a fully-coupled or jittering wheel needs both for each wheel in
// every derivative evaluation; libm's sincos was 18 % of an RK4 step of the
// hub with four fully-coupled wheels).  docs/dynamics.md "The derivative as
// computed" states the accuracy.
//
// Method, for |x| <= kSinCosReducedMax (1e10 rad, 0.3 years at 1,000 rad/s):
//   k = nearest integer to x 2/pi, r = x - k pi/2 with pi/2 split into five
//   parts, the first four of at most 20 significant bits so that k P_i is
//   exact for |k| < 2^33 (Cody and Waite's reduction; the first difference
//   is exact by Sterbenz's lemma, the pieces carry pi/2 to ~133 bits);
//   sin r and cos r on |r| <= pi/4 (plus the rounding of k) by their Taylor
//   series to r^17 and r^16 (truncation < 1e-19), in Estrin form;
//   the quadrant k mod 4 picks and signs them.
// Beyond that bound, and for inf or NaN, std::sin and std::cos.
// Accuracy (sim_test_sin_cos, against std::sin/std::cos over 3 10^6
// arguments up to the bound): |error| <= 4.5e-16 absolute; the rotor angle
// itself carries an absolute rounding of ulp(x)/2 = 1.2e-16 at x = 2 and
// 1e-6 at x = 1e10, so the reduction adds nothing the state does not
// already carry.  Only +, -, * and one comparison: the same bits on every
// IEEE-754 double platform without fused multiply-add contraction, and no
// library call.
#ifndef SIM_SIN_COS_H
#define SIM_SIN_COS_H

#include <cmath>
#include <cstdint>

namespace sim {

struct SinCos {
  double s;  // sin x
  double c;  // cos x
};

inline constexpr double kSinCosReducedMax = 1e10;

#if defined(__GNUC__)
#define SIM_SIN_COS_INLINE inline __attribute__((always_inline))
#else
#define SIM_SIN_COS_INLINE inline
#endif

// Inlined: in the derivative the wheels' calls then overlap.
SIM_SIN_COS_INLINE SinCos sin_cos(double x)
{
  if (!(std::fabs(x) <= kSinCosReducedMax)) return {std::sin(x), std::cos(x)};
  // pi/2 = P1 + P2 + P3 + P4 + P5 + O(2e-43); P1..P4 have <= 20 significant bits
  constexpr double P1 = 0x1.921fcp+0;
  constexpr double P2 = -0x1.5777ap-21;
  constexpr double P3 = -0x1.73dccp-43;
  constexpr double P4 = 0x1.898ccp-64;
  constexpr double P5 = 0x1.45c06e0e68948p-86;
  constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
  constexpr double kRound = 0x1.8p52;  // adding and removing it rounds to an integer (|v| < 2^51)
  const double k = (x * kTwoOverPi + kRound) - kRound;
  const double r = (((x - k * P1) - k * P2) - k * P3 - k * P4) - k * P5;
  const double z = r * r;
  // Taylor coefficients 1/n! (signed), rounded to double, evaluated in
  // Estrin's form (a chain of 4 multiplications instead of Horner's 8)
  const double z2 = z * z;
  const double z4 = z2 * z2;
  const double ps = ((-1.0 / 6.0 + z * (1.0 / 120.0)) + z2 * (-1.0 / 5040.0 + z * (1.0 / 362880.0))) +
                    z4 * ((-1.0 / 39916800.0 + z * (1.0 / 6227020800.0)) +
                          z2 * (-1.0 / 1307674368000.0 + z * (1.0 / 355687428096000.0)));
  const double pc = ((1.0 / 24.0 + z * (-1.0 / 720.0)) + z2 * (1.0 / 40320.0 + z * (-1.0 / 3628800.0))) +
                    z4 * ((1.0 / 479001600.0 + z * (-1.0 / 87178291200.0)) + z2 * (1.0 / 20922789888000.0));
  const double sr = r + (r * z) * ps;
  const double cr = (1.0 - 0.5 * z) + z2 * pc;
  // quadrant q = k mod 4: (sin, cos) = (sr, cr), (cr, -sr), (-sr, -cr), (-cr, sr);
  // selected without branches (the quadrant of a spinning rotor is random)
  const auto q = static_cast<uint64_t>(static_cast<int64_t>(k));
  const bool odd = (q & 1u) != 0;
  const double s_abs = odd ? cr : sr;
  const double c_abs = odd ? sr : cr;
  const double s_sign = (q & 2u) != 0 ? -1.0 : 1.0;
  const double c_sign = ((q + 1u) & 2u) != 0 ? -1.0 : 1.0;
  return {s_sign * s_abs, c_sign * c_abs};
}

}  // namespace sim

#undef SIM_SIN_COS_INLINE

#endif  // SIM_SIN_COS_H
