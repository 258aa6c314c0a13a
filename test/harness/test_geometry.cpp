// One vocabulary for the geometry (docs/harness.md, "One vocabulary:
// geometry"): vehicle_geometry() forms it once from the scenario, and the
// plant and the FSW configuration both take it from there.  The values below
// are worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "harness/core/run.h"
#include "harness/core/vehicle_geometry.h"
#include "harness/scenario/scenario.h"

namespace {

// Hub (100 kg) and tank (20 kg) both centred at r_BcB_B = (0.1, -0.2, 0.3):
// the vehicle's mass centre C is there too.  Thruster 0 is the main engine
// (not the FSW's); the ACS thrusters sit 1 m from C along x, y and z.
const char* kOffset =
    "name: geometry\n"
    "seed: 1\n"
    "duration: 1.0\n"
    "rates: {dt: 0.1}\n"
    "spacecraft:\n"
    "  mass: 100\n"
    "  inertia: [10, 11, 12]\n"
    "  com: [0.1, -0.2, 0.3]\n"
    "tank: {mass: 20, position: [0.1, -0.2, 0.3]}\n"
    "thrusters:\n"
    "  - {name: main, position: [0.1, -0.2, -0.7], direction: [0, 0, 1], F_max: 100, Isp: 300, acs: false}\n"
    "  - {name: a, position: [1.1, -0.2, 0.3], direction: [0, 0.6, 0.8], F_max: 1, Isp: 200}\n"
    "  - {name: b, position: [0.1, 0.8, 0.3], direction: [0, 0, 1], F_max: 2, Isp: 200, misalignment_deg: 1}\n"
    "  - {name: c, position: [0.1, -0.2, 1.3], direction: [1, 0, 0], F_max: 3, Isp: 200}\n"
    "fsw:\n"
    "  mrp_fb: {K: 1, P: 10}\n";

const double kTol = 1e-15;
const double kFswTol = 4.0 * std::numeric_limits<fsw_real>::epsilon();

Eigen::Vector3d v3(const fsw_real* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol, const std::string& what)
{
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a(k), b(k), tol) << what << " [" << k << "]";
}

}  // namespace

