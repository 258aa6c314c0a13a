// Shared part of the FSW contract harnesses (issue 13): the decoder that
// turns fuzz bytes into configs and input sequences, and the contract checks
// of docs/fsw-conventions.md.  One header, so each harness only says what
// its module's config, input and output look like.
//
// Decoding rule: every value is decoded as a perturbation of a NOMINAL value
// and a byte of 0 (or the end of the input) means "nominal".  An empty input
// therefore runs the nominal configuration through a nominal sequence, and
// short seeds reach the nominal paths; the fuzzer reaches the special values
// (NaN, inf, denormals, huge and tiny values, time going backwards, counts at
// and beyond capacity) by changing single bytes.
//
// A contract violation prints what was violated and calls abort(), which
// libFuzzer records as a crash with the input that caused it.
#ifndef KESTREL_FUZZ_FSW_INPUT_H
#define KESTREL_FUZZ_FSW_INPUT_H

#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

// ---- violations --------------------------------------------------------------
#ifdef KESTREL_FUZZ_COUNT_VIOLATIONS
// The target's timing replay of a corpus in a fsw_real float build
// (bench/target/m4f_fuzz_replay.cpp): the checks are written for double (a
// float on-time of 0.55000001 s breaks the 1.1 dt bound), so a check not met
// is counted by the replay and the input runs on, as it would without checks.
extern "C" void fuzz_violation_counted(void);
#define FUZZ_REQUIRE(cond, ...)                \
  do {                                         \
    if (!(cond)) fuzz_violation_counted();     \
  } while (0)
#else
#define FUZZ_REQUIRE(cond, ...)                                                     \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "\nFSW CONTRACT VIOLATION at %s:%d: ", __FILE__, __LINE__); \
      std::fprintf(stderr, __VA_ARGS__);                                            \
      std::fprintf(stderr, "\n");                                                   \
      std::abort();                                                                 \
    }                                                                               \
  } while (0)
#endif

// The harnesses never pass NULL: an FSW assertion is a finding too.
extern "C" void fsw_assert_failed(const char *file, int line)
{
  std::fprintf(stderr, "\nFSW_ASSERT failed at %s:%d\n", file, line);
  std::abort();
}

// A nominal call period for the pulsers: 100 ms for a 0 byte, else 1..255 ms.
inline uint64_t fuzz_period_ns(uint8_t b) { return (b == 0 ? 100u : b) * 1000000ull; }

// Trace of the decoded values (KESTREL_FUZZ_TRACE=1 when replaying a
// reproducer): how a finding is turned into plain numbers.
inline bool fuzz_tracing()
{
  static const bool on = std::getenv("KESTREL_FUZZ_TRACE") != nullptr;
  return on;
}
inline void fuzz_trace(const char *name, const fsw_real *v, int n)
{
  if (!fuzz_tracing()) return;
  std::fprintf(stderr, "  %s =", name);
  for (int i = 0; i < n; i++) std::fprintf(stderr, " %.17g", static_cast<double>(v[i]));
  std::fprintf(stderr, "\n");
}
inline void fuzz_trace_int(const char *name, long long v)
{
  if (fuzz_tracing()) std::fprintf(stderr, "  %s = %lld\n", name, v);
}

// ---- decoder -------------------------------------------------------------------
class FuzzIn {
 public:
  FuzzIn(const uint8_t *data, size_t size) : p_(data), n_(size) {}

  uint8_t u8() { return i_ < n_ ? p_[i_++] : 0; }

