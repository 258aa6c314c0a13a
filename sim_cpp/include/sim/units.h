// units: named conversions for configuration loaders (docs/dynamics.md §0).
// The plant itself works in SI only.
#ifndef SIM_UNITS_H
#define SIM_UNITS_H

#include <cstdint>

namespace sim {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerSecPerRpm = 2.0 * kPi / 60.0;  // [rad/s / RPM]
constexpr double kRadPerDeg = kPi / 180.0;             // [rad / deg]
constexpr double kKgMPerGCm = 1e-5;                    // [kg*m / (g*cm)]   static imbalance
constexpr double kKgM2PerGCm2 = 1e-7;                  // [kg*m^2 / (g*cm^2)] dynamic imbalance
constexpr double kMuEarth = 3.986004415e14;            // [m^3/s^2]
constexpr double kMuMars = 4.2828314e13;               // [m^3/s^2]

// Plant clock [ns] -> seconds: t_ns * 1e-9, the conversion the nanosecond
// plant has always used (keeps thruster event times and sub-step lengths
// bit-identical).  It equals the decimal value for the usual steps (1e-5 s
// .. 2 s in 1-2-5 steps) but can differ from it by one ulp (30 ms, 120 ms,
// 1 us): a run that needs a step of exactly the double 0.03 cannot have it.
constexpr double seconds_from_ns(int64_t t_ns) { return static_cast<double>(t_ns) * 1e-9; }

constexpr double rad_s_from_rpm(double rpm) { return rpm * kRadPerSecPerRpm; }
constexpr double rad_from_deg(double deg) { return deg * kRadPerDeg; }

// J_s = h_max / Omega_max when a wheel is specified by momentum capacity (§4.1).
constexpr double spin_inertia_from_capacity(double h_max, double Omega_max)
{
  return h_max / Omega_max;
}

}  // namespace sim

#endif  // SIM_UNITS_H
