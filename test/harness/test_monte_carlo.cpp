// Monte Carlo campaigns (harness/monte_carlo.h, docs/monte-carlo.md): the
// distributions' sample statistics against their closed forms (bounds at 4
// standard errors: a false alarm about once in 16,000 checks, and the
// streams are fixed, so a pass stays a pass), the vector dispersions' angles
// recomputed here from the drawn values, reproducibility (threads, order,
// subsets, other dispersions), the criteria on closed-form columns, an
// invalid draw, and a run reproduced from its manifest.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <cstring>
#include <numeric>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "harness/mc/monte_carlo.h"
#include "harness/mc/mc_journal.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "scenario/mc_draw.h"
#include "sim/attitude.h"

namespace fs = std::filesystem;
using namespace harness;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kZ = 4.0;  // [-] bound in standard errors

// A small, fast spacecraft: 3 balanced wheels, 20 s at 10 Hz.
std::string base_text(const std::string& mc)
{
  return R"(name: mc_test
seed: 7
duration: 20.0
rates: {dt: 0.1, fsw_divisor: 1, record_divisor: 1}
spacecraft:
  mass: 750.0
  inertia: [900.0, 800.0, 600.0]
  com: [0.0, 0.0, 0.0]
  initial:
    sigma_BN: [0.1, 0.2, -0.3]
    omega_BN_B: [0.001, -0.01, 0.03]
wheel_defaults: {model: balanced, J_s: 0.0795775, u_max: 0.2}
wheels:
  - {name: rw1, axis: [1.0, 0.0, 0.0]}
  - {name: rw2, axis: [0.0, 1.0, 0.0]}
  - {name: rw3, axis: [0.0, 0.0, 1.0]}
fsw:
  mode: inertial
  mrp_fb: {K: 3.5, P: 30.0}
outputs: {hdf5: false, report_data: false}
events:
  - {name: fail, t: 10.0, actions: [{device: rw2, action: fail_off}]}
monte_carlo:
)" + mc;
}

Scenario load(const std::string& mc) { return load_scenario_text(base_text(mc), "mc_test.yaml"); }

struct Stats {
  double mean = 0, sd = 0;
};
Stats stats(const std::vector<double>& x)
{
  Stats s;
  s.mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  double v = 0;
  for (double a : x) v += (a - s.mean) * (a - s.mean);
  s.sd = std::sqrt(v / static_cast<double>(x.size() - 1));
  return s;
}

// N draws of one dispersion of `mc`, each value read back with `get`.
template <class F>
std::vector<double> draws(const Scenario& sc, size_t n, F get)
{
  std::vector<double> out;
  for (size_t k = 0; k < n; ++k) {
    const McDraw d = draw_run(sc, 99, k, false);  // the draws and each key's checks
    EXPECT_TRUE(d.invalid.empty()) << d.invalid;
    out.push_back(get(d));
  }
  return out;
}

constexpr size_t kN = 2000;  // draws per statistic (a few ms each)

}  // namespace

TEST(McStream, NormalAndUniformMoments)
{
  McStream r(1, 0, "x");
  const size_t n = 200000;
  std::vector<double> g(n), u(n);
  for (size_t i = 0; i < n; ++i) g[i] = r.normal();
  for (size_t i = 0; i < n; ++i) u[i] = r.uniform();
  const Stats sg = stats(g), su = stats(u);
  const double rn = std::sqrt(static_cast<double>(n));
  EXPECT_NEAR(sg.mean, 0.0, kZ / rn);
  EXPECT_NEAR(sg.sd, 1.0, kZ * std::sqrt(0.5) / rn);  // sd of the sample sd: 1/sqrt(2n)
  EXPECT_NEAR(su.mean, 0.5, kZ * std::sqrt(1.0 / 12.0) / rn);
  EXPECT_NEAR(su.sd * su.sd, 1.0 / 12.0, kZ * std::sqrt(1.0 / 180.0) / rn);  // var of U^2 terms: 1/180
  for (double x : u) ASSERT_TRUE(x >= 0.0 && x < 1.0);
}

TEST(McStream, StreamsOfOtherRunsAndKeysAreUncorrelated)
{
  const size_t n = 100000;
  McStream a(1, 0, "spacecraft.mass"), b(1, 1, "spacecraft.mass"), c(1, 0, "spacecraft.com");
  double ab = 0, ac = 0;
  for (size_t i = 0; i < n; ++i) {
    const double x = a.normal();
    ab += x * b.normal();
    ac += x * c.normal();
  }
  // the sample correlation of independent N(0,1) streams has sd 1/sqrt(n)
  EXPECT_NEAR(ab / n, 0.0, kZ / std::sqrt(static_cast<double>(n)));
  EXPECT_NEAR(ac / n, 0.0, kZ / std::sqrt(static_cast<double>(n)));
}

TEST(McDraw, NormalUniformTruncatedNormal)
{
  const double rn = std::sqrt(static_cast<double>(kN));
  {
    const Scenario sc = load("  dispersions: [{key: spacecraft.mass, dist: normal, std: 10}]\n");
    const Stats s = stats(draws(sc, kN, [](const McDraw& d) { return d.sc.spacecraft.mass; }));
    EXPECT_NEAR(s.mean, 750.0, kZ * 10.0 / rn);  // the mean defaults to the nominal value
    EXPECT_NEAR(s.sd, 10.0, kZ * 10.0 / std::sqrt(2.0 * kN));
  }
  {
    const Scenario sc = load("  dispersions: [{key: spacecraft.mass, dist: uniform, min: 700, max: 800}]\n");
    const std::vector<double> x = draws(sc, kN, [](const McDraw& d) { return d.sc.spacecraft.mass; });
    const Stats s = stats(x);
    const double sd = 100.0 / std::sqrt(12.0);
    EXPECT_NEAR(s.mean, 750.0, kZ * sd / rn);
    EXPECT_NEAR(s.sd, sd, kZ * sd * std::sqrt(0.8 / 4.0) / rn);  // sd of a uniform's sample sd: sd*sqrt((k-1)/4n), k = 9/5
    for (double v : x) ASSERT_TRUE(v >= 700.0 && v <= 800.0);
  }
  {
    // truncated to [745, 770] about 750 with sd 10: alpha = -0.5, beta = 2
    const Scenario sc =
        load("  dispersions: [{key: spacecraft.mass, dist: truncated_normal, std: 10, min: 745, max: 770}]\n");
    const std::vector<double> x = draws(sc, kN, [](const McDraw& d) { return d.sc.spacecraft.mass; });
    auto phi = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI); };
    auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
    const double a = -0.5, b = 2.0, Z = Phi(b) - Phi(a);
    const double mean = 750.0 + 10.0 * (phi(a) - phi(b)) / Z;
    const double var = 100.0 * (1.0 + (a * phi(a) - b * phi(b)) / Z - std::pow((phi(a) - phi(b)) / Z, 2));
    const Stats s = stats(x);
    EXPECT_NEAR(s.mean, mean, kZ * std::sqrt(var) / rn);
    for (double v : x) ASSERT_TRUE(v >= 745.0 && v <= 770.0);
  }
}