  // A real near `nominal`: nominal (s < 128), a modest scaling (128..159), a
  // relative step (160..191), a special value (192..223), a power-of-two
  // rescaling over the whole exponent range (224..239), raw bits (240..255).
  double real(double nominal)
  {
    static const double kScale[32] = {0.5, 2.0, -1.0, 0.0, 0.9, 1.1, 0.99, 1.01, 0.999999, 1.000001,
                                      10.0, 0.1, 100.0, 0.01, 1e3, 1e-3, 1e6, 1e-6, 1e9, 1e-9,
                                      -0.5, -2.0, 1.5, 0.75, 3.0, 1.0 / 3.0, 1e12, 1e-12, 4.0, 0.25,
                                      1e15, 1e-15};
    static const double kSpecial[32] = {NAN, -NAN, INFINITY, -INFINITY, 0.0, -0.0,
                                        4.9406564584124654e-324, -4.9406564584124654e-324, 1e-320,
                                        DBL_MIN, 1e-308, 1e-300, 1e-150, 1e-12, 1e-6, 1.0, -1.0, 0.5,
                                        3.0, 10.0, 1e6, 1e12, 1e150, 1e300, 1e307, 1e308, 1.5e308,
                                        -1.5e308, DBL_MAX, -DBL_MAX, -1e308, 3.14159265358979323846};
    const uint8_t s = u8();
    if (s < 128) return nominal;
    if (s < 160) return nominal * kScale[s - 128];
    if (s < 192) return nominal + (static_cast<int8_t>(u8()) / 16.0) * (std::fabs(nominal) + 1.0) * 0.1 * (s - 159);
    if (s < 224) return kSpecial[s - 192];
    if (s < 240) return std::ldexp(nominal == 0.0 ? 1.0 : nominal, static_cast<int8_t>(u8()) * 8 + (s - 232));
    double d;
    uint8_t b[8];
    for (uint8_t &x : b) x = u8();
    std::memcpy(&d, b, sizeof d);
    return d;
  }

  // n reals, each near nominal[i] (or near `all` when nominal is NULL).
  void reals(fsw_real *v, int n, const double *nominal, double all = 0.0)
  {
    for (int i = 0; i < n; i++) v[i] = static_cast<fsw_real>(real(nominal != nullptr ? nominal[i] : all));
  }

  // A unit vector near `nominal` (3 reals).  Besides the element-wise
  // perturbation (usually not unit: check must reject it) it produces exact
  // unit vectors in any direction, copies or negations of `prev` (duplicate
  // and opposite axes) and small tilts, so that accepted but degenerate
  // geometry (coplanar, parallel) is reachable.
  void unit3(fsw_real v[3], const double nominal[3], const fsw_real *prev)
  {
    const uint8_t s = u8();
    double d[3] = {nominal[0], nominal[1], nominal[2]};
    if (s >= 128 && s < 176) {  // a direction from three signed bytes, odd s: tilted by 2^-k
      for (double &x : d) x = static_cast<int8_t>(u8());
      if (s & 1) d[(s / 2) % 3] += std::ldexp(1.0, -static_cast<int>(u8() % 64));
    } else if (s >= 176 && s < 192 && prev != nullptr) {  // prev, maybe tilted or negated
      const double sign = (s & 1) ? -1.0 : 1.0, tilt = (s & 2) ? std::ldexp(1.0, -static_cast<int>(u8() % 64)) : 0.0;
      for (int k = 0; k < 3; k++) d[k] = sign * prev[k];
      d[u8() % 3] += tilt;
    } else if (s >= 192 && s < 208) {  // nominal tilted by 2^-k about one axis
      d[s % 3] += std::ldexp(1.0, -static_cast<int>(u8() % 64));
    } else if (s >= 208) {  // element-wise (mostly not unit)
      for (int k = 0; k < 3; k++) v[k] = static_cast<fsw_real>(real(nominal[k]));
      return;
    }
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) v[k] = static_cast<fsw_real>(n > 0.0 ? d[k] / n : nominal[k]);
  }

  // A count near `nominal`: 0, 1, 2, 3, cap-1, cap, cap+1, -1, INT_MIN,
  // INT_MAX, 64, 65 or anything in 0..cap+1.
  int count(int nominal, int cap)
  {
    const int table[12] = {0, 1, 2, 3, cap - 1, cap, cap + 1, -1, INT_MIN, INT_MAX, 64, 65};
    const uint8_t s = u8();
    if (s < 160) return nominal;
    if (s < 172) return table[s - 160];
    return (s - 172) % (cap + 2);
  }

  // An enum or 0/1 flag near `nominal`: also out-of-range values.
  int flag(int nominal)
  {
    const int table[8] = {0, 1, 2, -1, 3, INT_MAX, INT_MIN, 255};
    const uint8_t s = u8();
    return s < 192 ? nominal : table[s % 8];
  }

  // A 0/1 availability byte (mostly 0, sometimes 1, rarely invalid).
  uint8_t avail()
  {
    const uint8_t s = u8();
    if (s < 200) return 0;
    if (s < 250) return 1;
    return static_cast<uint8_t>(s == 250 ? 2 : s);
  }
  void avail_mask(uint8_t *a, int n)
  {
    for (int i = 0; i < n; i++) a[i] = avail();
  }

  // An unsigned setting near `nominal` (counts such as k_reject).
  uint32_t u32(uint32_t nominal)
  {
    const uint32_t table[8] = {0, 1, 2, 3, 100, 0x7fffffffu, 0xfffffffeu, 0xffffffffu};
    const uint8_t s = u8();
    return s < 192 ? nominal : table[s % 8];
  }

  // The next time stamp after t: usually t + period, else equal, backwards,
  // to 0, jitter of +-1 % and +-2 %, much shorter/longer, near UINT64_MAX.
  uint64_t next_time(uint64_t t, uint64_t period)
  {
    const uint8_t s = u8();
    if (s < 160) return t + period;
    switch (s - 160) {
      case 0: return t;
      case 1: return t - 1;
      case 2: return t >= period ? t - period : 0;
      case 3: return 0;
      case 4: return t + 1;
      case 5: return t + period / 2;
      case 6: return t + 2 * period;
      case 7: return t + period / 100 * 101;
      case 8: return t + period / 100 * 99;
      case 9: return t + period / 1000 * 1011;
      case 10: return UINT64_MAX;
      case 11: return t + 1000000000000000000ull;
      case 12: return t + period / 1000 * 980;
      case 13: return t + period * 1000;
      default: return t + (static_cast<uint64_t>(u8()) + 1) * (period / 64 + 1);
    }
  }

  // Number of calls in the sequence (nominal when the byte is 0).
  int steps(int nominal, int max)
  {
    const uint8_t s = u8();
    return s == 0 ? nominal : 1 + s % max;
  }

  // What to do before a call: 0 nothing, 1 reset the module.
  int op()
  {
    return u8() >= 244 ? 1 : 0;
  }

 private:
  const uint8_t *p_;
  size_t n_;
  size_t i_ = 0;
};

