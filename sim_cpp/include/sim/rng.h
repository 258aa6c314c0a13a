// rng: deterministic random streams for the plant's sensors (docs/dynamics.md
// §9, §13; one stream per name, so Monte Carlo runs are repeatable).
//
// A stream is named: its seed is derived from the run seed and the
// component's name, so a component draws the same numbers whatever other
// components exist, in whatever order or thread they run.  Nothing seeds
// itself (no clock, no std::random_device).
//
// Engine: std::mt19937_64, whose output sequence the C++ standard fixes.
// Distributions are implemented here (never std::*_distribution, whose
// algorithms differ between standard libraries):
//   uniform()  53-bit multiple of 2^-53 in [0, 1)
//   normal()   Marsaglia's polar method; the second variate of each pair is
//              kept for the next call.  Uses only +, *, sqrt and log.
// Bit-identical across platforms as long as std::log is correctly rounded
// for the arguments met (glibc's is); within one build, always.
#ifndef SIM_RNG_H
#define SIM_RNG_H

#include <cmath>
#include <cstdint>
#include <random>
#include <string_view>

#include <Eigen/Dense>

#include "sim/state_io.h"

namespace sim {

// 64-bit FNV-1a hash of a name (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
constexpr uint64_t fnv1a64(std::string_view s)
{
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char ch : s) {
    h ^= static_cast<uint8_t>(ch);
    h *= 0x100000001b3ull;
  }
  return h;
}

// SplitMix64 finaliser of (x + golden gamma): a bijection on 64-bit words.
constexpr uint64_t splitmix64(uint64_t x)
{
  uint64_t z = x + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Seed of the stream `name` in run `run_seed`.  For a fixed run seed, names
// with different FNV-1a hashes get different seeds (both steps are bijective).
constexpr uint64_t derive_seed(uint64_t run_seed, std::string_view name)
{
  return splitmix64(splitmix64(run_seed) ^ fnv1a64(name));
}

class Rng {
 public:
  Rng(uint64_t run_seed, std::string_view name) : eng_(derive_seed(run_seed, name)) {}

  uint64_t next_u64() { return eng_(); }

  double uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }

  // Standard normal N(0, 1).
  double normal()
  {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

  // Three independent N(0, 1) draws, x then y then z.
  Eigen::Vector3d normal3()
  {
    const double x = normal();
    const double y = normal();
    const double z = normal();
    return Eigen::Vector3d(x, y, z);
  }

  // The stream's position (a checkpoint, sim/state_io.h): the engine's
  // words and index, and the spare normal draw.
  void state_io(StateIO& io)
  {
    io.value("rng.engine", eng_);
    io.value("rng.has_spare", has_spare_);
    io.value("rng.spare", spare_);
  }

 private:
  std::mt19937_64 eng_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace sim

#endif  // SIM_RNG_H
