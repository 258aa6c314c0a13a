/* Shared test support: assert-hook probes, seeded random numbers that are
 * identical on every platform (never std::*_distribution, whose output
 * differs between standard libraries), and real-type tolerances. */
#ifndef KESTREL_TEST_SUPPORT_H
#define KESTREL_TEST_SUPPORT_H

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif
unsigned long kestrel_assert_count(void);
const char *kestrel_assert_last_file(void);
int kestrel_assert_last_line(void);
void kestrel_assert_reset(void);
#ifdef __cplusplus
}

#include <cmath>
#include <cstdint>

namespace kt {

/* true when the library was built with float reals */
constexpr bool kFloat = sizeof(fsw_real) == sizeof(float);

/* Pick the tolerance for the real type in use. */
constexpr double tol(double for_double, double for_float)
{
  return kFloat ? for_float : for_double;
}

/* SplitMix64: tiny, well-mixed, bit-identical on every platform. */
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t next_u64()
  {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /* uniform in [0, 1) with 53 random bits */
  double uniform() { return static_cast<double>(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /* standard normal by Box-Muller (no std::normal_distribution) */
  double normal()
  {
    double u1 = uniform();
    double u2 = uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  int uniform_int(int lo, int hi_inclusive)
  {
    uint64_t span = static_cast<uint64_t>(hi_inclusive - lo) + 1u;
    return lo + static_cast<int>(next_u64() % span);
  }
  /* uniformly distributed unit vector */
  void unit3(double out[3])
  {
    double n2;
    do {
      for (int i = 0; i < 3; i++) out[i] = uniform(-1.0, 1.0);
      n2 = out[0] * out[0] + out[1] * out[1] + out[2] * out[2];
    } while (n2 > 1.0 || n2 < 1e-6);
    double n = std::sqrt(n2);
    for (int i = 0; i < 3; i++) out[i] /= n;
  }

 private:
  uint64_t s_;
};

}  // namespace kt
#endif

#endif /* KESTREL_TEST_SUPPORT_H */