TEST(Geometry, OffsetMassCentreAndThrustersAgreeInPlantAndFsw)
{
  const harness::Scenario sc = harness::load_scenario_text(kOffset, "geometry.yaml");
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  // by hand: r_TjC_B = r_TjB_B - r_CB_B and the unit nominal axes, ACS thrusters a, b, c
  const Eigen::Vector3d r_TjC[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Eigen::Vector3d t_hat[3] = {{0, 0.6, 0.8}, {0, 0, 1}, {1, 0, 0}};
  const double F_max[3] = {1, 2, 3};
  const double d = 1.0 * M_PI / 180.0;  // b's misalignment tilts +z_B toward +x_B (truth only)
  const Eigen::Vector3d t_true_b(std::sin(d), 0.0, std::cos(d));

  // the one place the geometry is formed
  const harness::VehicleGeometry g = harness::vehicle_geometry(sc);
  expect_near(g.r_BcB_B, c, 0.0, "r_BcB_B");
  ASSERT_EQ(g.thrusters.size(), 4u);
  ASSERT_EQ(g.acs_to_plant, (std::vector<int>{1, 2, 3}));
  EXPECT_FALSE(g.thrusters[0].acs);
  ASSERT_EQ(g.r_TB_B.size(), 1u);
  expect_near(g.r_TB_B[0], c, 0.0, "r_TB_B");

  // plant: mass centre, nozzle positions relative to it, truth axes
  harness::Run run(sc);
  const sim::Plant& plant = run.plant();
  const Eigen::Vector3d c_plant = plant.mass_props().c_B;
  expect_near(c_plant, c, kTol, "plant c_B");
  const auto& tp = plant.thrusters().params();
  ASSERT_EQ(tp.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    const sim::ThrusterParams& p = tp[static_cast<size_t>(i + 1)];
    expect_near(p.r_TjB_B - c_plant, r_TjC[i], kTol, "plant r_TjC_B " + std::to_string(i));
    expect_near(p.t_hat_B, i == 1 ? t_true_b : t_hat[i], kTol, "plant t_hat_B " + std::to_string(i));
    EXPECT_NEAR(p.t_hat_B.norm(), 1.0, kTol);
    EXPECT_EQ(p.F_max, F_max[i]);
  }
  expect_near(tp[0].r_TjB_B - c_plant, Eigen::Vector3d(0, 0, -1), kTol, "engine r_TjC_B");

  // FSW: the ACS thrusters only, nominal axes; positions relative to the mass
  // centre the FSW is given each cycle (r_CoM_B = the plant's c_B)
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  ASSERT_EQ(cfg.has_thrusters, 1);
  ASSERT_EQ(cfg.thr_map.num_thr, 3);
  for (int i = 0; i < 3; ++i) {
    expect_near(v3(cfg.thr_map.r_thr_B[i]) - c_plant, r_TjC[i], kFswTol, "FSW r_thr_B - r_CoM_B " + std::to_string(i));
    expect_near(v3(cfg.thr_map.gt_hat_B[i]), t_hat[i], kFswTol, "FSW gt_hat_B " + std::to_string(i));
    EXPECT_NEAR(static_cast<double>(cfg.thr_map.F_max[i]), F_max[i], kFswTol);
  }
  // the torque each ACS thruster gives about C, as the FSW's map sees it: (r - r_C) x t
  const Eigen::Vector3d L_a = (v3(cfg.thr_map.r_thr_B[0]) - c_plant).cross(v3(cfg.thr_map.gt_hat_B[0]));
  expect_near(L_a, Eigen::Vector3d(0, -0.8, 0.6), kFswTol, "torque of a");
}

TEST(Geometry, WheelAxesGivenOnceReachEveryModuleCopy)
{
  const std::string text = std::string(kOffset).substr(0, std::string(kOffset).find("tank:")) +
                           "wheels:\n"
                           "  - {model: balanced, axis: [1, 0, 0], J_s: 0.01, u_max: 0.1}\n"
                           "  - {model: balanced, axis: [0, 0.6, 0.8], J_s: 0.02, u_max: 0.2}\n"
                           "  - {model: balanced, axis: [0, 0, 1], J_s: 0.03, u_max: 0.3}\n"
                           "fsw:\n"
                           "  mrp_fb: {K: 1, P: 10}\n";
  const harness::Scenario sc = harness::load_scenario_text(text, "wheels.yaml");
  const harness::VehicleGeometry g = harness::vehicle_geometry(sc);
  ASSERT_EQ(g.gs_hat_B.size(), 3u);
  expect_near(g.gs_hat_B[1], Eigen::Vector3d(0, 0.6, 0.8), kTol, "gs_hat_B 1");
  const FswAcsGeometry geo = harness::fsw_geometry(sc, g);
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  harness::Run run(sc);
  ASSERT_EQ(geo.num_rw, 3);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d gs = g.gs_hat_B[static_cast<size_t>(i)];
    expect_near(run.plant().wheel_params(i).gs_hat_nom_B, gs, 0.0, "plant gs_hat_nom_B");
    expect_near(v3(geo.gs_hat_B[i]), gs, kFswTol, "FswAcsGeometry gs_hat_B");
    // the flight library's copies (fsw_acs_config_set_geometry), not the harness's
    expect_near(v3(cfg.mrp_fb.gs_hat_B[i]), gs, kFswTol, "mrp_fb gs_hat_B");
    expect_near(v3(cfg.rw_map.gs_hat_B[i]), gs, kFswTol, "rw_map gs_hat_B");
    expect_near(v3(cfg.rw_null.gs_hat_B[i]), gs, kFswTol, "rw_null gs_hat_B");
  }
}
