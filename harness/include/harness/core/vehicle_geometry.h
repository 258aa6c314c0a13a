// vehicle_geometry: the spacecraft's geometry in one vocabulary (docs/
// harness.md, "One vocabulary: geometry").  Every point is located relative
// to the body origin B, every vector is in body components (suffix _B), SI.
// vehicle_geometry() forms it from a scenario; the plant (plant_builder) and
// the FSW configuration (fsw_geometry) both take it from there, so the
// scenario -> plant and scenario -> FSW conversions each happen once.
#ifndef HARNESS_CORE_VEHICLE_GEOMETRY_H
#define HARNESS_CORE_VEHICLE_GEOMETRY_H

#include <vector>

#include <Eigen/Dense>

#include "harness/core/scenario_types.h"

extern "C" {
#include "fsw/fsw_acs.h"
}

namespace harness {

struct ThrusterGeometry {
  Eigen::Vector3d r_TjB_B = Eigen::Vector3d::Zero();       // [m] nozzle Tj relative to B
  Eigen::Vector3d t_hat_B = Eigen::Vector3d::UnitZ();      // [-] nominal unit thrust axis (what the FSW believes)
  Eigen::Vector3d t_hat_true_B = Eigen::Vector3d::UnitZ(); // [-] truth axis: t_hat_B tilted by the misalignment
  double F_max = 0.0;                                      // [N] steady-state thrust
  bool acs = true;                                         // false: main engine (not mapped by the FSW)
};

struct VehicleGeometry {
  Eigen::Vector3d r_BcB_B = Eigen::Vector3d::Zero();  // [m] hub mass centre Bc relative to B
  std::vector<Eigen::Vector3d> gs_hat_B;              // [-] (num_rw) nominal wheel spin axes, unit
  std::vector<Eigen::Vector3d> r_WB_B;                // [m] (num_rw) wheel frame origins W relative to B
  std::vector<ThrusterGeometry> thrusters;            // plant order (the scenario's)
  std::vector<int> acs_to_plant;                      // FSW thruster index -> plant thruster index
  std::vector<Eigen::Vector3d> r_TB_B;                // [m] tank centres relative to B (tank, then rcs_tank)
};

// The geometry a scenario gives.  Thrusters with acs: true are the FSW's, in
// scenario order.
VehicleGeometry vehicle_geometry(const Scenario& sc);

// The FSW's view of the geometry (nominal axes; the ACS thrusters only), with
// the wheels' J_s and u_max from the scenario: what fsw_acs_config_set_geometry
// writes into the module configurations.  Counts beyond the FSW's capacities
// are kept as given (fsw_acs_config_set_geometry rejects them).
FswAcsGeometry fsw_geometry(const Scenario& sc, const VehicleGeometry& g);

// Truth thrust axis of a thruster misaligned by `delta` [rad]: the nominal
// axis d tilted by delta about a = unit(d x x_B) (or unit(d x y_B) when d is
// within 25 deg of x_B).  For d = +z_B this tilts toward +x_B.
Eigen::Vector3d misaligned_axis(const Eigen::Vector3d& d, double delta);

}  // namespace harness

#endif  // HARNESS_CORE_VEHICLE_GEOMETRY_H