TEST(McDraw, ChoiceFollowsItsWeights)
{
  const Scenario sc = load(
      "  dispersions: [{key: \"wheels[0].model\", dist: choice, values: [balanced, simple_jitter], weights: [1, 3]}]\n");
  const std::vector<double> x = draws(sc, kN, [](const McDraw& d) {
    EXPECT_EQ(d.drawn.size(), 1u);
    const bool jitter = d.sc.wheels[0].params.model == sim::WheelModel::SimpleJitter;
    EXPECT_EQ(d.drawn[0], jitter ? 1.0 : 0.0);  // the drawn column is the chosen value's index
    return jitter ? 1.0 : 0.0;
  });
  const double p = 0.75;
  EXPECT_NEAR(stats(x).mean, p, kZ * std::sqrt(p * (1 - p) / kN));
}

TEST(McDraw, UnitVectorAnglesAreRayleighOrUniformOnTheCap)
{
  const Eigen::Vector3d n(0.0, 1.0, 0.0);  // wheels[1].axis
  {
    const double sig = 1.0 * kDeg;
    const Scenario sc = load("  dispersions: [{key: \"wheels[1].axis\", dist: unit_vector, angle_std_deg: 1.0}]\n");
    const std::vector<double> th2 = draws(sc, kN, [&](const McDraw& d) {
      const Eigen::Vector3d v = d.sc.wheels[1].params.gs_hat_nom_B;
      EXPECT_NEAR(v.norm(), 1.0, 1e-12);
      const double th = std::atan2(v.cross(n).norm(), v.dot(n));  // recomputed, not the drawn column
      EXPECT_NEAR(th / kDeg, d.drawn[0], 1e-9);
      return th * th;
    });
    // two tilt components N(0, sig): theta^2 is exponential with mean 2 sig^2 (and sd 2 sig^2)
    EXPECT_NEAR(stats(th2).mean, 2 * sig * sig, kZ * 2 * sig * sig / std::sqrt(static_cast<double>(kN)));
  }
  {
    const double mx = 5.0 * kDeg;
    const Scenario sc = load("  dispersions: [{key: \"wheels[1].axis\", dist: unit_vector, angle_max_deg: 5.0}]\n");
    const std::vector<double> c = draws(sc, kN, [&](const McDraw& d) { return d.sc.wheels[1].params.gs_hat_nom_B.dot(n); });
    // uniform on the cap: cos(theta) uniform on [cos(max), 1]
    const double lo = std::cos(mx), w = 1.0 - lo;
    EXPECT_NEAR(stats(c).mean, (1.0 + lo) / 2.0, kZ * w / std::sqrt(12.0 * kN));
    for (double x : c) ASSERT_GE(x, lo - 1e-12);
  }
}

TEST(McDraw, AttitudeRotationAngles)
{
  const Eigen::Vector3d s0(0.1, 0.2, -0.3);
  const Eigen::Matrix3d C0 = sim::dcm_BN_from_sigma(s0);
  auto angle = [&](const McDraw& d) {
    const Eigen::Matrix3d dC = sim::dcm_BN_from_sigma(d.sc.spacecraft.initial.sigma_BN) * C0.transpose();
    const double c = std::clamp((dC.trace() - 1.0) / 2.0, -1.0, 1.0);
    const double th = std::acos(c);
    EXPECT_NEAR(th / kDeg, d.drawn[0], 1e-6);
    return th;
  };
  {
    const double sig = 2.0 * kDeg;
    const Scenario sc = load("  dispersions: [{key: spacecraft.initial.sigma_BN, dist: attitude, angle_std_deg: 2}]\n");
    std::vector<double> th2;
    for (double t : draws(sc, kN, angle)) th2.push_back(t * t);
    // rotation vector N(0, sig) per axis: theta^2 / sig^2 is chi-square with 3 dof (mean 3, sd sqrt(6))
    EXPECT_NEAR(stats(th2).mean, 3 * sig * sig, kZ * std::sqrt(6.0) * sig * sig / std::sqrt(static_cast<double>(kN)));
  }
  {
    const double mx = 30.0 * kDeg;
    const Scenario sc = load("  dispersions: [{key: spacecraft.initial.sigma_BN, dist: attitude, angle_max_deg: 30}]\n");
    const std::vector<double> th = draws(sc, kN, angle);
    EXPECT_NEAR(stats(th).mean, mx / 2, kZ * mx / std::sqrt(12.0 * kN));
    for (double t : th) ASSERT_LE(t, mx + 1e-9);
  }
}

TEST(McDraw, NormalVectorPerAxis)
{
  const Scenario sc =
      load("  dispersions: [{key: spacecraft.initial.omega_BN_B, dist: normal_vector, std: [0.001, 0.002, 0.004]}]\n");
  const Eigen::Vector3d nom(0.001, -0.01, 0.03), sd(0.001, 0.002, 0.004);
  for (int a = 0; a < 3; ++a) {
    const Stats s = stats(draws(sc, kN, [a](const McDraw& d) { return d.sc.spacecraft.initial.omega_BN_B(a); }));
    EXPECT_NEAR(s.mean, nom(a), kZ * sd(a) / std::sqrt(static_cast<double>(kN)));
    EXPECT_NEAR(s.sd, sd(a), kZ * sd(a) / std::sqrt(2.0 * kN));
  }
}

TEST(McDraw, InertiaKeepsPrincipalValuesTimesScaleAndRotatesTheFrame)
{
  const double sig = 3.0 * kDeg;
  const Scenario sc =
      load("  dispersions: [{key: spacecraft.inertia, dist: inertia, angle_std_deg: 3, principal_std_rel: 0.02}]\n");
  std::vector<double> th2;
  for (size_t k = 0; k < kN; ++k) {
    const McDraw d = draw_run(sc, 5, k, false);
    ASSERT_TRUE(d.invalid.empty()) << d.invalid;
    const Eigen::Matrix3d I = d.sc.spacecraft.inertia;
    ASSERT_NEAR((I - I.transpose()).norm(), 0.0, 1e-9);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I);
    // nominal principal values 600, 800, 900 (ascending) times the drawn scales
    const double nominal[3] = {600.0, 800.0, 900.0};
    std::vector<double> want = {nominal[0] * d.drawn[1], nominal[1] * d.drawn[2], nominal[2] * d.drawn[3]};
    std::sort(want.begin(), want.end());
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(es.eigenvalues()(c), want[static_cast<size_t>(c)], 1e-9 * want[2]);
    // the rotation between the nominal principal frame (columns z, y, x for the ascending
    // moments 600, 800, 900) and the drawn one, up to the eigenvectors' signs: its angle
    Eigen::Matrix3d V0;
    V0 << Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX();
    double th = M_PI;
    for (int sgn = 0; sgn < 8; ++sgn) {
      const Eigen::Vector3d s((sgn & 1) ? -1 : 1, (sgn & 2) ? -1 : 1, (sgn & 4) ? -1 : 1);
      const Eigen::Matrix3d R = es.eigenvectors() * s.asDiagonal() * V0.transpose();
      if (R.determinant() < 0) continue;
      th = std::min(th, std::acos(std::clamp((R.trace() - 1.0) / 2.0, -1.0, 1.0)));
    }
    EXPECT_NEAR(th / kDeg, d.drawn[0], 1e-5);
    th2.push_back(th * th);
  }
  EXPECT_NEAR(stats(th2).mean, 3 * sig * sig, kZ * std::sqrt(6.0) * sig * sig / std::sqrt(static_cast<double>(kN)));
}

