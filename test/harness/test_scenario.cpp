// Scenario schema: the shipped S1 loads with the SI values worked out by
// hand; unit suffixes convert; errors carry line numbers; overrides apply;
// the manifest form reloads to the same scenario.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/scenario/scenario.h"

namespace {

namespace fs = std::filesystem;

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

TEST(Scenario, SetOfAVectorABoolAndAWord)
{
  const harness::Scenario sc = harness::load_scenario_text(
      kMini, "t.yaml",
      {{"spacecraft.initial.omega_BN_B", "[0.01, -0.02, 0.03]"}, {"outputs.csv", "true"},
       {"description", "a: b, [c]"}, {"fsw.mode", "sun_safe"}, {"spacecraft.inertia.1", "13"}});
  EXPECT_EQ(sc.spacecraft.initial.omega_BN_B, Eigen::Vector3d(0.01, -0.02, 0.03));
  EXPECT_TRUE(sc.outputs.csv);
  EXPECT_EQ(sc.description, "a: b, [c]");  // a word key takes the text as it is, not as YAML
  EXPECT_EQ(sc.fsw.mode, harness::FswMode::SunSafe);
  EXPECT_EQ(sc.spacecraft.inertia(1, 1), 13.0);  // one element of a list in the file

  auto v = issues_of(kMini, {{"spacecraft.com.2", "0.5"}});  // no 'com' list in the file
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].message.find("set the whole vector"), std::string::npos) << v[0].message;
  v = issues_of(kMini, {{"spacecraft.inertia.3", "1"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].message, "no list element '3' (the list has 3 entries)");
  v = issues_of(kMini, {{"outputs.csv", "maybe"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].str(), "t.yaml: --set outputs.csv: outputs.csv: expected true or false, got scalar 'maybe'");
  v = issues_of(kMini, {{"spacecraft.initial.omega_BN_B_deg_s", "[1, 2]"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].where, "--set spacecraft.initial.omega_BN_B_deg_s");
  EXPECT_NE(v[0].message.find("list of 3 numbers"), std::string::npos);
  v = issues_of(kMini, {{"spacecraft.com", "[1, 2"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].message.find("not valid YAML"), std::string::npos);
  v = issues_of(kMini, {{"seed.x", "1"}});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].message.find("single value"), std::string::npos);
}

TEST(Scenario, SetOfOneSpellingReplacesTheOther)
{
  // wheel 3 of kMini has Omega_0_rpm: 60; --set Omega_0 replaces it
  const harness::Scenario sc = harness::load_scenario_text(kMini, "t.yaml", {{"wheels.2.Omega_0", "1.5"}});
  EXPECT_EQ(sc.wheels[2].params.Omega_0, 1.5);
  const harness::Scenario sc2 = harness::load_scenario_text(kMini, "t.yaml", {{"wheels[2].Omega_0_rpm", "30"}});
  EXPECT_NEAR(sc2.wheels[2].params.Omega_0, M_PI, 1e-15);
}

TEST(Scenario, UnknownSetPathNamesTheSetWithAHint)
{
  struct Case {
    const char* path;
    const char* key;
    const char* hint;
  };
  for (const Case& c : {Case{"fsw.mrp_fb.Kp", "fsw.mrp_fb.Kp", "did you mean 'K'?"},
                        Case{"rates.dtt", "rates.dtt", "did you mean 'dt'?"},
                        Case{"wheels.1.J_ss", "wheels[1].J_ss", "did you mean 'J_s'?"},
                        Case{"wheel_defaults.Omega_0_rmp", "wheel_defaults.Omega_0_rmp", "did you mean 'Omega_0_rpm'?"},
                        Case{"sensors.tachometr.sigma", "sensors.tachometr", "did you mean 'tachometer'?"},
                        Case{"durtion", "durtion", "did you mean 'duration'?"}}) {
    SCOPED_TRACE(c.path);
    const auto v = issues_of(kMini, {{c.path, "1"}});
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, c.key);
    EXPECT_EQ(v[0].where.rfind("--set ", 0), 0u);
    EXPECT_EQ(v[0].where.find('='), std::string::npos);  // the --set named, as for other problems
    EXPECT_NE(v[0].message.find("unknown key"), std::string::npos);
    EXPECT_NE(v[0].message.find(c.hint), std::string::npos) << v[0].message;
    EXPECT_EQ(v[0].line, 0);
  }
}