// ---- contract checks -----------------------------------------------------------
inline bool fuzz_known_status(int s) { return s >= FSW_E_NOT_INIT && s <= FSW_W_RATE; }

inline bool fuzz_status_in(int s, std::initializer_list<int> allowed)
{
  for (int a : allowed)
    if (a == s) return true;
  return false;
}

inline bool fuzz_finite(const fsw_real *v, int n)
{
  for (int i = 0; i < n; i++)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// Index of the first entry of v[from..cap) that is not exactly +0, or -1.
inline int fuzz_nonzero_from(const fsw_real *v, int from, int cap)
{
  for (int i = from < 0 ? 0 : from; i < cap; i++)
    if (v[i] != 0 || std::signbit(v[i])) return i;
  return -1;
}

inline double fuzz_norm3(const fsw_real *v)
{
  // long double: no overflow for any finite double vector
  const long double a = v[0], b = v[1], c = v[2];
  return static_cast<double>(std::sqrt(a * a + b * b + c * c));
}

// First byte in which a and b differ, or -1.
inline long fuzz_first_diff(const void *a, const void *b, size_t n)
{
  // memcmp first: the byte loop, instrumented for coverage (two traced
  // comparisons per byte), took 60 % of fuzz_fsw_acs's time on its states
  // of tens of KiB; it only runs to locate a difference for the report.
  if (std::memcmp(a, b, n) == 0) return -1;
  const unsigned char *x = static_cast<const unsigned char *>(a), *y = static_cast<const unsigned char *>(b);
  for (size_t i = 0; i < n; i++)
    if (x[i] != y[i]) return static_cast<long>(i);
  return -1;
}

// One checked update call.  `call` runs the update; `mask` clears in a copy
// of the state what may change on an error (health counters, scratch areas
// documented to carry no meaning between calls); `is_safe(out, status)`
// tells whether the output is the documented safe output for that error.  Checks: a known status from
// `allowed`; on an error the safe output and a state byte-identical to the
// state before the call (after masking).  Returns the status.
template <class St, class Out, class Call, class Mask, class Safe>
int fuzz_call(const char *who, St &st, Out &out, std::initializer_list<int> allowed, Call call, Mask mask,
              Safe is_safe)
{
  static St before, after;  // states can be tens of KiB
  std::memcpy(&before, &st, sizeof st);
  std::memset(&out, 0xA5, sizeof out);  // the module must write every byte it promises
  const int s = call();
  if (fuzz_tracing()) std::fprintf(stderr, "%s -> %s\n", who, fsw_status_name(static_cast<FswStatus>(s)));
  FUZZ_REQUIRE(fuzz_known_status(s), "%s returned unknown status %d", who, s);
  FUZZ_REQUIRE(fuzz_status_in(s, allowed), "%s returned %s, which its header does not list", who,
               fsw_status_name(static_cast<FswStatus>(s)));
  if (s < 0) {
    FUZZ_REQUIRE(is_safe(out, s), "%s returned %s without the documented safe output", who,
                 fsw_status_name(static_cast<FswStatus>(s)));
    std::memcpy(&after, &st, sizeof st);
    mask(before);
    mask(after);
    const long d = fuzz_first_diff(&before, &after, sizeof st);
    FUZZ_REQUIRE(d < 0, "%s returned %s but changed its state (first differing byte %ld of %zu)", who,
                 fsw_status_name(static_cast<FswStatus>(s)), d, sizeof st);
  }
  return s;
}

// init with a decoded config.  Checks: check() returns a known config
// status, init() returns the same, OK <=> ready.  On rejection, `update`
// (a closure that runs one checked update with a nominal input) must return
// FSW_E_NOT_INIT with the safe output and no state change.  Returns 1 if
// the config was accepted.
template <class St, class Cfg, class Ready, class Update>
int fuzz_init(const char *who, St &st, const Cfg &cfg, FswStatus (*check)(const Cfg *),
              FswStatus (*init)(St *, const Cfg *), Ready ready, Update update)
{
  const int c = check(&cfg);
  FUZZ_REQUIRE(fuzz_status_in(c, {FSW_OK, FSW_E_CONFIG, FSW_E_CAPACITY, FSW_E_SINGULAR}),
               "%s check returned %d", who, c);
  std::memset(&st, 0x5A, sizeof st);  // init must not depend on what was there
  const int i = init(&st, &cfg);
  FUZZ_REQUIRE(i == c, "%s init returned %d but check %d", who, i, c);
  if (c == FSW_OK) {
    FUZZ_REQUIRE(ready(st) == 1, "%s init accepted the config but the state is not ready", who);
    return 1;
  }
  FUZZ_REQUIRE(ready(st) == 0, "%s init rejected the config (%d) but the state is ready", who, c);
  const int u = update();
  FUZZ_REQUIRE(u == FSW_E_NOT_INIT, "%s update after a rejected init returned %d", who, u);
  return 0;
}

// Masks of the common cases: the state's health counters only.
template <class St>
void fuzz_mask_health(St &s)
{
  std::memset(&s.health, 0, sizeof s.health);
}
template <class St>
void fuzz_mask_common_health(St &s)
{
  std::memset(&s.common.health, 0, sizeof s.common.health);
}

// ---- nominal geometry shared by the wheel harnesses -----------------------------
// Count and clamp: the number of array entries to decode for a count that
// may be out of range.
inline int fuzz_clamp_count(int n, int cap) { return n < 0 ? 0 : (n > cap ? cap : n); }

// Wheel i of the nominal set: a pyramid at 40 deg elevation, azimuths
// 45 + 90 i deg (the 4-wheel reference set, repeated beyond 4 wheels).
inline void fuzz_pyramid_axis(int i, double g[3])
{
  const double el = 40.0 * 3.14159265358979323846 / 180.0,
               az = (45.0 + 90.0 * (i % 4) + 7.0 * (i / 4)) * 3.14159265358979323846 / 180.0;
  g[0] = std::cos(el) * std::cos(az);
  g[1] = std::cos(el) * std::sin(az);
  g[2] = std::sin(el);
}

// Decode the count and spin axes of a wheel set (nominal: 4-wheel pyramid).
inline int fuzz_wheel_axes(FuzzIn &in, fsw_real gs[FSW_MAX_RW][3], int *num_rw)
{
  *num_rw = in.count(4, FSW_MAX_RW);
  const int n = fuzz_clamp_count(*num_rw, FSW_MAX_RW);
  for (int i = 0; i < n; i++) {
    double g[3];
    fuzz_pyramid_axis(i, g);
    in.unit3(gs[i], g, i > 0 ? gs[i - 1] : nullptr);
  }
  fuzz_trace_int("num_rw", *num_rw);
  for (int i = 0; i < n; i++) fuzz_trace("gs_hat_B[i]", gs[i], 3);
  return n;
}

// Nominal wheel-speed-like values: 100, -80, 60, -40, ... rad/s.
inline void fuzz_speeds(FuzzIn &in, fsw_real *v, int n, double base)
{
  for (int i = 0; i < n; i++) v[i] = static_cast<fsw_real>(in.real(base * ((i % 2) ? -1.0 : 1.0) * (5 - i % 4) / 5.0));
}

// |[Gs_a] (a - b)| and the scale sum |g_i| |a_i - b_i| over the available
// wheels (long double): the body torque the difference a - b would make.
inline void fuzz_wheel_torque_diff(const fsw_real gs[FSW_MAX_RW][3], const uint8_t *avail, int n,
                                   const fsw_real *a, const fsw_real *b, double *diff, double *scale)
{
  long double t[3] = {0, 0, 0}, sc = 0;
  for (int i = 0; i < n; i++) {
    if (avail[i]) continue;
    const long double d = static_cast<long double>(a[i]) - b[i];
    for (int k = 0; k < 3; k++) t[k] += gs[i][k] * d;
    sc += std::fabs(d) + std::fabs(static_cast<long double>(a[i])) + std::fabs(static_cast<long double>(b[i]));
  }
  *diff = static_cast<double>(std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]));
  *scale = static_cast<double>(sc);
}

