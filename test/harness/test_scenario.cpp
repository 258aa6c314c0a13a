// Scenario schema: the shipped S1 loads with the SI values worked out by
// hand; unit suffixes convert; errors carry line numbers; overrides apply;
// the manifest form reloads to the same scenario.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/scenario.h"

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

// Minimal valid scenario; line numbers below refer to this text.
const char* kMini =
    "name: mini\n"                          // 1
    "seed: 3\n"                             // 2
    "duration: 2.0\n"                       // 3
    "rates: {dt: 0.1}\n"                    // 4
    "spacecraft:\n"                         // 5
    "  mass: 100\n"                         // 6
    "  inertia: [10, 11, 12]\n"             // 7
    "wheels:\n"                             // 8
    "  - {model: balanced, axis: [1, 0, 0], J_s: 0.01, u_max: 0.1}\n"  // 9
    "  - {model: balanced, axis: [0, 1, 0], J_s: 0.01, u_max: 0.1}\n"  // 10
    "  - {model: balanced, axis: [0, 0, 1], J_s: 0.01, u_max: 0.1, Omega_0_rpm: 60}\n"  // 11
    "fsw:\n"                                // 12
    "  mrp_fb: {K: 1, P: 10}\n";            // 13

std::vector<harness::ScenarioIssue> issues_of(const std::string& text, std::vector<harness::Override> ov = {})
{
  try {
    harness::load_scenario_text(text, "t.yaml", ov);
  } catch (const harness::ScenarioError& e) {
    return e.issues();
  }
  return {};
}

}  // namespace

TEST(Scenario, ShippedS1LoadsWithSiValues)
{
  const harness::Scenario sc = harness::load_scenario(kS1);
  EXPECT_EQ(sc.name, "s1_sun_pointing");
  EXPECT_EQ(sc.wheels.size(), 4u);
  EXPECT_EQ(sc.rates.fsw_divisor, 10u);
  EXPECT_EQ(sc.tick_ns(), 10'000'000u);
  EXPECT_EQ(sc.num_ticks(), 60'000u);
  // 100 rpm = 100 * 2 pi / 60 rad/s = 10.4719755119659775
  EXPECT_NEAR(sc.wheels[0].params.Omega_0, 10.4719755119659775, 1e-13);
  // 6000 rpm = 628.318530717958648 rad/s
  EXPECT_NEAR(sc.wheels[3].params.Omega_max, 628.318530717958648, 1e-11);
  // 80 deg = 1.39626340159546366 rad
  EXPECT_NEAR(sc.sensors.css.fov, 1.39626340159546366, 1e-15);
  // 20 arcsec = 9.69627362e-5 rad
  EXPECT_NEAR(sc.sensors.star_tracker.sigma_cross, 20.0 * M_PI / 180.0 / 3600.0, 1e-18);
  EXPECT_EQ(sc.wheels[2].params.model, sim::WheelModel::FullyCoupled);  // from wheel_defaults
  EXPECT_EQ(sc.wheels[1].name, "rw2");
  EXPECT_NEAR(sc.wheels[0].params.gs_hat_nom_B.norm(), 1.0, 1e-15);  // renormalised
  EXPECT_EQ(sc.spacecraft.inertia(1, 1), 800.0);
  EXPECT_EQ(sc.spacecraft.inertia(0, 1), 0.0);
  EXPECT_EQ(sc.fsw.mode, harness::FswMode::SunSafe);
  EXPECT_EQ(sc.sensors.css.normals_B.size(), 8u);
}

TEST(Scenario, MinimalTextLoadsWithDefaults)
{
  const harness::Scenario sc = harness::load_scenario_text(kMini, "t.yaml");
  EXPECT_EQ(sc.rates.fsw_divisor, 1u);
  EXPECT_EQ(sc.fsw.mode, harness::FswMode::Inertial);
  EXPECT_EQ(sc.fsw.mrp_fb.K_i, -1.0);
  EXPECT_NEAR(sc.wheels[2].params.Omega_0, 2.0 * M_PI, 1e-14);  // 60 rpm = 2 pi rad/s
  EXPECT_TRUE(sc.outputs.hdf5);
  EXPECT_FALSE(sc.outputs.csv);
}

TEST(Scenario, ErrorsNameFileLineAndKey)
{
  std::string t = kMini;
  t.replace(t.find("mass: 100"), 9, "mass: -1");
  auto v = issues_of(t);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].file, "t.yaml");
  EXPECT_EQ(v[0].line, 6);
  EXPECT_EQ(v[0].column, 9);  // the value "-1" starts in column 9
  EXPECT_EQ(v[0].key, "spacecraft.mass");
  EXPECT_EQ(v[0].str().rfind("t.yaml:6:9: spacecraft.mass: must be > 0 [kg]", 0), 0u) << v[0].str();

  // several problems are all reported
  t = kMini;
  t.replace(t.find("K: 1,"), 5, "K: x,");
  t.replace(t.find("seed: 3"), 7, "sed: 3");
  v = issues_of(t);
  ASSERT_GE(v.size(), 3u);  // unknown 'sed', missing 'seed', bad K
  bool unknown = false, missing = false, gain = false;
  for (const auto& is : v) {
    unknown = unknown || (is.key == "sed" && is.line == 2 && is.message.find("unknown key") != std::string::npos);
    missing = missing || (is.key == "seed" && is.message.find("required key missing") != std::string::npos);
    gain = gain || (is.key == "fsw.mrp_fb.K" && is.line == 13);
  }
  EXPECT_TRUE(unknown);
  EXPECT_TRUE(missing);
  EXPECT_TRUE(gain);
}

