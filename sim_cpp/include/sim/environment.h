// environment: point-mass gravity, Sun position, Sun direction and
// illumination, and two-body conic helpers for scenario set-up
// (docs/dynamics.md §0, §6, §9.3, §11).  Frames: N inertial (centred on
// the central body), B body.  Units: SI.
//
// Gravity in the dynamics is applied by SpacecraftModel at the mass centre
// with SpacecraftParams::mu (§3), plus j2_acceleration() when
// SpacecraftParams::J2 is set; point_mass_gravity() is the point-mass law
// for scenario code and tests.  Gravity gradient, SRP, drag and magnetic
// torques act only through the effectors of sim/environment_effectors.h,
// when they are added to a plant (docs/environment.md, "In the plant").
#ifndef SIM_ENVIRONMENT_H
#define SIM_ENVIRONMENT_H

#include <Eigen/Dense>

namespace sim {

constexpr double kAU = 149597870693.0;          // [m] astronomical unit (§0)
constexpr double kMuSun = 1.3271244002331e20;   // [m^3/s^2]
constexpr double kRadiusSun = 6.957e8;          // [m] IAU nominal solar radius
constexpr double kRadiusMars = 3396.19e3;       // [m] Mars equatorial radius (§11 S2)
constexpr double kRadiusEarth = 6378.1363e3;    // [m]

struct CentralBody {
  double mu = 0.0;      // [m^3/s^2] gravity parameter, >= 0 (0: gravity off)
  double radius = 0.0;  // [m]       shadowing radius, >= 0 (0: no eclipses)
};

CentralBody mars();   // mu 4.2828314e13, R 3396.19 km
CentralBody earth();  // mu 3.986004415e14, R 6378.1363 km

// g_N = -mu r / |r|^3; zero for mu = 0.
Eigen::Vector3d point_mass_gravity(double mu, const Eigen::Vector3d& r_N);

// Earth's second zonal harmonic and its reference radius, WGS 84 (NIMA
// TR8350.2, 3rd ed., 2000: the normalised C(2,0) = -0.484166774985e-3,
// J2 = -sqrt(5) C(2,0); a = 6378137 m).
constexpr double kJ2Earth = 1.08262668e-3;       // [-]
constexpr double kRadiusJ2Earth = 6378137.0;     // [m]

// The J2 part of a central body's gravity, N components, with N z along the
// body's rotation axis (for the Earth: N is the mean equator of date):
//   a = -(3/2) J2 mu R^2 / r^5 [x (1 - 5 z^2/r^2), y (1 - 5 z^2/r^2), z (3 - 5 z^2/r^2)],
// the gradient of the potential's J2 term (j2_potential).  Zero for J2 = 0.
Eigen::Vector3d j2_acceleration(double mu, double J2, double R, const Eigen::Vector3d& r_N);
// The J2 term of the potential energy per unit mass [J/kg], so that the
// total is -mu/r + j2_potential and a = -grad of it:
//   U_J2 = (mu J2 R^2 / (2 r^3)) (3 z^2/r^2 - 1).
double j2_potential(double mu, double J2, double R, const Eigen::Vector3d& r_N);

// Sun position relative to the central body: r_SunN_N(t) = R_z(n t) r0,
// i.e. fixed for n = 0 (scenario S1: (1 AU, 0, 0)), or the central body's
// circular heliocentric motion seen from the body for n = sqrt(mu_sun/|r0|^3).
struct SunParams {
  Eigen::Vector3d r_SunN_N0 = Eigen::Vector3d(kAU, 0.0, 0.0);  // [m] at t = 0
  double n = 0.0;  // [rad/s] apparent angular rate about N z
};

// Throws std::invalid_argument naming `name.field` and the value.
void validate(const SunParams& p, const char* name = "sun");
void validate(const CentralBody& b, const char* name = "body");

Eigen::Vector3d sun_position_N(const SunParams& p, double t);

// Unit vector from the spacecraft to the Sun, B components:
// s_B = [BN] unit(r_Sun - r_sc)  (§9.3).
Eigen::Vector3d sun_direction_B(const Eigen::Matrix3d& dcm_BN, const Eigen::Vector3d& r_scN_N,
                                const Eigen::Vector3d& r_SunN_N);

// (1 AU / |r_Sun - r_sc|)^2: flux relative to 1 AU (§9.3).
double solar_flux_scale(const Eigen::Vector3d& r_scN_N, const Eigen::Vector3d& r_SunN_N);

// Fraction of the solar disk visible from r_sc past a spherical central body
// of radius R_body at the origin (conical shadow with penumbra: overlap of
// two disks of apparent radii asin(R/d)), in [0, 1].  1 when R_body = 0.
double illumination_factor(const Eigen::Vector3d& r_scN_N, const Eigen::Vector3d& r_SunN_N,
                           double R_body, double R_sun = kRadiusSun);

// ------------------------------------------------------------- two-body

struct OrbitElements {
  double energy = 0.0;  // [m^2/s^2] specific orbital energy v^2/2 - mu/r
  Eigen::Vector3d h_N = Eigen::Vector3d::Zero();  // [m^2/s] specific angular momentum r x v
  double e = 0.0;       // [-] eccentricity
  double a = 0.0;       // [m] semi-major axis (negative for hyperbolas, inf for parabolas)
  double r_p = 0.0;     // [m] periapsis radius
  double r_a = 0.0;     // [m] apoapsis radius (inf for e >= 1)
};

OrbitElements elements_from_rv(double mu, const Eigen::Vector3d& r_N, const Eigen::Vector3d& v_N);

struct OrbitState {
  Eigen::Vector3d r_N, v_N;  // [m], [m/s]
};

// State at time t after periapsis (t < 0: before) on the conic with
// periapsis radius r_p and eccentricity e (ellipse e < 1 or hyperbola
// e > 1), in the perifocal frame: x toward periapsis, z along h.  Solves
// Kepler's equation by Newton iteration.
OrbitState conic_state_from_periapsis(double mu, double r_p, double e, double t);

// Hyperbolic approach (§11 S2): e = 1 + r_p v_inf^2 / mu.
inline double hyperbolic_eccentricity(double mu, double r_p, double v_inf)
{
  return 1.0 + r_p * v_inf * v_inf / mu;
}

}  // namespace sim

#endif  // SIM_ENVIRONMENT_H