TEST(McDraw, AnInvalidDrawIsReportedNotRun)
{
  // principal values near the triangle limit (I3 ~ I1 + I2): a 20 % scale often breaks it
  std::string text = base_text("  dispersions: [{key: spacecraft.inertia, dist: inertia, principal_std_rel: 0.2}]\n");
  text.replace(text.find("[900.0, 800.0, 600.0]"), 21, "[400.0, 500.0, 890.0]");
  const Scenario sc = load_scenario_text(text, "mc_test.yaml");
  size_t invalid = 0;
  for (uint64_t k = 0; k < 200; ++k) {
    const McDraw d = draw_run(sc, 1, k);
    if (d.invalid.empty()) continue;
    ++invalid;
    EXPECT_NE(d.invalid.find("spacecraft.inertia"), std::string::npos) << d.invalid;
    EXPECT_EQ(d.drawn.size(), 4u);  // the drawn values stay for the table
  }
  EXPECT_GT(invalid, 10u);
  EXPECT_LT(invalid, 190u);
}

// A run without full results leaves the plant and FSW check to its Run (the
// same builders in the same order): its record is the one the checked draw
// gives.  The FSW's own check (fsw_acs_check: keepout + hysteresis at most
// half the wheel speed limit, 5,000 rad/s, a rule the reader leaves to it)
// refuses part of the drawn hysteresis values; those runs are invalid draws
// with the reason the check names and a folder with their manifest only.
TEST(McDraw, ALightRunRefusedByThePlantOrFswIsTheCheckedDrawsInvalidRun)
{
  const std::string file = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s3_monte_carlo.yaml";
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string at = "  dispersions:\n";
  ASSERT_NE(text.find(at), std::string::npos);
  text.insert(text.find(at) + at.size(), "    - {key: fsw.rw_bias.hysteresis, dist: uniform, min: 0, max: 9000}\n");
  const Scenario sc = load_scenario_text(text, file, {{"duration", "10"}});
  const McPlan plan = make_mc_plan(sc, 7, 12);
  const fs::path dir = fs::temp_directory_path() / ("kestrel_mc_light_check_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  size_t refused = 0;
  for (uint64_t k = 0; k < plan.runs; ++k) {
    const McDraw d = draw_run(plan.nominal, *plan.bound, plan.master_seed, k);
    const fs::path run_dir = dir / std::to_string(k);
    const McRecord r = run_mc_one(plan, k, run_dir, false, nullptr);
    EXPECT_EQ(r.invalid, !d.invalid.empty()) << "run " << k << ": " << d.invalid;
    EXPECT_EQ(r.drawn, d.drawn) << "run " << k;
    if (d.invalid.empty()) {
      EXPECT_TRUE(r.complete) << "run " << k << ": " << r.reason;
      continue;
    }
    ++refused;
    EXPECT_EQ(r.reason, "invalid draw: " + d.invalid);
    EXPECT_NE(d.invalid.find("rejected by fsw_acs_check"), std::string::npos) << d.invalid;
    EXPECT_FALSE(r.pass);
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(run_dir)) files.push_back(e.path().filename().string());
    EXPECT_EQ(files, std::vector<std::string>{"manifest.json"}) << "run " << k;
  }
  fs::remove_all(dir);
  // P(hysteresis > 5000 rad/s - keepout 31.4 rad/s) = (9000 - 4968.6) / 9000 = 0.448 a run
  EXPECT_GT(refused, 0u);
  EXPECT_LT(refused, plan.runs);
}

TEST(McDraw, RunKDependsOnSeedAndIndexAndKeyOnly)
{
  const Scenario a = load(
      "  dispersions:\n    - {key: spacecraft.mass, dist: normal, std: 10}\n"
      "    - {key: \"events[0].t\", dist: uniform, min: 2, max: 18}\n");
  const Scenario b = load(
      "  dispersions:\n    - {key: \"events[0].t\", dist: uniform, min: 2, max: 18}\n"
      "    - {key: spacecraft.com, dist: normal_vector, std: 0.01}\n");
  for (uint64_t k : {0ULL, 7ULL, 123456789ULL}) {
    const McDraw x = draw_run(a, 42, k), y = draw_run(a, 42, k), z = draw_run(b, 42, k);
    EXPECT_EQ(x.drawn, y.drawn);
    EXPECT_EQ(x.sc.seed, y.sc.seed);
    EXPECT_EQ(x.sc.events[0].t, z.sc.events[0].t);  // another set of dispersions, same key: same draw
    EXPECT_NE(x.sc.events[0].t, draw_run(a, 43, k).sc.events[0].t);
    EXPECT_NE(x.sc.events[0].t, draw_run(a, 42, k + 1).sc.events[0].t);
    EXPECT_LT(x.sc.seed, 1ULL << 53);
    EXPECT_FALSE(x.sc.monte_carlo.has_value());
  }
}

namespace {

// One dispersion of every kind (DistKind), a list expanded with [*] and a
// key written with its unit suffix among them.
const char* kEveryKind =
    "  seed: 17\n  dispersions:\n"
    "    - {key: spacecraft.mass, dist: normal, std: 10}\n"
    "    - {key: fsw.mrp_fb.K, dist: truncated_normal, std: 0.5, min: 2.5, max: 4.5}\n"
    "    - {key: \"events[0].t\", dist: uniform, min: 2, max: 18}\n"
    "    - {key: \"wheels[*].model\", dist: choice, values: [balanced, simple_jitter], weights: [2, 1]}\n"
    "    - {key: \"wheels[*].axis\", dist: unit_vector, angle_std_deg: 0.5}\n"
    "    - {key: spacecraft.initial.omega_BN_B, dist: normal_vector, std: [0.001, 0.002, 0.004]}\n"
    "    - {key: spacecraft.initial.sigma_BN, dist: attitude, angle_max_deg: 20}\n"
    "    - {key: spacecraft.inertia, dist: inertia, angle_std_deg: 2, principal_std_rel: 0.03}\n"
    "    - {key: \"wheels[2].Omega_0_rpm\", dist: uniform, half_width: 50}\n";

void expect_same_draw(const McDraw& a, const McDraw& b, uint64_t k)
{
  EXPECT_EQ(a.invalid, b.invalid) << "run " << k;
  ASSERT_EQ(a.drawn.size(), b.drawn.size()) << "run " << k;
  EXPECT_EQ(0, std::memcmp(a.drawn.data(), b.drawn.data(), a.drawn.size() * sizeof(double))) << "run " << k;
  EXPECT_EQ(scenario_to_json_text(a.sc), scenario_to_json_text(b.sc)) << "run " << k;
}

}  // namespace

