// Attitude keys in their other forms (quaternion, 3-2-1 Euler angles,
// axis-angle): the MRP each gives, checked against closed forms worked out
// here (tan of a quarter angle, elementary DCMs composed by hand), the
// shadow set beyond 180 deg, and every rejection with its line and key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "harness/scenario/scenario.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// A valid scenario whose line 13 is `fsw:`; `att` goes on line 14 (under fsw)
// and `init` on line 7 (under spacecraft.initial).
std::string scenario(const std::string& att, const std::string& init = "sigma_BN: [0, 0, 0]")
{
  return "name: att\n"                          // 1
         "duration: 1.0\n"                      // 2
         "rates: {dt: 0.1}\n"                   // 3
         "spacecraft:\n"                        // 4
         "  mass: 100\n"                        // 5
         "  inertia: [10, 11, 12]\n"            // 6
         "  initial: {" + init + "}\n"          // 7
         "wheels:\n"                            // 8
         "  - {model: balanced, axis: [1, 0, 0], J_s: 0.01, u_max: 0.1}\n"  // 9
         "  - {model: balanced, axis: [0, 1, 0], J_s: 0.01, u_max: 0.1}\n"  // 10
         "  - {model: balanced, axis: [0, 0, 1], J_s: 0.01, u_max: 0.1}\n"  // 11
         "seed: 3\n"                            // 12
         "fsw:\n"                               // 13
         "  inertial: {" + att + "}\n"          // 14
         "  mrp_fb: {K: 1, P: 10}\n";           // 15
}

Eigen::Vector3d target_of(const std::string& att)
{
  return harness::load_scenario_text(scenario(att), "t.yaml").fsw.sigma_R0N;
}

std::vector<harness::ScenarioIssue> issues_of(const std::string& text)
{
  try {
    harness::load_scenario_text(text, "t.yaml");
  } catch (const harness::ScenarioError& e) {
    return e.issues();
  }
  return {};
}

// `text` is refused with an issue at t.yaml line `line`, key `key`, whose message holds `words`.
void expect_issue(const std::string& text, const std::string& key, int line, const std::string& words)
{
  const auto issues = issues_of(text);
  ASSERT_FALSE(issues.empty()) << text;
  bool found = false;
  for (const auto& i : issues)
    found = found || (i.key == key && i.line == line && i.file == "t.yaml" && i.message.find(words) != std::string::npos);
  EXPECT_TRUE(found) << key << " -> " << issues.front().str();
}

// Frame rotations about x, y, z by t (the DCM [XN] of a frame X rotated by t
// from N about that axis), written out element by element.
Eigen::Matrix3d R1(double t)
{
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, std::cos(t), std::sin(t), 0, -std::sin(t), std::cos(t);
  return m;
}
Eigen::Matrix3d R2(double t)
{
  Eigen::Matrix3d m;
  m << std::cos(t), 0, -std::sin(t), 0, 1, 0, std::sin(t), 0, std::cos(t);
  return m;
}
Eigen::Matrix3d R3(double t)
{
  Eigen::Matrix3d m;
  m << std::cos(t), std::sin(t), 0, -std::sin(t), std::cos(t), 0, 0, 0, 1;
  return m;
}

// [XN] of an MRP, from the closed form C = I + (8 [s~]^2 - 4 (1 - s.s) [s~]) / (1 + s.s)^2.
Eigen::Matrix3d dcm_of_mrp(const Eigen::Vector3d& s)
{
  Eigen::Matrix3d t;
  t << 0, -s(2), s(1), s(2), 0, -s(0), -s(1), s(0), 0;
  const double s2 = s.squaredNorm();
  return Eigen::Matrix3d::Identity() + (8.0 * t * t - 4.0 * (1.0 - s2) * t) / ((1.0 + s2) * (1.0 + s2));
}

}  // namespace

TEST(ScenarioAttitude, QuaternionOfNinetyDegreesAboutZ)
{
  const double c = std::cos(45.0 * kDeg), s = std::sin(45.0 * kDeg);
  const Eigen::Vector3d sigma = target_of("sigma_R0N_quaternion: [" + std::to_string(c) + ", 0, 0, " +
                                          std::to_string(s) + "]");
  // |q| = 1 within 1e-6 after 6-digit printing: renormalised; sigma = e tan(phi/4)
  EXPECT_NEAR(sigma(0), 0.0, 1e-15);
  EXPECT_NEAR(sigma(1), 0.0, 1e-15);
  EXPECT_NEAR(sigma(2), std::tan(22.5 * kDeg), 1e-7);
  // exact input: exact to rounding
  const Eigen::Vector3d exact = target_of("sigma_R0N_quaternion: [0.70710678118654757, 0, 0, 0.70710678118654757]");
  EXPECT_NEAR(exact(2), std::tan(22.5 * kDeg), 1e-15);
}

