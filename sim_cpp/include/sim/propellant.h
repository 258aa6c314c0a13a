// propellant: tanks and quasi-static depletion (docs/dynamics.md §2, §5.6).
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

// merge_tanks_into_hub with the parts that do not depend on m_p formed once:
// the hub's mass moment and inertia about B, and each tank's inertia about B
// per kilogram, (2/5 R_T^2 + |r_T|^2) I - r_T r_T^T (both of its terms are
// linear in m_p).  merge() is what the plant evaluates in every derivative;
// it equals merge_tanks_into_hub to rounding (sim_test_propellant).
class TankMerger {
 public:
  TankMerger() = default;
  TankMerger(const HubParams& hub, const TankParams* tanks, int num_tanks);
  HubParams merge(const TankArray& m_p) const;

 private:
  HubParams hub_;
  Eigen::Vector3d first_moment_h_ = Eigen::Vector3d::Zero();  // [kg m]    m_h r_BcB
  Eigen::Matrix3d I_h_B_ = Eigen::Matrix3d::Zero();           // [kg m^2]  hub about B
  int n_ = 0;
  std::array<Eigen::Vector3d, kMaxTanks> r_{};                // [m]       tank centres
  std::array<Eigen::Matrix3d, kMaxTanks> I_per_kg_B_{};       // [m^2]     tank about B per kg
};

// Rocket equation (§5.6, THR-8): delta-v [m/s] of a burn from mass m0 to m1.
inline double rocket_delta_v(double Isp, double m0, double m1)
{
  return kG0 * Isp * std::log(m0 / m1);
}

}  // namespace sim

#endif  // SIM_PROPELLANT_H