TEST(McBinding, ACampaignBoundOnceDrawsWhatAFreshBindingDraws)
{
  const Scenario sc = load(kEveryKind);
  const McPlan plan = make_mc_plan(sc, 17, 40);
  ASSERT_TRUE(plan.bound);
  std::set<DistKind> kinds;
  for (const DispersionSpec& s : plan.bound->specs) kinds.insert(s.dist);
  EXPECT_EQ(kinds.size(), 8u);                // every distribution
  EXPECT_EQ(plan.bound->targets.size(), 13u);  // 6 keys + 3 wheels' models + 3 wheels' axes + Omega_0_rpm
  EXPECT_EQ(plan.drawn.size(), 1u + 1 + 1 + 3 + 3 + 3 + 1 + 4 + 1);
  // runs in reverse order, then forward: a draw leaves nothing in the binding
  std::vector<uint64_t> order;
  for (uint64_t k = 40; k-- > 0;) order.push_back(k);
  for (uint64_t k = 0; k < 40; ++k) order.push_back(k);
  for (uint64_t k : order) {
    const McDraw bound = draw_run(sc, *plan.bound, 17, k, false);
    const McDraw fresh = draw_run(sc, 17, k, false);  // bound for this run alone
    ASSERT_TRUE(bound.invalid.empty()) << bound.invalid;
    ASSERT_EQ(bound.drawn.size(), plan.drawn.size());
    expect_same_draw(bound, fresh, k);
    // the values are set where the keys point
    EXPECT_EQ(bound.sc.spacecraft.mass, bound.drawn[0]);
    EXPECT_EQ(bound.sc.fsw.mrp_fb.K, bound.drawn[1]);
    EXPECT_EQ(bound.sc.events[0].t, bound.drawn[2]);
    for (size_t w = 0; w < 3; ++w)
      EXPECT_EQ(bound.sc.wheels[w].params.model == sim::WheelModel::SimpleJitter ? 1.0 : 0.0, bound.drawn[3 + w]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(bound.sc.spacecraft.initial.omega_BN_B(c), bound.drawn[9 + static_cast<size_t>(c)]);
    // stored in rad/s: read back in rpm to rounding
    EXPECT_DOUBLE_EQ(std::get<double>(get_parameter(bound.sc, "wheels[2].Omega_0_rpm").value), bound.drawn.back());
  }
  for (uint64_t k : {0ULL, 39ULL})  // with the checks of the drawn scenario
    expect_same_draw(draw_run(sc, *plan.bound, 17, k), draw_run(sc, 17, k), k);
}

TEST(McBinding, ABadKeyIsRejectedWhenTheCampaignIsReadOrPlanned)
{
  // read: the file's line, the dispersion's key
  std::string text = base_text(kEveryKind);
  text.replace(text.find("fsw.mrp_fb.K,"), 13, "fsw.mrp_fb.Q,");
  try {
    (void)load_scenario_text(text, "mc_test.yaml");
    ADD_FAILURE() << "a dispersion of an unknown key was read";
  } catch (const ScenarioError& e) {
    const ScenarioIssue& is = e.issues().front();
    EXPECT_EQ(is.file, "mc_test.yaml");
    EXPECT_EQ(is.line, 27);  // "    - {key: fsw.mrp_fb.Q, ..."
    EXPECT_EQ(is.key, "monte_carlo.dispersions[1].key");
    EXPECT_NE(is.message.find("unknown key"), std::string::npos) << is.message;
  }
  // planned: a campaign changed after it was read
  Scenario sc = load(kEveryKind);
  const int line = sc.monte_carlo->dispersions[1].line;
  EXPECT_EQ(line, 27);
  sc.monte_carlo->dispersions[1].key = "fsw.mrp_fb.Q";
  sc.monte_carlo->dispersions[3].values[1] = "wobbly";
  try {
    (void)make_mc_plan(sc, 17, 4);
    ADD_FAILURE() << "a campaign with an unknown key was planned";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 4u);  // the key; the choice's value, once per wheel
    const ScenarioIssue& is = e.issues()[0];
    EXPECT_EQ(is.file, "mc_test.yaml");
    EXPECT_EQ(is.line, line);
    EXPECT_EQ(is.key, "monte_carlo.dispersions[1].key");
    EXPECT_NE(is.message.find("unknown key"), std::string::npos) << is.message;
    EXPECT_EQ(e.issues()[1].key, "monte_carlo.dispersions[3].key");
    EXPECT_NE(e.issues()[1].message.find("value 1 ('wobbly')"), std::string::npos) << e.issues()[1].message;
  }
}

namespace {

std::vector<McRecord> campaign(const McPlan& plan, const fs::path& dir, unsigned jobs, std::vector<uint64_t> idx)
{
  fs::remove_all(dir);
  McRunOptions o;
  o.jobs = jobs;
  o.indices = std::move(idx);
  bool stopped = false;
  std::vector<McRecord> r = run_mc_runs(plan, dir, o, stopped);
  EXPECT_FALSE(stopped);
  return r;
}

// Runs 0 to 5 of `plan` into dir (resumed from its journal or not); `ran`
// gets the finished-run count of each progress report.
std::vector<McRecord> run_six(const McPlan& plan, const fs::path& dir, bool resume, std::vector<uint64_t>& ran)
{
  McRunOptions o;
  o.indices = {0, 1, 2, 3, 4, 5};
  o.resume = resume;
  o.progress = [&](const McProgress& p) { ran.push_back(p.done); };
  bool stopped = false;
  return run_mc_runs(plan, dir, o, stopped);
}

void expect_same(const McRecord& a, const McRecord& b)
{
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.pass, b.pass);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.drawn, b.drawn);
  ASSERT_EQ(a.metrics.size(), b.metrics.size());
  for (size_t i = 0; i < a.metrics.size(); ++i)
    EXPECT_TRUE(a.metrics[i] == b.metrics[i] || (std::isnan(a.metrics[i]) && std::isnan(b.metrics[i])));
  EXPECT_EQ(0, std::memcmp(a.series.data(), b.series.data(), a.series.size() * sizeof(float)));
}

const char* kCampaign =
    "  seed: 11\n  dispersions:\n"
    "    - {key: spacecraft.inertia, dist: inertia, angle_std_deg: 2, principal_std_rel: 0.03}\n"
    "    - {key: \"wheels[*].axis\", dist: unit_vector, angle_std_deg: 0.5}\n"
    "    - {key: spacecraft.initial.sigma_BN, dist: attitude, angle_max_deg: 20}\n"
    "    - {key: \"events[0].t\", dist: uniform, min: 5, max: 15}\n"
    "  criteria:\n"
    "    - {name: t_mean, column: t, stat: mean, below: 100}\n"
    "    - {name: t_last, column: t, stat: final, after: 3, until: 12.5, below: 100}\n"
    "    - {name: late_error, column: pointing_error_deg, stat: max, after: 15, below: 5}\n"
    "  retention: {keep_first: 1, thin_samples: 21}\n";

}  // namespace