TEST(ScenarioAttitude, NegatedQuaternionIsTheSameAttitude)
{
  const Eigen::Vector3d a = target_of("sigma_R0N_quaternion: [0.5, 0.5, 0.5, 0.5]");
  const Eigen::Vector3d b = target_of("sigma_R0N_quaternion: [-0.5, -0.5, -0.5, -0.5]");
  EXPECT_EQ(a, b);
  // 120 deg about (1,1,1)/sqrt(3): sigma = e tan(30 deg)
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a(i), std::tan(30.0 * kDeg) / std::sqrt(3.0), 1e-15);
}

TEST(ScenarioAttitude, AxisAngleAndShadowSetBeyondHalfATurn)
{
  const Eigen::Vector3d a = target_of("sigma_R0N_axis_angle: {axis: [0, 0, 2], angle_deg: 90}");
  EXPECT_NEAR(a(2), std::tan(22.5 * kDeg), 1e-15);  // axis of any length, normalised
  // 270 deg about z is -90 deg about z: the shadow set, |sigma| <= 1
  const Eigen::Vector3d b = target_of("sigma_R0N_axis_angle: {axis: [0, 0, 1], angle_deg: 270}");
  EXPECT_NEAR(b(2), -std::tan(22.5 * kDeg), 1e-15);
  EXPECT_LE(b.norm(), 1.0);
  // 200 deg about x: shadow of tan(50 deg) is -1/tan(50 deg) = -tan(40 deg)
  const Eigen::Vector3d c = target_of("sigma_R0N_axis_angle: {axis: [1, 0, 0], angle_deg: 200}");
  EXPECT_NEAR(c(0), -std::tan(40.0 * kDeg), 1e-15);
  // exactly 180 deg: |sigma| = 1; 360 deg: no rotation
  EXPECT_NEAR(target_of("sigma_R0N_axis_angle: {axis: [0, 1, 0], angle_deg: 180}")(1), 1.0, 1e-15);
  EXPECT_NEAR(target_of("sigma_R0N_axis_angle: {axis: [0, 1, 0], angle_deg: 360}").norm(), 0.0, 1e-15);
  // a quaternion with q0 < 0 (a rotation written beyond 180 deg) gives the short branch too
  const double h = 135.0 * kDeg;  // half of 270 deg
  const Eigen::Vector3d q = target_of("sigma_R0N_quaternion: [" + std::to_string(std::cos(h)) + ", 0, 0, " +
                                      std::to_string(std::sin(h)) + "]");
  EXPECT_NEAR(q(2), -std::tan(22.5 * kDeg), 1e-6);
}

