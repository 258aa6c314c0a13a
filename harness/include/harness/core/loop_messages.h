// loop_messages: the harness's own messages of the closed loop (plain
// structs on harness::Channel).  The FSW's messages are the application's
// FswAcsSensorMsg / FswAcsActuatorMsg / FswAcsHealthMsg (fsw/fsw_acs_msgs.h).
// Frames: N inertial, B body (origin at point B), C the mass centre.
#ifndef HARNESS_LOOP_MESSAGES_H
#define HARNESS_LOOP_MESSAGES_H

#include <cstdint>

#include "sim/capacities.h"

extern "C" {
#include "fsw/fsw_acs_msgs.h"
}

namespace harness {

constexpr int kMaxRw = sim::kMaxWheels;
constexpr int kMaxEnvSources = 4;  // gravity gradient, solar pressure, drag, magnetic
constexpr int kMaxThr = sim::kMaxThrusters;
constexpr int kMaxMtq = sim::kMaxMagnetorquers;

// Plant truth at the tick (written every tick by the truth task).
struct TruthMsg {
  double sigma_BN[3];       // [-]
  double omega_BN_B[3];     // [rad/s]
  double r_BN_N[3];         // [m]
  double v_BN_N[3];         // [m/s]
  double r_CN_N[3];         // [m]   mass centre
  double v_CN_N[3];         // [m/s] mass centre
  double r_CoM_B[3];        // [m]   mass centre relative to B
  double m_sc;              // [kg]  total mass
  double m_prop;            // [kg]  propellant left (all tanks)
  double Omega[kMaxRw];     // [rad/s] wheel speeds rel. B
  double u_s[kMaxRw];       // [N*m]   motor torque held by the plant
  double F_thr[kMaxThr];    // [N]     thrust magnitude of each thruster now
  // [N*m] disturbance torque about the mass centre C, B components, of each
  // environment source (EnvSource order; zero where a source is off):
  // L_C = L_B - c x F_B from the effector's load at this state.
  double L_env_C_B[kMaxEnvSources][3];
  // Earth-orbit truth (TruthTask::environment_truth; zero where not recorded):
  double illumination;                // [-] visible fraction of the Sun's disk (epoch set), 0 umbra .. 1 sunlit
  double field_B[3];                  // [T] geomagnetic field the magnetic torque acts with, B
  double H_env_N[kMaxEnvSources][3];  // [N*m*s] angular momentum given by each source, int [NB] L_C dt, N
  double H_wheels_N[3];               // [N*m*s] wheels' spin momentum sum J_s Omega g_s, N
};

// Sampled outputs of the gyro, star tracker and wheel tachometers, held
// between samples.  The gyro platform P and the star-tracker case C coincide
// with B, so omega_PN_P = omega_BN_B and sigma_CN = sigma_BN as measured.
struct SensorSampleMsg {
  double omega_PN_P[3];    // [rad/s] gyro output
  int64_t gyro_t_ns;       // [ns] time tag of the gyro sample
  uint8_t gyro_valid;      // [-] 1 once the gyro has sampled
  double sigma_CN[3];      // [-] star-tracker attitude (MRP, |sigma| <= 1)
  int64_t st_t_ns;         // [ns] time tag of the star-tracker sample
  uint8_t st_valid;        // [-] 1 if the latest star-tracker sample is valid (sampled, not Sun-excluded)
  double Omega[kMaxRw];    // [rad/s] tachometer wheel speeds
  int64_t tach_t_ns;       // [ns]
  uint8_t tach_valid;      // [-]
};

struct CssMsg {
  double y[FSW_MAX_CSS];  // [reading units] (num_css) coarse-sun-sensor outputs
};

struct SunHeadingMsg {
  double sun_B[3];  // [-] unit Sun heading in B (FSW css_sun estimate); 0 when no valid heading
  int valid;        // [-] 1 if sun_B holds a heading
  int num_lit;      // [-] lit coarse sun sensors
};

struct ThrCmdMsg {
  double T_on[kMaxThr];  // [s] on-time requests sent to the plant (plant thruster order)
};

// Magnetorquer dipole commands (`mtq_cmd`): applied to the rods at each FSW
// tick (dipole mode: held; PWM mode: the duty cycle's dipole).  Written by
// scenario events (action `dipole`) until the flight software commands the
// rods; zero (rods off) until written.
struct MtqCmdMsg {
  double m_cmd[kMaxMtq];  // [A*m^2] (num magnetorquers) dipole along each rod's axis
};

// The rods as they act (`mtq_state`, record ticks).
struct MtqStateMsg {
  double dipole[kMaxMtq];  // [A*m^2] acting dipole along each rod's axis
  double power[kMaxMtq];   // [W] coil power
};

// The magnetometer's reading as handed on (`magnetometer`), held between
// samples; scenario faults (dropout, frozen, bias) are applied to it.
struct MagnetometerMsg {
  double B_S[3];      // [T] measured field, sensor axes S (NaN during a dropout)
  int64_t t_ns;       // [ns] time tag of the sample
  uint8_t valid;      // [-] 1 once sampled and not dropped out
  uint8_t saturated;  // [-] 1 if an axis was clipped at the range
};

struct MetricsMsg {
  double pointing_error;  // [rad]
  double H_C_N[3];        // [kg*m^2/s]
  double E_rot;           // [J]
  double dv_ng;           // [m/s] |accumulated non-gravitational velocity change| of C
  double orbit_e;         // [-]   osculating eccentricity (mu > 0)
  double orbit_r_p;       // [m]   osculating periapsis radius (mu > 0)
  double orbit_energy;    // [J/kg] specific orbital energy (mu > 0)
};

}  // namespace harness

#endif  // HARNESS_LOOP_MESSAGES_H