TEST(McCampaign, CriteriaOnClosedFormColumns)
{
  const McPlan plan = make_mc_plan(load(kCampaign), 11, 3);
  const fs::path dir = fs::temp_directory_path() / "kestrel_mc_test_criteria";
  const std::vector<McRecord> r = campaign(plan, dir, 1, {0, 1, 2});
  ASSERT_EQ(r.size(), 3u);
  size_t t_mean = 0, t_last = 0;
  for (size_t m = 0; m < plan.metrics.size(); ++m) {
    if (plan.metrics[m].col.name == "t_mean") t_mean = m;
    if (plan.metrics[m].col.name == "t_last") t_last = m;
  }
  for (const McRecord& x : r) {
    // t = 0, 0.1, ..., 20 s: the mean is 10 s; the last row with t <= 12.5 s is t = 12.5 s
    EXPECT_NEAR(x.metrics[t_mean], 10.0, 1e-12);
    EXPECT_NEAR(x.metrics[t_last], 12.5, 1e-12);
    EXPECT_TRUE(x.complete);
  }
  // 21 thinned samples over 201 rows: every 10th row, t = 0, 1, ..., 20 s
  ASSERT_EQ(plan.series_t.size(), 21u);
  for (size_t j = 0; j < 21; ++j) EXPECT_NEAR(plan.series_t[j], static_cast<double>(j), 1e-12);
  EXPECT_TRUE(r[0].full);  // keep_first: 1
  EXPECT_TRUE(fs::exists(dir / "runs" / "000000" / "results.h5") || fs::exists(dir / "runs" / "000000" / "summary.txt"));
  EXPECT_TRUE(fs::exists(dir / "runs" / "000002" / "manifest.json"));
  fs::remove_all(dir);
}

TEST(McCampaign, SameRecordsWithAnyThreadsOrderOrSubset)
{
  const McPlan plan = make_mc_plan(load(kCampaign), 11, 8);
  const fs::path d1 = fs::temp_directory_path() / "kestrel_mc_test_j1";
  const fs::path d2 = fs::temp_directory_path() / "kestrel_mc_test_j2";
  const std::vector<McRecord> a = campaign(plan, d1, 1, {0, 1, 2, 3, 4, 5, 6, 7});
  const std::vector<McRecord> b = campaign(plan, d2, 2, {7, 3, 5, 1, 0, 6, 2, 4});  // another order
  ASSERT_EQ(a.size(), 8u);
  ASSERT_EQ(b.size(), 8u);
  for (size_t i = 0; i < 8; ++i) expect_same(a[i], b[i]);
  const std::vector<McRecord> c = campaign(plan, d2, 2, {5, 2});  // --only 2,5
  ASSERT_EQ(c.size(), 2u);
  expect_same(a[2], c[0]);
  expect_same(a[5], c[1]);
  fs::remove_all(d1);
  fs::remove_all(d2);
}