TEST(Scenario, WheelIndexAndSuffixErrors)
{
  std::string t = kMini;
  t.replace(t.find("Omega_0_rpm: 60"), 15, "Omega_0_rpm: 60, Omega_0: 1");
  auto v = issues_of(t);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].line, 11);
  EXPECT_NE(v[0].key.find("wheels[2]"), std::string::npos);
  EXPECT_NE(v[0].message.find("not both"), std::string::npos);
}

TEST(Scenario, OverridesApplyAndAreNamedInErrors)
{
  const harness::Scenario sc = harness::load_scenario_text(
      kMini, "t.yaml", {{"fsw.mrp_fb.K", "2.5"}, {"wheels.1.model", "fully_coupled"}, {"wheels.1.m_w", "2"},
                      {"rates.fsw_divisor", "2"}});
  EXPECT_EQ(sc.fsw.mrp_fb.K, 2.5);
  EXPECT_EQ(sc.wheels[1].params.model, sim::WheelModel::FullyCoupled);
  EXPECT_EQ(sc.rates.fsw_divisor, 2u);

  auto v = issues_of(kMini, {{"fsw.mrp_fb.P", "-3"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].where, "--set fsw.mrp_fb.P");
  EXPECT_EQ(v[0].line, 0);
  v = issues_of(kMini, {{"wheels.7.J_s", "1"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].message.find("no list element"), std::string::npos);
  v = issues_of(kMini, {{"fsw.mrp_fb.Q", "1"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].key, "fsw.mrp_fb.Q");
  EXPECT_NE(v[0].message.find("unknown key"), std::string::npos);
  v = issues_of(kMini, {{"nosuch.key", "1"}});  // the override creates an unknown map
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].key, "nosuch");
  EXPECT_EQ(v[0].where, "--set nosuch.key");
  EXPECT_THROW(harness::parse_override("novalue"), std::invalid_argument);
  EXPECT_EQ(harness::parse_override("a.b=c=d").value, "c=d");
}

TEST(Scenario, ManifestFormReloadsIdentically)
{
  const harness::Scenario a = harness::load_scenario(kS1, {{"fsw.rw_null.enabled", "true"}});
  const std::string ja = harness::scenario_to_json_text(a);
  const harness::Scenario b = harness::load_scenario_text(ja, "m.json");
  EXPECT_EQ(harness::scenario_to_json_text(b), ja);
  // bit-exact SI values survive the text round trip
  EXPECT_EQ(a.wheels[0].params.Omega_0, b.wheels[0].params.Omega_0);
  EXPECT_EQ(a.wheels[0].params.gs_hat_nom_B, b.wheels[0].params.gs_hat_nom_B);
  EXPECT_EQ(a.sensors.css.fov, b.sensors.css.fov);
  EXPECT_EQ(a.fsw.Omega_des, b.fsw.Omega_des);
  EXPECT_TRUE(b.fsw.rw_null);
}

TEST(Scenario, NeverCrashesOnOddDocuments)
{
  for (const char* text : {"", "~", "[1, 2]", "42", "name: [", "a: {b: [c, {d: e}]}", "wheels: [[[[]]]]",
                           "spacecraft: {inertia: [[1,2],[3]]}", "? [a]\n: b\n", "rates: {dt: !!binary AAAA}",
                           "fsw: {mrp_fb: {K: 1e400}}", "seed: 99999999999999999999999"}) {
    SCOPED_TRACE(text);
    EXPECT_THROW(harness::load_scenario_text(text, "odd.yaml"), harness::ScenarioError);
  }
}

TEST(Scenario, OverrideIndexOutOfRangeOrAbsurdIsACleanMessage)
{
  for (const char* idx : {"3", "99999999999999999999", "18446744073709551616", "x", "-1"}) {
    SCOPED_TRACE(idx);
    const std::string path = std::string("wheels.") + idx + ".model";
    std::vector<harness::ScenarioIssue> v;
    ASSERT_NO_FATAL_FAILURE(v = issues_of(kMini, {{path, "balanced"}}));
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].message, std::string("no list element '") + idx + "' (the list has 3 entries)");
    EXPECT_EQ(v[0].where, "--set " + path + "=balanced");
  }
  // as the leaf of the path too
  auto v = issues_of(kMini, {{"wheels.99999999999999999999", "{}"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].message.find("no list element"), std::string::npos);
}