// ---- the typed setter ----------------------------------------------------------------

namespace {
std::string set_error(harness::Scenario& sc, const std::string& path, const harness::ParameterValue& v)
{
  try {
    harness::set_parameter(sc, path, v);
  } catch (const harness::ScenarioError& e) {
    EXPECT_EQ(e.issues().size(), 1u);
    return e.issues().front().key + ": " + e.issues().front().message;
  }
  return "";
}
}  // namespace

TEST(SetParameter, SetsTypedValuesLikeTheEquivalentSet)
{
  harness::Scenario a = harness::load_scenario(kS1);
  harness::set_parameter(a, "fsw.mrp_fb.K", 3.5);
  harness::set_parameter(a, "wheels.2.Omega_0_rpm", 50);           // int, suffix converts
  harness::set_parameter(a, "wheels[1].model", "balanced");         // a choice, as a word
  harness::set_parameter(a, "fsw.rw_null.enabled", true);           // a bool
  harness::set_parameter(a, "spacecraft.initial.omega_BN_B_deg_s", Eigen::Vector3d(1, -2, 3));
  harness::set_parameter(a, "sensors.css.fov_deg", 60.0);
  harness::set_parameter(a, "rates.record_divisor", 5);
  harness::set_parameter(a, "seed", uint64_t{18446744073709551615ull});
  harness::set_parameter(a, "fsw.mrp_fb.inertia", Eigen::Vector3d(900, 800, 600));  // diagonal
  harness::set_parameter(a, "wheels.3.axis", Eigen::Vector3d(0, 0, 1.0004));          // renormalised
  const harness::Scenario b = harness::load_scenario(
      kS1, {{"fsw.mrp_fb.K", "3.5"},
            {"wheels.2.Omega_0_rpm", "50"},
            {"wheels.1.model", "balanced"},
            {"fsw.rw_null.enabled", "true"},
            {"spacecraft.initial.omega_BN_B_deg_s", "[1, -2, 3]"},
            {"sensors.css.fov_deg", "60"},
            {"rates.record_divisor", "5"},
            {"seed", "18446744073709551615"},
            {"fsw.mrp_fb.inertia", "[900, 800, 600]"},
            {"wheels.3.axis", "[0, 0, 1.0004]"}});
  EXPECT_EQ(harness::scenario_to_json_text(a), harness::scenario_to_json_text(b));
  EXPECT_EQ(a.wheels[3].params.gs_hat_nom_B, Eigen::Vector3d(0, 0, 1));
  EXPECT_NO_THROW(harness::validate_scenario(a));
}