namespace {

std::string file_text(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

// The p-th percentile of the values, linear between order statistics
// (p/100 (n - 1) counted from the smallest): the test's own.
double percentile_of(std::vector<double> v, double p)
{
  std::sort(v.begin(), v.end());
  const double x = p / 100.0 * static_cast<double>(v.size() - 1);
  const double lo = std::floor(x);
  const size_t i = static_cast<size_t>(lo), j = std::min(i + 1, v.size() - 1);
  return v[i] + (x - lo) * (v[j] - v[i]);
}

}  // namespace

// Every finished run's record is on disk as the campaign returns, and the
// summary written from that journal a record at a time is the summary of
// the records in memory, byte for byte; the envelope percentiles (through
// the transposed scratch file) are those of the runs' series.
TEST(McJournal, TheSummaryStreamedFromTheJournalIsTheSummaryOfTheRecords)
{
  const McPlan plan = make_mc_plan(load(kCampaign), 11, 8);
  const fs::path d = fs::temp_directory_path() / "kestrel_mc_test_journal";
  const fs::path da = d / "from_journal", db = d / "from_memory";
  fs::remove_all(d);
  McRunOptions o;
  o.jobs = 2;
  o.indices = {0, 1, 2, 3, 4, 5, 6, 7};
  bool stopped = false;
  const std::vector<McRunState> states = run_mc_journal(plan, d, o, stopped);
  ASSERT_EQ(states.size(), 8u);
  EXPECT_EQ(mc_journal_indices(d), o.indices);
  std::vector<McRecord> recs;
  for (const McRunState& s : states) recs.push_back(read_mc_record(mc_record_path(d, s.index)));
  const std::vector<McRecord> again = campaign(plan, d / "again", 1, o.indices);
  for (size_t i = 0; i < 8; ++i) {
    expect_same(recs[i], again[i]);
    EXPECT_EQ(states[i].pass, recs[i].pass);
  }
  fs::create_directories(da);
  fs::create_directories(db);
  McSummaryInfo info;
  write_mc_outputs(plan, McJournalRecords(d, states), info, da);
  write_mc_outputs(plan, recs, info, db);
  for (const char* f : {"summary.csv", "mc_runs.json", "mc_report_data.json"})
    EXPECT_EQ(file_text(da / f), file_text(db / f)) << f;
  EXPECT_FALSE(fs::exists(da / ".mc_series.scratch"));
  const nlohmann::json j = nlohmann::json::parse(file_text(da / "mc_report_data.json"));
  const size_t S = plan.series_rows.size(), C = plan.series_columns.size();
  ASSERT_GT(S * C, 0u);
  for (size_t c = 0; c < C; ++c)
    for (size_t s = 0; s < S; ++s) {
      std::vector<double> v;
      for (const McRecord& r : recs)
        if (!r.invalid && std::isfinite(r.series[s * C + c])) v.push_back(r.series[s * C + c]);
      const nlohmann::json& lv = j["series"]["percentiles"]["columns"][plan.series_columns[c]];
      const double levels[] = {0.0, 5.0, 50.0, 95.0, 100.0};
      for (size_t l = 0; l < 5; ++l) EXPECT_DOUBLE_EQ(lv[l][s].get<double>(), percentile_of(v, levels[l]));
    }
  EXPECT_EQ(j["table"].size(), 8u);
  fs::remove_all(d);
}

// --resume: the runs with a record are not run again; without it every
// run is (a record left by an earlier campaign is not taken).
TEST(McJournal, AResumedCampaignRunsOnlyTheRunsWithoutARecord)
{
  const McPlan plan = make_mc_plan(load(kCampaign), 11, 6);
  const fs::path d = fs::temp_directory_path() / "kestrel_mc_test_resume";
  const std::vector<McRecord> whole = campaign(plan, d, 1, {0, 1, 2, 3, 4, 5});
  fs::remove(mc_record_path(d, 2));  // runs 2 and 4 were not finished when the campaign was killed
  fs::remove(mc_record_path(d, 4));
  std::ofstream(d / "records" / ".000004.json.tmp") << "{\"kestrel_mc_runs\":1,\"rec";  // a write cut short
  std::vector<uint64_t> ran;
  const std::vector<McRecord> resumed = run_six(plan, d, true, ran);
  EXPECT_EQ(ran, (std::vector<uint64_t>{5, 6}));  // two runs, counted after the 4 done
  ASSERT_EQ(resumed.size(), 6u);
  for (size_t i = 0; i < 6; ++i) expect_same(whole[i], resumed[i]);
  ran.clear();
  run_six(plan, d, false, ran);
  EXPECT_EQ(ran.size(), 6u);
  fs::remove_all(d);
}

// Group commit: a record added to the writer is a temporary file, not
// listed, until its group is committed; then every record of the group is
// in place and reads back.  A writer that commits at once holds none.
TEST(McJournal, AddedRecordsAreListedOnlyOnceCommitted)
{
  const fs::path d = fs::temp_directory_path() / "kestrel_mc_test_group";
  fs::remove_all(d);
  McJournalWriter w(d, 1e9, 1000);  // commits only when asked
  for (uint64_t k : {3ULL, 1ULL, 2ULL}) {
    McRecord r;
    r.index = k;
    r.seed = 100 + k;
    r.metrics = {0.25 * static_cast<double>(k)};
    w.add(r);
  }
  EXPECT_EQ(w.held(), 3u);
  EXPECT_TRUE(mc_journal_indices(d).empty());
  w.commit();
  EXPECT_EQ(w.held(), 0u);
  EXPECT_EQ(mc_journal_indices(d), (std::vector<uint64_t>{1, 2, 3}));
  for (uint64_t k : {1ULL, 2ULL, 3ULL}) {
    const McRecord b = read_mc_record(mc_record_path(d, k));
    EXPECT_EQ(b.index, k);
    EXPECT_EQ(b.seed, 100 + k);
    EXPECT_EQ(b.metrics.at(0), 0.25 * static_cast<double>(k));
  }
  McRecord r;
  r.index = 9;
  McJournalWriter at_once(d, 0.0);
  at_once.add(r);
  EXPECT_EQ(at_once.held(), 0u);
  EXPECT_EQ(mc_journal_indices(d), (std::vector<uint64_t>{1, 2, 3, 9}));
  McJournalWriter by_count(d, 1e9, 2);
  r.index = 10;
  by_count.add(r);
  EXPECT_EQ(by_count.held(), 1u);
  r.index = 11;
  by_count.add(r);
  EXPECT_EQ(by_count.held(), 0u);
  EXPECT_EQ(mc_journal_indices(d), (std::vector<uint64_t>{1, 2, 3, 9, 10, 11}));
  fs::remove_all(d);
}

// A campaign killed (SIGKILL) between two commits of its journal: the runs
// finished since the last commit have no record (their temporary files are
// not listed), and --resume runs them again with the same records as an
// uninterrupted campaign.
TEST(McJournal, ACampaignKilledBetweenCommitsResumesToTheSameRecords)
{
  Scenario sc = load(kCampaign);
  sc.monte_carlo->retention.keep_failing = false;  // no full-results rerun (it commits first)
  const McPlan plan = make_mc_plan(sc, 11, 6);
  const fs::path d = fs::temp_directory_path() / "kestrel_mc_test_kill_between_commits";
  const std::vector<McRecord> whole = campaign(plan, d / "whole", 1, {0, 1, 2, 3, 4, 5});
  fs::remove_all(d / "killed");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {  // one thread: the campaign in this process, killed after its third run
    McRunOptions o;
    o.indices = {0, 1, 2, 3, 4, 5};
    o.commit_seconds = 1e9;
    o.progress = [](const McProgress& p) {
      if (p.done == 3) ::raise(SIGKILL);
    };
    bool stopped = false;
    run_mc_journal(plan, d / "killed", o, stopped);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EXPECT_TRUE(mc_journal_indices(d / "killed").empty());  // three runs finished, none committed
  size_t temps = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(d / "killed" / "records"))
    temps += e.path().filename().string().find(".tmp") != std::string::npos ? 1 : 0;
  EXPECT_EQ(temps, 3u);
  std::vector<uint64_t> ran;
  const std::vector<McRecord> resumed = run_six(plan, d / "killed", true, ran);
  EXPECT_EQ(ran.size(), 6u);  // none was done
  ASSERT_EQ(resumed.size(), 6u);
  for (size_t i = 0; i < 6; ++i) expect_same(whole[i], resumed[i]);
  fs::remove_all(d);
}

// A record is written whole or not at all; the journal lists only whole
// records; a damaged one is refused naming its file.
TEST(McJournal, RecordsAreWrittenWholeAndReadBackOrRefused)
{
  const fs::path d = fs::temp_directory_path() / "kestrel_mc_test_records";
  fs::remove_all(d);
  McRecord r;
  r.index = 42;
  r.seed = 7;
  r.reason = "x";
  r.drawn = {1.5, NAN};
  r.metrics = {2.25};
  r.series = {0.5f, NAN};
  write_mc_record(d, r);
  write_mc_record(d, r);  // replaced
  const McRecord b = read_mc_record(mc_record_path(d, 42));
  EXPECT_EQ(b.index, 42u);
  EXPECT_EQ(b.seed, 7u);
  EXPECT_EQ(b.reason, "x");
  EXPECT_EQ(b.drawn[0], 1.5);
  EXPECT_TRUE(std::isnan(b.drawn[1]));
  EXPECT_EQ(b.series[0], 0.5f);
  for (const char* junk : {".000043.json.tmp", "notes.json", "12x.json", "000044.json~"})
    std::ofstream(d / "records" / junk) << "{}";
  fs::create_directories(d / "records" / "000045.json");
  std::ofstream(d / "records" / "000046.json") << "{\"kestrel_mc_runs\":1,\"records\":[";
  EXPECT_EQ(mc_journal_indices(d), (std::vector<uint64_t>{42, 46}));
  size_t n = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(d / "records"))
    n += e.path().filename().string().find(".tmp") != std::string::npos ? 1 : 0;
  EXPECT_EQ(n, 1u);  // only the one made by hand: write_mc_record leaves none
  try {
    read_mc_record(mc_record_path(d, 46));
    ADD_FAILURE() << "a damaged record was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("000046.json"), std::string::npos) << e.what();
  }
  remove_mc_journal(d);
  EXPECT_FALSE(fs::exists(d / "records"));
  fs::remove_all(d);
}