// First entry i < n of an available-wheel output that is not 0 for an
// unavailable wheel, or -1.
inline int fuzz_unavail_nonzero(const fsw_real *u, const uint8_t *avail, int n)
{
  for (int i = 0; i < n; i++)
    if (avail[i] == 1 && u[i] != 0) return i;
  return -1;
}

// The pulsers: one on-time check for every entry.  First call after reset:
// t_on = first (b * init_off_pulse_on_time); else 0 <= t_on <= 1.1 dt (the
// saturated value) and a non-zero t_on is at least min_on, unless it is the
// saturated value t_max and `sat_exempt` (the remainder and Schmitt pulsers
// keep a saturated thruster on through the period).
inline void fuzz_check_on_times(const char *who, const fsw_real *t_on, int n, int first, double first_value,
                                double dt, double t_max, double min_on, bool sat_exempt)
{
  FUZZ_REQUIRE(fuzz_finite(t_on, FSW_MAX_THR), "%s: non-finite on-time under OK/warning", who);
  FUZZ_REQUIRE(fuzz_nonzero_from(t_on, n, FSW_MAX_THR) < 0, "%s: non-zero on-time beyond num_thr", who);
  for (int i = 0; i < n; i++) {
    if (first) {
      FUZZ_REQUIRE(t_on[i] == first_value, "%s: first call t_on[%d] = %.17g, expected %.17g", who, i, t_on[i],
                   first_value);
      continue;
    }
    FUZZ_REQUIRE(t_on[i] >= 0 && t_on[i] <= t_max * (1 + 1e-12),
                 "%s: t_on[%d] = %.17g outside [0, %.17g] (call period %.17g s)", who, i, t_on[i], t_max, dt);
    FUZZ_REQUIRE(t_on[i] == 0 || t_on[i] >= min_on * (1 - 1e-12) || (sat_exempt && t_on[i] >= t_max * (1 - 1e-12)),
                 "%s: t_on[%d] = %.17g is below the minimum on-time %.17g", who, i, t_on[i], min_on);
  }
}

#endif  // KESTREL_FUZZ_FSW_INPUT_H