TEST(SetParameter, RefusesBadValuesNamingTheKeyAndLeavesTheScenarioAlone)
{
  harness::Scenario sc = harness::load_scenario(kS1);
  const std::string before = harness::scenario_to_json_text(sc);
  EXPECT_EQ(set_error(sc, "fsw.mrp_fb.K", -2.0), "fsw.mrp_fb.K: must be > 0 [N*m], got -2");
  EXPECT_EQ(set_error(sc, "fsw.mrp_fb.K", true), "fsw.mrp_fb.K: expected a number, got true");
  EXPECT_EQ(set_error(sc, "fsw.mrp_fb.K", std::nan("")), "fsw.mrp_fb.K: must be finite, got nan");
  EXPECT_EQ(set_error(sc, "outputs.csv", 1), "outputs.csv: expected true or false, got 1");
  EXPECT_EQ(set_error(sc, "rates.fsw_divisor", 2.5), "rates.fsw_divisor: expected an integer, got 2.5");
  EXPECT_EQ(set_error(sc, "rates.fsw_divisor", 0), "rates.fsw_divisor: must be in [1, 1000000], got 0");
  EXPECT_EQ(set_error(sc, "seed", -1), "seed: expected a non-negative integer, got -1");
  EXPECT_EQ(set_error(sc, "fsw.mode", "sunny"), "fsw.mode: expected one of {inertial, sun_safe, detumble, nadir}, got 'sunny'");
  EXPECT_EQ(set_error(sc, "name", "a b"), "name: must be non-empty and use only letters, digits, '_' and '-'");
  EXPECT_EQ(set_error(sc, "wheels.0.axis", Eigen::Vector3d(1, 1, 0)).rfind("wheels[0].axis: must be a unit vector", 0), 0u);
  EXPECT_EQ(set_error(sc, "spacecraft.inertia", Eigen::Vector3d(1, 1, 3)).rfind("spacecraft.inertia: inertia violates", 0), 0u);
  EXPECT_EQ(set_error(sc, "spacecraft.initial.sigma_BN", Eigen::Vector3d(1, 1, 0)),
            "spacecraft.initial.sigma_BN: MRP must have |sigma| <= 1 (use the shadow set)");
  EXPECT_EQ(set_error(sc, "sensors.css.fov_deg", 91.0), "sensors.css.fov_deg: half-angle must be in (0, 90 deg], got 91");
  EXPECT_EQ(set_error(sc, "rates.dt", 1.5e-10), "rates.dt: must be a whole number of nanoseconds (>= 1 ns), got 1.5e-10 s");
  // paths
  EXPECT_EQ(set_error(sc, "fsw.mrp_fb.Kp", 1.0), "fsw.mrp_fb.Kp: unknown key (did you mean 'K'?)");
  EXPECT_EQ(set_error(sc, "wheels.4.J_s", 1.0), "wheels[4].J_s: no list element '4' (the list has 4 entries)");
  EXPECT_EQ(set_error(sc, "wheels.99999999999999999999.J_s", 1.0),
            "wheels[99999999999999999999].J_s: no list element '99999999999999999999' (the list has 4 entries)");
  EXPECT_EQ(set_error(sc, "tank.mass", 1.0), "tank.mass: there is no 'tank' in this scenario");
  EXPECT_NE(set_error(sc, "wheel_defaults.J_s", 1.0).find("set wheels.<i>.<key> instead"), std::string::npos);
  EXPECT_NE(set_error(sc, "fsw.mrp_fb", 1.0).find("names a section"), std::string::npos);
  EXPECT_NE(set_error(sc, "sensors.css.normals", 1.0).find("cannot be set"), std::string::npos);
  EXPECT_EQ(harness::scenario_to_json_text(sc), before);  // nothing changed
  // the issue reads like a --set one
  try {
    harness::set_parameter(sc, "fsw.mrp_fb.P", 0.0);
    FAIL();
  } catch (const harness::ScenarioError& e) {
    EXPECT_EQ(e.issues()[0].str(), kS1 + ": set_parameter fsw.mrp_fb.P: fsw.mrp_fb.P: must be > 0 [N*m*s], got 0");
  }
}

TEST(SetParameter, CrossKeyChecksAreValidateScenarios)
{
  harness::Scenario sc = harness::load_scenario(kS1);
  harness::set_parameter(sc, "wheels.0.u_min", 0.5);  // > u_max 0.2: a check across keys
  harness::set_parameter(sc, "duration", 600.005);    // not a multiple of dt
  try {
    harness::validate_scenario(sc);
    FAIL();
  } catch (const harness::ScenarioError& e) {
    bool umin = false, dur = false;
    for (const auto& is : e.issues()) {
      umin = umin || (is.key == "wheels[0].u_min" && is.message.find("must be < u_max") != std::string::npos);
      dur = dur || (is.key == "duration" && is.message.find("whole number of steps") != std::string::npos);
      EXPECT_EQ(is.line, 0);
      EXPECT_EQ(is.file, kS1);
    }
    EXPECT_TRUE(umin);
    EXPECT_TRUE(dur);
  }
}