TEST(McCampaign, ARunIsReproducedFromItsManifest)
{
  const McPlan plan = make_mc_plan(load(kCampaign), 11, 4);
  const fs::path dir = fs::temp_directory_path() / "kestrel_mc_test_manifest";
  const std::vector<McRecord> r = campaign(plan, dir, 2, {0, 1, 2, 3});
  for (uint64_t k : {0ULL, 3ULL}) {
    char name[16];
    std::snprintf(name, sizeof name, "%06llu", static_cast<unsigned long long>(k));
    const Scenario sc = load_scenario((dir / "runs" / name / "manifest.json").string());
    harness::Run run(sc);
    while (run.step_ticks(1000)) {
      if (run.done()) break;
    }
    run.finish();
    // the final pointing error and the thinned series of the campaign's record, bit for bit
    size_t pe = 0;
    for (size_t m = 0; m < plan.metrics.size(); ++m)
      if (plan.metrics[m].col.name == "pointing_error_final") pe = m;
    EXPECT_EQ(run.final_pointing_error_deg(), r[k].metrics[pe]);
    const MemorySink& mem = run.memory();
    const size_t col = run.recorder().column_index("pointing_error_deg");
    const size_t C = plan.series_columns.size();
    size_t sc_col = 0;
    for (size_t c = 0; c < C; ++c)
      if (plan.series_columns[c] == "pointing_error_deg") sc_col = c;
    for (size_t j = 0; j < plan.series_rows.size(); ++j)
      EXPECT_EQ(static_cast<float>(mem.at(plan.series_rows[j], col)), r[k].series[j * C + sc_col]);
  }
  fs::remove_all(dir);
}

TEST(McCampaign, RetentionKeepsTheFirstFailingRunsWhateverTheThreads)
{
  // every run fails (the mean of t over 0..20 s is 10 s, not below 1); keep_first 1,
  // max_failing 2: runs 0 (first), 1 and 2 (the first two failing ones after it)
  // keep full results, the others their manifest only -- with 1 thread or 2
  std::string mc = kCampaign;
  auto sub = [&mc](const std::string& from, const std::string& to) { mc.replace(mc.find(from), from.size(), to); };
  sub("stat: mean, below: 100}", "stat: mean, below: 1.0}");
  sub("retention: {keep_first: 1,", "retention: {keep_first: 1, max_failing: 2,");
  const McPlan plan = make_mc_plan(load(mc), 11, 6);
  for (unsigned jobs : {1u, 2u}) {
    const fs::path dir = fs::temp_directory_path() / ("kestrel_mc_test_ret" + std::to_string(jobs));
    const std::vector<McRecord> r = campaign(plan, dir, jobs, {5, 4, 3, 2, 1, 0});
    ASSERT_EQ(r.size(), 6u);
    for (const McRecord& x : r) {
      EXPECT_FALSE(x.pass);
      EXPECT_EQ(x.full, x.index <= 2) << "run " << x.index << " with " << jobs << " threads";
      char name[16];
      std::snprintf(name, sizeof name, "%06llu", static_cast<unsigned long long>(x.index));
      EXPECT_EQ(fs::exists(dir / "runs" / name / "summary.txt"), x.index <= 2);
      EXPECT_TRUE(fs::exists(dir / "runs" / name / "manifest.json"));
      EXPECT_EQ(x.reason.rfind("t_mean: ", 0), 0u) << x.reason;
    }
    fs::remove_all(dir);
  }
}

// The S3 Monte Carlo reference campaign (scenarios/s3_monte_carlo.yaml),
// shortened: 5 runs of 45,000 s (7.9 orbits: the detumble, whose bound is
// 30,000 s, and 1.6 orbits of the hold window that starts at 36,000 s), on 2
// threads, twice (the second time in another order): the records are bit for
// bit the same.  Each criterion is evaluated (a number, and the pass flag
// follows the file's thresholds), and run 0's criteria are recomputed here
// from its full recorded rows (the run reproduced from its manifest): the
// time in DETUMBLE counted row by row against the mean-of-fsw_mode reading,
// the first exit, the hold's peak |H_wheels_N| and pointing error.  The
// campaign's summary and report are written.
TEST(S3MonteCarlo, ShortCampaignEvaluatesItsCriteriaRepeatablyAndWritesItsReport)
{
#ifndef KESTREL_TEST_CAMPAIGNS
  GTEST_SKIP() << "10 runs of 45,000 s at 0.1 s: a campaign, host-release only";
#endif
  const std::string file = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s3_monte_carlo.yaml";
  const Scenario sc = load_scenario(file, {{"duration", "45000"}, {"outputs.report_data", "false"}});
  ASSERT_TRUE(sc.monte_carlo);
  EXPECT_EQ(sc.monte_carlo->runs, 50u);  // as shipped; shortened here by runs and duration
  const McPlan plan = make_mc_plan(sc, sc.monte_carlo->seed, 5);
  struct Want {
    const char* name;
    bool below;
    double threshold;
  };
  // the file's criteria (their derivation is in its header)
  const Want want[] = {{"detumble_time", false, 2.25}, {"stays_nadir", false, 2.5}, {"hold_momentum", true, 0.011},
                       {"hold_pointing", true, 3.0},   {"no_fsw_error", true, 0.5}};
  std::vector<size_t> crit;
  for (const Want& w : want) {
    size_t m = 0;
    while (m < plan.metrics.size() && plan.metrics[m].col.name != w.name) ++m;
    ASSERT_LT(m, plan.metrics.size()) << w.name;
    EXPECT_GE(plan.metrics[m].criterion, 0) << w.name;
    EXPECT_EQ(plan.metrics[m].below, w.below) << w.name;
    EXPECT_EQ(plan.metrics[m].threshold, w.threshold) << w.name;
    crit.push_back(m);
  }
  const fs::path d1 = fs::temp_directory_path() / "kestrel_mc_test_s3_a";
  const fs::path d2 = fs::temp_directory_path() / "kestrel_mc_test_s3_b";
  const std::vector<McRecord> a = campaign(plan, d1, 2, {0, 1, 2, 3, 4});
  const std::vector<McRecord> b = campaign(plan, d2, 2, {4, 2, 0, 3, 1});
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(b.size(), 5u);
  for (size_t i = 0; i < 5; ++i) expect_same(a[i], b[i]);

  for (const McRecord& r : a) {
    EXPECT_FALSE(r.invalid) << r.reason;
    EXPECT_TRUE(r.complete) << r.reason;
    bool pass = r.complete && !r.invalid;
    for (size_t c = 0; c < crit.size(); ++c) {
      const double v = r.metrics[crit[c]];
      ASSERT_TRUE(std::isfinite(v)) << "run " << r.index << ": " << want[c].name;
      pass = pass && (want[c].below ? v < want[c].threshold : v > want[c].threshold);
    }
    EXPECT_EQ(r.pass, pass) << "run " << r.index << ": " << r.reason;
    std::printf("S3 MC run %llu: %.0f s in DETUMBLE, hold peak |H_w| %.3g N*m*s, pointing %.2f deg: %s\n",
                static_cast<unsigned long long>(r.index), (3.0 - r.metrics[crit[0]]) * 40000.0, r.metrics[crit[2]],
                r.metrics[crit[3]], r.pass ? "pass" : r.reason.c_str());
  }

  // run 0 again from its manifest, its criteria from the full rows
  harness::Run run(load_scenario((d1 / "runs" / "000000" / "manifest.json").string()));
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const MemorySink& m = run.memory();
  const std::vector<double> t = m.column("t"), mode = m.column("fsw_mode"), pe = m.column("pointing_error_deg");
  const std::vector<double> hx = m.column("H_wheels_N_x"), hy = m.column("H_wheels_N_y"), hz = m.column("H_wheels_N_z");
  size_t rows = 0, in_detumble = 0, exit = t.size();
  double mode_min = 10.0, h_max = 0.0, pe_max = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (exit == t.size() && mode[k] != 2.0) exit = k;
    if (t[k] <= 39990.0) {
      ++rows;
      in_detumble += mode[k] == 2.0 ? 1 : 0;
    }
    if (t[k] >= 30000.0) mode_min = std::min(mode_min, mode[k]);
    if (t[k] >= 36000.0) {
      h_max = std::max(h_max, std::sqrt(hx[k] * hx[k] + hy[k] * hy[k] + hz[k] * hz[k]));
      pe_max = std::max(pe_max, pe[k]);
    }
  }
  ASSERT_EQ(rows, 4000u);  // t = 0, 10, ..., 39,990 s
  ASSERT_LT(exit, t.size()) << "run 0 never left DETUMBLE";
  const double mean = (2.0 * static_cast<double>(in_detumble) + 3.0 * static_cast<double>(rows - in_detumble)) / 4000.0;
  EXPECT_NEAR(a[0].metrics[crit[0]], mean, 1e-12);
  // the file's reading of it: (3 - mean) x 40,000 s is the first exit time (no re-entry)
  EXPECT_NEAR((3.0 - a[0].metrics[crit[0]]) * 40000.0, t[exit], 1e-6);
  EXPECT_EQ(a[0].metrics[crit[1]], mode_min);
  EXPECT_NEAR(a[0].metrics[crit[2]], h_max, 1e-15);
  EXPECT_EQ(a[0].metrics[crit[3]], pe_max);

  // the summary and the report
  McSummaryInfo info;
  info.source = file;
  write_mc_outputs(plan, a, info, d1);
  for (const char* f : {"summary.csv", "summary.h5", "mc_report_data.json", "mc_runs.json"})
    EXPECT_TRUE(fs::exists(d1 / f)) << f;
  std::ifstream csv(d1 / "summary.csv");
  std::string header;
  std::getline(csv, header);
  for (const Want& w : want) EXPECT_NE(header.find(w.name), std::string::npos) << header;