TEST(ScenarioAttitude, Euler321ComposesElementaryRotations)
{
  const double yaw = 30.0, pitch = -20.0, roll = 75.0;
  const Eigen::Vector3d sigma = target_of("sigma_R0N_euler_321_deg: [30, -20, 75]");
  const Eigen::Matrix3d expect = R1(roll * kDeg) * R2(pitch * kDeg) * R3(yaw * kDeg);
  EXPECT_LT((dcm_of_mrp(sigma) - expect).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LE(sigma.norm(), 1.0);
  // a single yaw of 90 deg is 90 deg about z
  EXPECT_NEAR(target_of("sigma_R0N_euler_321_deg: [90, 0, 0]")(2), std::tan(22.5 * kDeg), 1e-15);
  // beyond 180 deg of rotation: yaw 170, roll 170 -> still |sigma| <= 1 and the same DCM
  const Eigen::Vector3d big = target_of("sigma_R0N_euler_321_deg: [170, 0, 170]");
  EXPECT_LE(big.norm(), 1.0);
  EXPECT_LT((dcm_of_mrp(big) - R1(170 * kDeg) * R3(170 * kDeg)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(ScenarioAttitude, EveryAttitudeKeyTakesTheForms)
{
  const std::string init = "sigma_BN_axis_angle: {axis: [1, 0, 0], angle_deg: 90}";
  const harness::Scenario sc = harness::load_scenario_text(scenario("", init), "t.yaml");
  EXPECT_NEAR(sc.spacecraft.initial.sigma_BN(0), std::tan(22.5 * kDeg), 1e-15);
  std::string nadir = scenario("");
  nadir += "  nadir: {sigma_BdR_euler_321_deg: [0, 90, 0]}\n";
  EXPECT_NEAR(harness::load_scenario_text(nadir, "t.yaml").fsw.sigma_BdR(1), std::tan(22.5 * kDeg), 1e-15);
}

TEST(ScenarioAttitude, WrittenAsTheMrpAndReloadedExactly)
{
  const harness::Scenario sc =
      harness::load_scenario_text(scenario("sigma_R0N_euler_321_deg: [10, 20, 30]"), "t.yaml");
  const std::string json = harness::scenario_to_json_text(sc, 2);
  EXPECT_EQ(json.find("euler"), std::string::npos);
  EXPECT_NE(json.find("sigma_R0N"), std::string::npos);
  const harness::Scenario again = harness::load_scenario_text(json, "m.json");
  EXPECT_EQ(again.fsw.sigma_R0N, sc.fsw.sigma_R0N);  // bit for bit
}

TEST(ScenarioAttitude, RejectionsNameLineAndKey)
{
  struct Case {
    std::string att;
    std::string key;
    std::string words;
  };
  const Case cases[] = {
      {"sigma_R0N: [0, 0, 0.1], sigma_R0N_quaternion: [1, 0, 0, 0]", "fsw.inertial.sigma_R0N_quaternion",
       "one form only"},
      {"sigma_R0N_euler_321_deg: [0, 0, 0], sigma_R0N_axis_angle: {axis: [1, 0, 0], angle_deg: 1}",
       "fsw.inertial.sigma_R0N_axis_angle", "one form only"},
      {"sigma_R0N_quaternion: [1, 0, 0, 0.1]", "fsw.inertial.sigma_R0N_quaternion", "|q| = 1.00498"},
      {"sigma_R0N_quaternion: [0, 0, 0, 0]", "fsw.inertial.sigma_R0N_quaternion", "unit quaternion"},
      {"sigma_R0N_quaternion: [1, 0, 0]", "fsw.inertial.sigma_R0N_quaternion", "4 finite numbers"},
      {"sigma_R0N_quaternion: [1, 0, 0, .nan]", "fsw.inertial.sigma_R0N_quaternion", "4 finite numbers"},
      {"sigma_R0N_axis_angle: {axis: [0, 0, 0], angle_deg: 10}", "fsw.inertial.sigma_R0N_axis_angle.axis",
       "must not be zero"},
      {"sigma_R0N_axis_angle: {axis: [0, 0, 1]}", "fsw.inertial.sigma_R0N_axis_angle.angle_deg", "required"},
      {"sigma_R0N_axis_angle: {axis: [0, 0, 1], angle_deg: 400}", "fsw.inertial.sigma_R0N_axis_angle.angle_deg",
       "+-360"},
      {"sigma_R0N_axis_angle: {axis: [0, 0, 1], angle: 1}", "fsw.inertial.sigma_R0N_axis_angle.angle", "unknown"},
      {"sigma_R0N_axis_angle: [0, 0, 1]", "fsw.inertial.sigma_R0N_axis_angle", "expected a map"},
      {"sigma_R0N_euler_321_deg: [1, 2]", "fsw.inertial.sigma_R0N_euler_321_deg", ""},
  };
  for (const Case& c : cases) expect_issue(scenario(c.att), c.key, 14, c.words);
  // the initial attitude: two forms at line 7
  const auto two = issues_of(scenario("", "sigma_BN: [0, 0, 0], sigma_BN_euler_321_deg: [1, 2, 3]"));
  ASSERT_EQ(two.size(), 1u);
  EXPECT_EQ(two[0].key, "spacecraft.initial.sigma_BN_euler_321_deg");
  EXPECT_EQ(two[0].line, 7);
}

TEST(ScenarioAttitude, EventReferenceTakesTheForms)
{
  // line 17: the event's action
  auto with_action = [](const std::string& action) {
    return scenario("") + "events:\n  - {t: 0.5, actions: [" + action + "]}\n";
  };
  const harness::Scenario sc = harness::load_scenario_text(
      with_action("{device: fsw, action: reference, sigma_R0N_axis_angle: {axis: [0, 0, 1], angle_deg: 270}}"),
      "t.yaml");
  ASSERT_EQ(sc.events.size(), 1u);
  const auto& a = sc.events[0].actions;
  ASSERT_EQ(a.size(), 3u);  // read as the three component commands
  EXPECT_EQ(a[0].action, "reference_x");
  EXPECT_EQ(a[1].action, "reference_y");
  EXPECT_EQ(a[2].action, "reference_z");
  EXPECT_NEAR(a[0].value, 0.0, 1e-15);
  EXPECT_NEAR(a[1].value, 0.0, 1e-15);
  EXPECT_NEAR(a[2].value, -std::tan(22.5 * kDeg), 1e-15);  // 270 deg: the shadow set
  // the same as the components written, and the manifest reloads to them bit for bit
  const harness::Scenario again = harness::load_scenario_text(harness::scenario_to_json_text(sc, 2), "m.json");
  ASSERT_EQ(again.events[0].actions.size(), 3u);
  for (size_t c = 0; c < 3; ++c) EXPECT_EQ(again.events[0].actions[c].value, a[c].value);
  const harness::Scenario mrp = harness::load_scenario_text(
      with_action("{device: fsw, action: reference, sigma_R0N: [0.1, -0.2, 0.3]}"), "t.yaml");
  EXPECT_EQ(mrp.events[0].actions[1].value, -0.2);

  struct Case {
    std::string action, key, words;
  };
  const Case cases[] = {
      {"{device: fsw, action: reference}", "events[0].actions[0].sigma_R0N", "required"},
      {"{device: fsw, action: reference, value: 1, sigma_R0N: [0, 0, 0]}", "events[0].actions[0].value", "not a value"},
      {"{device: gyro, action: reference, sigma_R0N: [0, 0, 0]}", "events[0].actions[0].device", "device: fsw"},
      {"{device: fsw, action: reference, sigma_R0N: [0, 0, 0], sigma_R0N_quaternion: [1, 0, 0, 0]}",
       "events[0].actions[0].sigma_R0N_quaternion", "one form only"},
      {"{device: fsw, action: reference, sigma_R0N_quaternion: [3, 0, 0, 0]}",
       "events[0].actions[0].sigma_R0N_quaternion", "unit quaternion"},
      {"{device: fsw, action: reference_x, sigma_R0N: [0, 0, 0]}", "events[0].actions[0].sigma_R0N", "unknown"},
  };
  for (const Case& c : cases) expect_issue(with_action(c.action), c.key, 17, c.words);
}

TEST(ScenarioAttitude, SetOverridesTheFormsAndSetParameterTakesTheMrp)
{
  // --set of a form replaces the MRP written in the file (one spelling at a time)
  const std::string text = scenario("sigma_R0N: [0.1, 0.2, 0.3]");
  const harness::Scenario sc = harness::load_scenario_text(
      text, "t.yaml", {harness::parse_override("fsw.inertial.sigma_R0N_axis_angle={axis: [0, 0, 1], angle_deg: 90}")});
  EXPECT_NEAR(sc.fsw.sigma_R0N(0), 0.0, 1e-15);
  EXPECT_NEAR(sc.fsw.sigma_R0N(2), std::tan(22.5 * kDeg), 1e-15);
  // ...and the MRP replaces a form
  const harness::Scenario back = harness::load_scenario_text(
      scenario("sigma_R0N_quaternion: [0, 0, 0, 1]"), "t.yaml", {harness::parse_override("fsw.inertial.sigma_R0N=[0, 0, 0.5]")});
  EXPECT_EQ(back.fsw.sigma_R0N, Eigen::Vector3d(0, 0, 0.5));
  // a bad form from --set names the --set
  try {
    harness::load_scenario_text(text, "t.yaml", {harness::parse_override("fsw.inertial.sigma_R0N_quaternion=[2, 0, 0, 0]")});
    ADD_FAILURE() << "not refused";
  } catch (const harness::ScenarioError& e) {
    EXPECT_EQ(e.issues().front().key, "fsw.inertial.sigma_R0N_quaternion");
    EXPECT_NE(e.issues().front().message.find("unit quaternion"), std::string::npos);
  }
  // set_parameter takes the MRP only
  harness::Scenario s2 = sc;
  EXPECT_THROW(harness::set_parameter(s2, "fsw.inertial.sigma_R0N_quaternion", Eigen::Vector3d(0, 0, 0)),
               harness::ScenarioError);
  EXPECT_EQ(s2.fsw.sigma_R0N, sc.fsw.sigma_R0N);
}
