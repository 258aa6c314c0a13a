// propellant: tanks and quasi-static depletion (spec plant-dynamics §2, §5.6).
// Frames: B.  Units: SI.
//
// A tank is a rigid body fixed in B: a point mass, or a uniform sphere of
// constant radius R_T ([I_T] = 2/5 m_p R_T^2 I3, Basilisk's constant-volume
// tank).  Mass properties are recomputed from the stage value of m_p at
// every derivative call; the depletion terms c' and [I'_T] are neglected
// (§5.6, Basilisk's default).  Because the tank is rigid and fixed in B,
// merging it into the hub (merge_tanks_into_hub) reproduces the §2 sums and
// the §8 tank terms h_T, e_T exactly.
#ifndef SIM_PROPELLANT_H
#define SIM_PROPELLANT_H

#include <array>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "sim/capacities.h"  // kMaxTanks, TankArray
#include "sim/spacecraft.h"   // HubParams
#include "sim/thruster.h"  // kG0

namespace sim {

struct TankParams {  // checked by validate(); fixed for a run
  Eigen::Vector3d r_TB_B = Eigen::Vector3d::Zero();  // [m]  tank centre T relative to B
  double m_p0 = 0.0;  // [kg] initial propellant mass, >= 0
  double R_T = 0.0;   // [m]  sphere radius for [I_T]; 0: point mass
};

// Throws std::invalid_argument naming `name.field` and the offending value.
void validate(const TankParams& p, const std::string& name = "tank");

// [I_T] about the tank centre for propellant mass m_p [kg].
Eigen::Matrix3d tank_inertia(const TankParams& p, double m_p);

// The hub with the tanks' propellant m_p[k] (negative values count as 0)
// merged in: total mass, CoM and inertia about the new CoM.
HubParams merge_tanks_into_hub(const HubParams& hub, const TankParams* tanks, int num_tanks,
                               const TankArray& m_p);

// Rocket equation (§5.6, THR-8): delta-v [m/s] of a burn from mass m0 to m1.
inline double rocket_delta_v(double Isp, double m0, double m1)
{
  return kG0 * Isp * std::log(m0 / m1);
}

}  // namespace sim

#endif  // SIM_PROPELLANT_H