#ifdef KESTREL_TEST_HAVE_REPORT
  ASSERT_TRUE(fs::exists(d1 / "mc_report.html"));
  EXPECT_GT(fs::file_size(d1 / "mc_report.html"), 20000u);
  std::ifstream page(d1 / "mc_report.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("s3_monte_carlo"), std::string::npos);
#endif
  fs::remove_all(d1);
  fs::remove_all(d2);
}

namespace {

// Two node trees alike in everything the reader looks at: the kind, a
// scalar's text, a map's keys in order, each element.
void expect_same_tree(const YAML::Node& a, const YAML::Node& b, const std::string& at)
{
  ASSERT_EQ(a.Type(), b.Type()) << at;
  switch (a.Type()) {
    case YAML::NodeType::Scalar: EXPECT_EQ(a.Scalar(), b.Scalar()) << at; break;
    case YAML::NodeType::Sequence:
      ASSERT_EQ(a.size(), b.size()) << at;
      for (size_t i = 0; i < a.size(); ++i) expect_same_tree(a[i], b[i], at + "[" + std::to_string(i) + "]");
      break;
    case YAML::NodeType::Map: {
      ASSERT_EQ(a.size(), b.size()) << at;
      auto ib = b.begin();
      for (auto ia = a.begin(); ia != a.end(); ++ia, ++ib) {
        ASSERT_EQ(ia->first.Scalar(), ib->first.Scalar()) << at;
        expect_same_tree(ia->second, ib->second, at + "." + ia->first.Scalar());
      }
      break;
    }
    default: break;
  }
}

// A scenario through the writer's text and YAML::Load, and through the
// tree built from the writer's JSON: the same tree, and the same scenario
// read from it (or the same first problem).
void expect_same_reload(const Scenario& sc, const std::string& what)
{
  const std::string text = scenario_to_json_text(sc);
  expect_same_tree(YAML::Load(text), yaml_of_json(nlohmann::json::parse(text)), what);
  std::string via_text, direct;
  try {
    via_text = scenario_to_json_text(load_canonical_scenario_text(text, "(drawn scenario)"));
  } catch (const ScenarioError& e) {
    via_text = "refused: " + e.issues().front().key + ": " + e.issues().front().message;
  }
  try {
    direct = scenario_to_json_text(reload_canonical_scenario(sc, "(drawn scenario)"));
  } catch (const ScenarioError& e) {
    direct = "refused: " + e.issues().front().key + ": " + e.issues().front().message;
  }
  EXPECT_EQ(via_text, direct) << what;
}

}  // namespace

// A draw is read back from the node tree built from the writer's JSON, not
// from its text (check_draw): for the draws of the shipped campaigns and
// of every kind of dispersion, for refused draws and for every shipped
// scenario, that tree is the one YAML::Load makes of the text, and the
// scenario read (or the problem found) is the same.
TEST(McDraw, TheReloadWithoutTextIsTheReloadOfTheText)
{
  const std::string dir = std::string(KESTREL_SOURCE_DIR) + "/scenarios/";
  std::vector<std::pair<std::string, Scenario>> campaigns;
  for (const char* f : {"s1_monte_carlo.yaml", "s3_monte_carlo.yaml", "mc_demo_drivers.yaml"})
    campaigns.emplace_back(f, load_scenario(dir + f));
  campaigns.emplace_back("every kind", load(kEveryKind));
  // events[0].t beyond the 20 s run: about half the draws are refused when read back
  campaigns.emplace_back("late event", load("  dispersions: [{key: \"events[0].t\", dist: uniform, min: 2, max: 40}]\n"));
  size_t refused = 0;
  for (const auto& [name, sc] : campaigns)
    for (uint64_t k = 0; k < 60; ++k) {
      const McDraw d = draw_run(sc, sc.monte_carlo->seed, k, false);  // the draws, not yet read back
      ASSERT_TRUE(d.invalid.empty()) << name << " run " << k << ": " << d.invalid;
      expect_same_reload(d.sc, name + " run " + std::to_string(k));
      refused += draw_run(sc, sc.monte_carlo->seed, k).invalid.empty() ? 0 : 1;
    }
  EXPECT_GT(refused, 10u);
  EXPECT_LT(refused, 50u);
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".yaml") expect_same_reload(load_scenario(e.path().string()), e.path().filename().string());
  // strings the text escapes or that read as other kinds when plain
  Scenario odd = load(kEveryKind);
  for (const char* s : {"", "null", "~", "true", "0x1f", "1e3", "a \"quoted\" \\ back\\slash", "tab\there\nline",
                        "\xc3\xa9t\xc3\xa9 \x01\x1f", "# not a comment: - [x] {y}"}) {
    odd.description = s;
    expect_same_reload(odd, std::string("description ") + s);
  }
}