TEST(Scenario, S2ManifestReloadsIdentically)
{
  const harness::Scenario a = harness::load_scenario(std::string(KESTREL_SOURCE_DIR) + "/scenarios/s2_mars_orbit_insertion.yaml");
  const std::string ja = harness::scenario_to_json_text(a);
  EXPECT_EQ(harness::scenario_to_json_text(harness::load_scenario_text(ja, "m.json")), ja);
  EXPECT_TRUE(a.burn.has_value());
  EXPECT_TRUE(a.rcs_tank.has_value());
}

// Every shipped scenario's canonical form (a run's manifest) loads back to
// the same form: keys whose 0 means "not given" (fsw.bdot.k, the momentum
// policies' gains, rw_bias.keepout, ...) are left out rather than written as
// a 0 their bounds refuse.
TEST(Scenario, EveryShippedScenariosManifestReloadsIdentically)
{
  size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(KESTREL_SOURCE_DIR) + "/scenarios")) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    const std::string ja = harness::scenario_to_json_text(harness::load_scenario(e.path().string()));
    try {
      EXPECT_EQ(harness::scenario_to_json_text(harness::load_scenario_text(ja, "m.json")), ja) << e.path();
    } catch (const harness::ScenarioError& err) {
      ADD_FAILURE() << e.path() << ": " << err.what();
    }
  }
  EXPECT_GE(n, 11u);
}

TEST(Scenario, EveryKeyIsDocumented)
{
  std::ifstream in(std::string(KESTREL_SOURCE_DIR) + "/docs/harness.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto paths = harness::scenario_key_paths();
  EXPECT_GT(paths.size(), 100u);
  for (const std::string& p : paths) {
    bool spelling = false;  // Omega_0_rpm: documented as Omega_0 (`_rpm`)
    for (const std::string& q : paths) spelling = spelling || (p.size() > q.size() + 1 && p.rfind(q + "_", 0) == 0);
    if (spelling) continue;
    const size_t dot = p.find_last_of('.');
    const std::string leaf = dot == std::string::npos ? p : p.substr(dot + 1);
    EXPECT_NE(doc.find(leaf), std::string::npos) << p << " is not in docs/harness.md";
  }
}

// ---- bounded input, durations, plausibility (issue 12) ----------------------------

namespace {
std::string first_issue(const std::string& text, std::vector<harness::Override> ov = {})
{
  const auto v = issues_of(text, std::move(ov));
  return v.empty() ? "" : v.front().str();
}
std::string with(std::string t, const std::string& from, const std::string& to)
{
  const size_t at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) t.replace(at, from.size(), to);
  return t;
}
}  // namespace

TEST(ScenarioBounds, DurationIsAWholeNumberOfStepsWithinARelativeTolerance)
{
  EXPECT_EQ(first_issue(with(kMini, "duration: 2.0", "duration: 0.3")), "");  // 2.9999999999999996 steps
  EXPECT_EQ(first_issue(with(kMini, "duration: 2.0", "duration: 1e9")), "");  // 1e10 steps, no storage
  EXPECT_EQ(first_issue(with(kMini, "duration: 2.0", "duration: 1e-9")),
            "t.yaml:3:11: duration: shorter than one step dt = 0.1 s");
  EXPECT_NE(first_issue(with(kMini, "duration: 2.0", "duration: 2.05")).find("t.yaml:3:11: duration: must be a whole "
                                                                              "number of steps dt = 0.1 s (it is 20.5"),
            std::string::npos);
  EXPECT_NE(first_issue(with(kMini, "duration: 2.0", "duration: 1e12")).find("too many steps"), std::string::npos);
  // every rate group's period
  EXPECT_NE(first_issue(with(kMini, "rates: {dt: 0.1}", "rates: {dt: 0.1, record_divisor: 3}"))
                .find("duration: must be a whole number of the period of rates.record_divisor (3 steps"),
            std::string::npos);
  EXPECT_NE(first_issue(kMini, {{"sensors.star_tracker.divisor", "7"}})
                .find("period of sensors.star_tracker.divisor (7 steps"),
            std::string::npos);
}

