// surface_forces: solar radiation pressure and aerodynamic drag on a body
// made of flat facets, and an exponential atmosphere.  Frames: N inertial
// (z = the Earth's rotation axis), B body.  Units: SI.  See
// docs/environment.md.
//
// Both loads sum facet by facet; every facet that faces the Sun (or the
// flow) counts in full: self-shadowing, shading of one facet by another,
// multiple reflections and the Earth's albedo and infrared are ignored.
#ifndef SIM_SURFACE_FORCES_H
#define SIM_SURFACE_FORCES_H

#include <array>

#include <Eigen/Dense>

#include "sim/capacities.h"  // kMaxFacets

namespace sim {

constexpr double kSpeedOfLight = 299792458.0;  // [m/s]
// Total solar irradiance at 1 AU: 1361 W/m^2 (Kopp & Lean 2011; IAU 2015
// Resolution B3 nominal value).  P = 1361 / c = 4.5398e-6 N/m^2 (the often
// quoted 4.56e-6 N/m^2 is the older 1367 W/m^2 / c).
constexpr double kSolarIrradiance1AU = 1361.0;                               // [W/m^2]
constexpr double kSolarPressure1AU = kSolarIrradiance1AU / kSpeedOfLight;  // [N/m^2]

struct Facet {
  double area = 0.0;                                 // [m^2] > 0
  Eigen::Vector3d n_B = Eigen::Vector3d::UnitZ();    // [-] unit outward normal, B
  Eigen::Vector3d r_B = Eigen::Vector3d::Zero();     // [m] centre of pressure from the B origin, B
  double absorbed = 1.0;   // [-] fraction of incident light absorbed, in [0, 1]
  double specular = 0.0;   // [-] fraction reflected specularly, in [0, 1]
  double diffuse = 0.0;    // [-] fraction reflected diffusely (Lambert), in [0, 1]; the three sum to 1
  double C_D = 2.2;        // [-] drag coefficient of the facet, >= 0
};

// A fixed-capacity set of facets (no heap): facets[0 .. count-1] are used.
struct FacetSet {
  std::array<Facet, kMaxFacets> facets{};
  int count = 0;  // [-] in [0, kMaxFacets]
};

// Throws std::invalid_argument naming `name.field` (`name[i].field` for a
// set) and the value: area > 0, |n_B| = 1 within 1e-9, finite r_B,
// fractions in [0, 1] summing to 1 within 1e-9, C_D >= 0.
void validate(const Facet& f, const char* name = "facet");
void validate(const FacetSet& s, const char* name = "facets");

// Force on the body and torque about a reference point (the mass centre).
struct SurfaceLoad {
  Eigen::Vector3d F_B = Eigen::Vector3d::Zero();  // [N] B components
  Eigen::Vector3d L_B = Eigen::Vector3d::Zero();  // [N m] about r_ref_B, B components
};

// Solar radiation pressure.  For each facet with c = n.s > 0:
//   F = -P A c [ (1 - specular) s + 2 (specular c + diffuse / 3) n ],
//   P = kSolarPressure1AU * flux_scale,
// i.e. absorbed: -P A c s; specular: -2 P A c^2 n; diffuse: -P A c (s + 2/3 n).
//   s_B        [-] unit vector from the spacecraft to the Sun, B
//   flux_scale [-] (1 AU / distance)^2 times the illuminated fraction
//              (solar_flux_scale * illumination_factor of sim/environment.h)
//   r_ref_B    [m] the point torques are taken about (mass centre), B
// Torque = sum (r_B - r_ref_B) x F.
SurfaceLoad srp_load(const FacetSet& s, const Eigen::Vector3d& s_B, double flux_scale,
                     const Eigen::Vector3d& r_ref_B = Eigen::Vector3d::Zero());

// Aerodynamic drag.  For each facet, with v = v_rel_B, v_hat = v/|v|:
//   F = -1/2 rho C_D A max(0, n.v_hat) |v|^2 v_hat
//   v_rel_B [m/s]    velocity of the body relative to the air, B (wind_velocity_N, rotated)
//   rho     [kg/m^3] air density
SurfaceLoad drag_load(const FacetSet& s, const Eigen::Vector3d& v_rel_B, double rho,
                      const Eigen::Vector3d& r_ref_B = Eigen::Vector3d::Zero());

// Velocity relative to an atmosphere co-rotating with the Earth, N:
// v_N - (kOmegaEarth z) x r_N.  (Winds are ignored.)
Eigen::Vector3d wind_velocity_N(const Eigen::Vector3d& r_N, const Eigen::Vector3d& v_N);

// ---------------------------------------------------------- atmosphere

// WGS 84 ellipsoid.
constexpr double kWgs84A = 6378137.0;              // [m] equatorial radius
constexpr double kWgs84F = 1.0 / 298.257223563;    // [-] flattening

// Height above the WGS 84 ellipsoid measured along the radius:
// |r| - a b / sqrt(b^2 cos^2 phi' + a^2 sin^2 phi'), phi' the geocentric
// latitude (sin phi' = z / |r|, the same in N and E).  Exceeds the
// geodetic height by about h f^2 / 2: 2.2 m at 400 km, 4.9 m at 1000 km.   [m]
double ellipsoid_height(const Eigen::Vector3d& r_N);

// Exponential atmosphere of Vallado, Fundamentals of Astrodynamics and
// Applications, Table 8-4 (28 bands, 0 .. >1000 km; base altitude h0,
// nominal density rho0, scale height H): rho = scale rho0 exp(-(h - h0)/H)
// in the band h0 <= h < h0_next (below 0: the first band; above 1000 km:
// the last).  Static, mean solar activity: no diurnal bulge, no solar or
// geomagnetic activity; `scale` stands in for them.
struct ExponentialAtmosphere {
  double scale = 1.0;  // [-] density scale factor, >= 0
};
void validate(const ExponentialAtmosphere& a, const char* name = "atmosphere");

double density(const ExponentialAtmosphere& a, double h);  // h [m] -> [kg/m^3]

}  // namespace sim

#endif  // SIM_SURFACE_FORCES_H
