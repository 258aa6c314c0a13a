// sim::sin_cos (the rotor angles' sine and cosine) against libm's std::sin
// and std::cos (glibc's are correctly rounded in practice, < 1 ulp, with a
// full Payne-Hanek reduction: an independent implementation), over the
// ranges the plant meets: a few turns, long runs up to the reduction's
// bound, the hard cases next to multiples of pi/2, and beyond the bound.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "sim/sin_cos.h"

namespace {

// Absolute error bound (docs/dynamics.md): 2^-52 x 2, about twice the
// rounding of a result near 1; the angle itself carries ulp(x)/2 >= 1.1e-16
// for |x| >= 1, so this adds nothing to what the state already holds.
constexpr double kAbsTol = 4.5e-16;

struct MaxErr {
  double s = 0.0, c = 0.0;
  double at_s = 0.0, at_c = 0.0;
  void add(double x)
  {
    const sim::SinCos sc = sim::sin_cos(x);
    const double es = std::fabs(sc.s - std::sin(x));
    const double ec = std::fabs(sc.c - std::cos(x));
    if (es > s) { s = es; at_s = x; }
    if (ec > c) { c = ec; at_c = x; }
  }
};

void expect_within(const MaxErr& e, const char* what)
{
  EXPECT_LE(e.s, kAbsTol) << what << ": sin worst at x = " << e.at_s;
  EXPECT_LE(e.c, kAbsTol) << what << ": cos worst at x = " << e.at_c;
  std::printf("%-34s max |err| sin %.3g  cos %.3g\n", what, e.s, e.c);
}

TEST(SinCos, AFewTurnsAgreeWithLibm)
{
  std::mt19937_64 g(20261204);
  std::uniform_real_distribution<double> u(-8.0 * M_PI, 8.0 * M_PI);
  MaxErr e;
  for (int i = 0; i < 1000000; ++i) e.add(u(g));
  expect_within(e, "|x| <= 8 pi");
}

TEST(SinCos, LongRunAnglesAgreeWithLibm)
{
  // log-uniform magnitudes 1e-3 .. 1e10 (a rotor at 1,000 rad/s for 0.3 years)
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> lg(-3.0, 10.0);
  std::bernoulli_distribution neg(0.5);
  MaxErr e;
  for (int i = 0; i < 1000000; ++i) {
    const double x = std::pow(10.0, lg(g));
    e.add(neg(g) ? -x : x);
  }
  expect_within(e, "1e-3 <= |x| <= 1e10");
}

TEST(SinCos, NextToMultiplesOfHalfPi)
{
  // The doubles nearest k pi/2 and their neighbours: the reduced argument
  // cancels to ~1e-17 .. 1e-6 there, where a short pi/2 would lose it.
  std::mt19937_64 g(11);
  std::uniform_int_distribution<int64_t> kd(-6000000000LL, 6000000000LL);
  MaxErr e;
  for (int i = 0; i < 1000000; ++i) {
    const int64_t k = i < 2000 ? i - 1000 : kd(g);
    double x = static_cast<double>(static_cast<long double>(k) * 1.57079632679489661923132169163975144L);
    const int steps = i % 5 - 2;
    for (int s = 0; s < std::abs(steps); ++s)
      x = std::nextafter(x, steps > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
    if (std::fabs(x) <= sim::kSinCosReducedMax) e.add(x);
  }
  expect_within(e, "next to k pi/2, |k| <= 6e9");
}

TEST(SinCos, ExactValuesAndSymmetry)
{
  EXPECT_EQ(sim::sin_cos(0.0).s, 0.0);
  EXPECT_EQ(sim::sin_cos(0.0).c, 1.0);
  const double tiny[] = {1e-300, 4.9e-324, 1e-20, 1e-9};
  for (const double x : tiny) {
    EXPECT_EQ(sim::sin_cos(x).s, x) << x;  // sin x = x to within x^3/6 < ulp(x)/2
    EXPECT_EQ(sim::sin_cos(x).c, 1.0) << x;
  }
  // Reduction and polynomials are odd/even term by term: exact symmetry.
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(0.0, 1e6);
  for (int i = 0; i < 100000; ++i) {
    const double x = u(g);
    const sim::SinCos p = sim::sin_cos(x), m = sim::sin_cos(-x);
    ASSERT_EQ(m.s, -p.s) << x;
    ASSERT_EQ(m.c, p.c) << x;
    ASSERT_LE(std::fabs(p.s * p.s + p.c * p.c - 1.0), 4.5e-16) << x;
  }
}

TEST(SinCos, BeyondTheBoundAndNonFinite)
{
  for (const double x : {1.0000001e10, -3e12, 1e300, -std::numeric_limits<double>::max()}) {
    EXPECT_EQ(sim::sin_cos(x).s, std::sin(x)) << x;
    EXPECT_EQ(sim::sin_cos(x).c, std::cos(x)) << x;
  }
  EXPECT_TRUE(std::isnan(sim::sin_cos(std::numeric_limits<double>::infinity()).s));
  EXPECT_TRUE(std::isnan(sim::sin_cos(-std::numeric_limits<double>::infinity()).c));
  EXPECT_TRUE(std::isnan(sim::sin_cos(std::numeric_limits<double>::quiet_NaN()).s));
  EXPECT_TRUE(std::isnan(sim::sin_cos(std::numeric_limits<double>::quiet_NaN()).c));
}

}  // namespace