TEST(ScenarioBounds, ActuatorsMustSpanThreeAxes)
{
  const std::string z = "[0, 0, 1]";
  const auto along_z = first_issue(kMini, {{"wheels.0.axis", z}, {"wheels.1.axis", z}});
  EXPECT_NE(along_z.find("t.yaml:8:1: wheels: the wheel axes cannot control three axes"), std::string::npos) << along_z;
  EXPECT_NE(along_z.find("all lie along one line"), std::string::npos) << along_z;
  const auto plane = first_issue(kMini, {{"wheels.2.axis", "[0.6, 0.8, 0]"}});
  EXPECT_NE(plane.find("all lie in one plane, so no torque about [0, 0, 1]"), std::string::npos) << plane;
  // thrusters for attitude: torque directions about the mass centre (S2 ships a spanning set)
  EXPECT_NO_THROW(harness::load_scenario(std::string(KESTREL_SOURCE_DIR) + "/scenarios/s2_mars_orbit_insertion.yaml"));
  // the same check through set_parameter + validate_scenario (no line: the key is named)
  harness::Scenario sc = harness::load_scenario(kS1);
  for (int i = 0; i < 4; ++i) harness::set_parameter(sc, "wheels." + std::to_string(i) + ".axis", Eigen::Vector3d(0, 0, 1));
  try {
    harness::validate_scenario(sc);
    FAIL();
  } catch (const harness::ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].key, "wheels");
  }
}

TEST(ScenarioBounds, UnitAwareAngleAndRateBounds)
{
  const std::string thr = std::string(kMini) +
                          "tank: {mass: 10}\nthrusters:\n  - {position: [0, 0, -1], direction: [0, 0, 1], F_max: 10, "
                          "Isp: 300, acs: false, misalignment: 5.0}\n";
  const auto mis = first_issue(thr);
  EXPECT_NE(mis.find("t.yaml:16:"), std::string::npos) << mis;
  EXPECT_NE(mis.find("thrusters[0].misalignment: must be in [0, 10 deg)"), std::string::npos) << mis;
  EXPECT_NE(mis.find("a value in degrees? use the _deg spelling"), std::string::npos) << mis;
  EXPECT_EQ(first_issue(with(thr, "misalignment: 5.0", "misalignment_deg: 5.0")), "");
  EXPECT_NE(first_issue(kMini, {{"spacecraft.initial.omega_BN_B", "[0, 0, 4]"}}).find("|omega| must be at most 180 deg/s"),
            std::string::npos);
  EXPECT_EQ(first_issue(kMini, {{"spacecraft.initial.omega_BN_B_deg_s", "[0, 0, 4]"}}), "");
  EXPECT_NE(first_issue(kMini, {{"sensors.star_tracker.sigma_cross", "20"}}).find("use the _arcsec spelling"),
            std::string::npos);
  EXPECT_EQ(first_issue(kMini, {{"sensors.star_tracker.sigma_cross_arcsec", "20"}}), "");
  EXPECT_NE(first_issue(kMini, {{"wheels.0.Omega_max", "6000"}}).find("use Omega_max_rpm"), std::string::npos);
}

TEST(ScenarioBounds, NonFilesHugeFilesAndFifosAreNamedNeverRead)
{
  const fs::path dir = fs::temp_directory_path() / "kestrel_scenario_bounds";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto issue_of_path = [](const std::string& p) -> std::string {
    try {
      harness::load_scenario(p);
    } catch (const harness::ScenarioError& e) {
      return e.issues().front().str();
    }
    return "";
  };
  EXPECT_EQ(issue_of_path(dir.string()), dir.string() + ": (file): not a scenario file: a directory");
  EXPECT_EQ(issue_of_path("/dev/null"), "/dev/null: (file): not a scenario file: a character device");
  const fs::path fifo = dir / "pipe.yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(issue_of_path(fifo.string()), fifo.string() + ": (file): not a scenario file: a FIFO");  // never blocks
  const fs::path big = dir / "big.yaml";
  {
    std::ofstream out(big);
    out << "description: \"" << std::string(1u << 20, 'x')  /* 1 MiB: the bound */ << "\"\n";
  }
  EXPECT_NE(issue_of_path(big.string()).find("file too large"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ScenarioBounds, ValidationDoesNotGrowWithTheDuration)
{
  // check_run_configuration builds no run storage: 6e8 s (6e10 steps) costs what 600 s does
  harness::Scenario sc = harness::load_scenario(kS1, {{"duration", "6e8"}});
  const auto t0 = std::chrono::steady_clock::now();
  harness::check_run_configuration(sc);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.5);
}

TEST(ScenarioBounds, OverrideValuesAreBoundedLikeAFile)
{
  // a value is YAML: two documents, a cyclic alias or deep nesting are named, never followed
  for (const char* v : {"[0, 0, 0]\n---\n[1, 1, 1]", "&a [*a, *a, *a]", "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]"}) {
    const auto is = issues_of(kMini, {{"spacecraft.com", v}});
    ASSERT_EQ(is.size(), 1u) << v;
    EXPECT_EQ(is[0].where, std::string("--set spacecraft.com=") + v) << is[0].str();
    EXPECT_EQ(is[0].message.rfind("value: ", 0), 0u) << is[0].str();
  }
}

// docs/harness.md states the most wheels a scenario may list; the reader
// agrees: that many load, one more is refused naming the limit (the page
// said 16 while the reader took 36).  The wheels are S1's pyramid repeated.
TEST(Scenario, DocumentedWheelLimitIsTheReadersLimit)
{
  std::ifstream in(std::string(KESTREL_SOURCE_DIR) + "/docs/harness.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const std::string row = "| `wheels` | list | at most min(`FSW_MAX_RW`, `sim::kMaxWheels`) = ";
  const size_t at = doc.find(row);
  ASSERT_NE(at, std::string::npos);
  const size_t n = std::stoul(doc.substr(at + row.size()));
  std::ifstream s1(kS1);
  std::stringstream s1ss;
  s1ss << s1.rdbuf();
  const std::string text = s1ss.str();
  const size_t w0 = text.find("\n  - {name: rw1");
  const size_t w1 = text.find("\n\nsensors:");
  ASSERT_NE(w0, std::string::npos);
  ASSERT_NE(w1, std::string::npos);
  const char* axes[4] = {"[ 0.541675220,  0.541675220, 0.642787610]", "[-0.541675220,  0.541675220, 0.642787610]",
                         "[-0.541675220, -0.541675220, 0.642787610]", "[ 0.541675220, -0.541675220, 0.642787610]"};
  auto with_wheels = [&](size_t count) {
    std::string w;
    for (size_t i = 0; i < count; ++i)
      w += "\n  - {name: rw" + std::to_string(i + 1) + ", axis: " + axes[i % 4] + ", position: [0.8, 0.8, 1.79]}";
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() / ("kestrel_wheels_" + std::to_string(count) + ".yaml");
    std::string rest = text.substr(w1);
    const size_t d0 = rest.find("Omega_des_rpm: [");  // one speed per wheel
    if (d0 != std::string::npos) {
      std::string speeds;
      for (size_t i = 0; i < count; ++i) speeds += (i ? ", " : "") + std::string("1000");
      rest = rest.substr(0, d0) + "Omega_des_rpm: [" + speeds + rest.substr(rest.find(']', d0));
    }
    std::ofstream(p) << text.substr(0, w0) << w << rest;
    return p.string();
  };
  const harness::Scenario ok = harness::load_scenario(with_wheels(n));
  EXPECT_EQ(ok.wheels.size(), n);
  try {
    harness::load_scenario(with_wheels(n + 1));
    ADD_FAILURE() << n + 1 << " wheels taken";
  } catch (const harness::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("at most " + std::to_string(n) + " wheels, got " + std::to_string(n + 1)),
              std::string::npos)
        << e.what();
  }
}
