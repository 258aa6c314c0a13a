// thr_momentum: thruster momentum management and dumping.
//
// Expected values are hand-derived (wheel momentum of a pyramid, Delta_H of
// the dump formula, pulse/coast timelines counted in control cycles,
// propellant from F t / (Isp g0)) or come from a plant written in the test
// (the wheels absorb the commanded thruster torque: h_w += L_thr dt).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "fsw/thr_momentum.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();
const double kG0 = 9.80665;
const uint64_t kNsPerS = 1000000000ull;

// Binary-exact timing and torque: dt = 1/8 s, L_dump = 1/64 N*m, so a full
// cycle carries 1/512 N*m*s; t_pulse_max = 2 s (16 cycles, 1/32 N*m*s per
// pulse), t_min_pulse = 1/4 s (1/256 N*m*s), t_coast = 1.5 s (12 cycles).
constexpr double kDt = 0.125;
constexpr uint64_t kDtNs = 125000000ull;
constexpr double kLdump = 1.0 / 64.0;
constexpr double kTpulse = 2.0;
constexpr double kTmin = 0.25;
constexpr double kTcoast = 1.5;
constexpr double kHup = 1.3;
constexpr double kHlo = 1.0;
constexpr double kJ = 0.05;

struct Fixture {
  std::unique_ptr<FswThrMomentumConfig> cfg = rwt::make0<FswThrMomentumConfig>();
  std::unique_ptr<FswThrMomentumState> st = rwt::make0<FswThrMomentumState>();
  std::unique_ptr<FswThrMomentumIn> in = rwt::make0<FswThrMomentumIn>();
  std::unique_ptr<FswThrMomentumOut> out = rwt::make0<FswThrMomentumOut>();
  double g[4][3];

  Fixture()
  {
    rwt::pyramid4(g);
    cfg->num_rw = 4;
    rwt::set_axes(cfg->gs_hat_B, g, 4);
    for (int i = 0; i < 4; i++) cfg->J_s[i] = static_cast<fsw_real>(kJ);
    cfg->h_upper = static_cast<fsw_real>(kHup);
    cfg->h_lower = static_cast<fsw_real>(kHlo);
    cfg->L_dump = static_cast<fsw_real>(kLdump);
    cfg->t_pulse_max = static_cast<fsw_real>(kTpulse);
    cfg->t_min_pulse = static_cast<fsw_real>(kTmin);
    cfg->t_coast = static_cast<fsw_real>(kTcoast);
    cfg->dt_cycle = static_cast<fsw_real>(kDt);
    cfg->num_thr = 2;
    cfg->F_max[0] = FSW_R(1.0);
    cfg->F_max[1] = FSW_R(2.0);
    cfg->Isp = FSW_R(200.0);
    in->enable = 1;
  }
  FswStatus init() { return fsw_thr_momentum_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_thr_momentum_update(st.get(), cfg.get(), in.get(), out.get()); }
  // Wheel speeds whose momentum is h (equal inertias J on the pyramid:
  // [Gs][Gs]^T = (4/3) I, so Omega_i = (3/(4J)) g_i . h gives sum J Omega_i g_i = h).
  void set_h(const double h[3])
  {
    for (int i = 0; i < 4; i++)
      in->Omega[i] = static_cast<fsw_real>(0.75 / kJ * (g[i][0] * h[0] + g[i][1] * h[1] + g[i][2] * h[2]));
  }
  void garbage()
  {
    std::memset(out.get(), 0x5A, sizeof *out);
  }
};

std::unique_ptr<Fixture> ready()
{
  auto f = rwt::make0<Fixture>();
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

// Field-by-field equality of two outputs (memcmp would also compare padding).
void expect_out_eq(const FswThrMomentumOut& a, const FswThrMomentumOut& b, const std::string& why)
{
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(a.L_thr_B[k], b.L_thr_B[k]) << why;
    EXPECT_EQ(a.dH_rem_B[k], b.dH_rem_B[k]) << why;
    EXPECT_EQ(a.h_w_B[k], b.h_w_B[k]) << why;
    EXPECT_EQ(a.dH_B[k], b.dH_B[k]) << why;
  }
  EXPECT_EQ(a.phase, b.phase) << why;
  EXPECT_EQ(a.h_norm, b.h_norm) << why;
  EXPECT_EQ(a.dumps, b.dumps) << why;
  EXPECT_EQ(a.aborts, b.aborts) << why;
  EXPECT_EQ(a.pulses, b.pulses) << why;
  EXPECT_EQ(a.t_dump, b.t_dump) << why;
  EXPECT_EQ(a.prop_dump, b.prop_dump) << why;
  EXPECT_EQ(a.prop_total, b.prop_total) << why;
}

// The state with its health counters replaced by `health` (memcpy: the
// padding bytes are compared too, and both states start zeroed).
std::unique_ptr<FswThrMomentumState> state_copy(const FswThrMomentumState& st, const FswHealth& health)
{
  auto c = rwt::make0<FswThrMomentumState>();
  std::memcpy(c.get(), &st, sizeof st);
  c->health = health;
  return c;
}

// |v| in double for double or fsw_real vectors.
template <class R>
double norm3(const R v[3])
{
  const double d[3] = {double(v[0]), double(v[1]), double(v[2])};
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

// Direction of the test momentum: (0.36, 0.48, 0.8) is a unit vector.
const double kDir[3] = {0.36, 0.48, 0.8};

void scaled_dir(double h[3], double m)
{
  for (int k = 0; k < 3; k++) h[k] = m * kDir[k];
}

// One record per cycle of the closed-loop dump simulation.
struct Cycle {
  FswStatus s;
  int phase;
  double L[3];
  double h[3];
  double rem;
};

// The test's plant: the wheels absorb the thruster torque requested in a
// cycle over the next dt (h_w += L_thr dt); the attitude stays put.
std::vector<Cycle> simulate(Fixture& f, double h[3], int cycles, uint64_t t0 = 0)
{
  std::vector<Cycle> log;
  for (int c = 0; c < cycles; c++) {
    f.in->t_ns = t0 + static_cast<uint64_t>(c) * kDtNs;
    f.set_h(h);
    Cycle r{};
    r.s = f.update();
    r.phase = f.out->phase;
    for (int k = 0; k < 3; k++) {
      r.L[k] = double(f.out->L_thr_B[k]);
      r.h[k] = h[k];
      h[k] += r.L[k] * kDt;
    }
    r.rem = norm3(f.out->dH_rem_B);
    log.push_back(r);
  }
  return log;
}

}  // namespace

// ---- configuration --------------------------------------------------------

// Verifies: REQ-THRMOM-001
TEST(ThrMomentumConfig, RejectsEachBadField)
{
  struct Row {
    const char* why;
    void (*spoil)(FswThrMomentumConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswThrMomentumConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many wheels", [](FswThrMomentumConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"no thrusters", [](FswThrMomentumConfig* c) { c->num_thr = 0; }, FSW_E_CAPACITY},
      {"too many thrusters", [](FswThrMomentumConfig* c) { c->num_thr = FSW_MAX_THR + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswThrMomentumConfig* c) { c->gs_hat_B[2][0] = FSW_R(0.9); }, FSW_E_CONFIG},
      {"axis NaN", [](FswThrMomentumConfig* c) { c->gs_hat_B[1][1] = kNaN; }, FSW_E_CONFIG},
      {"J_s zero", [](FswThrMomentumConfig* c) { c->J_s[3] = 0; }, FSW_E_CONFIG},
      {"J_s negative", [](FswThrMomentumConfig* c) { c->J_s[0] = FSW_R(-0.05); }, FSW_E_CONFIG},
      {"J_s above FSW_RW_J_S_MAX", [](FswThrMomentumConfig* c) { c->J_s[1] = FSW_RW_J_S_MAX * 2; }, FSW_E_CONFIG},
      {"h_upper NaN", [](FswThrMomentumConfig* c) { c->h_upper = kNaN; }, FSW_E_CONFIG},
      {"h_upper above FSW_THR_MOM_H_MAX",
       [](FswThrMomentumConfig* c) {
         c->h_upper = FSW_THR_MOM_H_MAX * 2;
         c->L_dump = FSW_THR_MOM_L_MAX;
       },
       FSW_E_CONFIG},
      {"h_upper beyond a million full cycles", [](FswThrMomentumConfig* c) { c->h_upper = FSW_R(4000.0); },
       FSW_E_CONFIG},
      {"h_lower = h_upper", [](FswThrMomentumConfig* c) { c->h_lower = c->h_upper; }, FSW_E_CONFIG},
      {"h_lower > h_upper", [](FswThrMomentumConfig* c) { c->h_lower = FSW_R(2.0); }, FSW_E_CONFIG},
      {"h_lower negative", [](FswThrMomentumConfig* c) { c->h_lower = FSW_R(-0.1); }, FSW_E_CONFIG},
      {"h_lower Inf", [](FswThrMomentumConfig* c) { c->h_lower = kInf; }, FSW_E_CONFIG},
      {"band below one minimum pulse", [](FswThrMomentumConfig* c) { c->h_lower = FSW_R(1.298); },
       FSW_E_CONFIG},
      {"L_dump zero", [](FswThrMomentumConfig* c) { c->L_dump = 0; }, FSW_E_CONFIG},
      {"L_dump negative", [](FswThrMomentumConfig* c) { c->L_dump = FSW_R(-0.01); }, FSW_E_CONFIG},
      {"L_dump Inf", [](FswThrMomentumConfig* c) { c->L_dump = kInf; }, FSW_E_CONFIG},
      {"L_dump above FSW_THR_MOM_L_MAX", [](FswThrMomentumConfig* c) { c->L_dump = FSW_THR_MOM_L_MAX * 2; },
       FSW_E_CONFIG},
      {"t_min_pulse > t_pulse_max", [](FswThrMomentumConfig* c) { c->t_min_pulse = FSW_R(2.5); }, FSW_E_CONFIG},
      {"t_min_pulse zero", [](FswThrMomentumConfig* c) { c->t_min_pulse = 0; }, FSW_E_CONFIG},
      {"t_pulse_max NaN", [](FswThrMomentumConfig* c) { c->t_pulse_max = kNaN; }, FSW_E_CONFIG},
      {"t_pulse_max beyond a million cycles",
       [](FswThrMomentumConfig* c) {
         c->dt_cycle = FSW_R(1e-3);
         c->t_pulse_max = FSW_R(2000.0);
       },
       FSW_E_CONFIG},
      {"t_coast negative", [](FswThrMomentumConfig* c) { c->t_coast = FSW_R(-1.0); }, FSW_E_CONFIG},
      {"t_coast NaN", [](FswThrMomentumConfig* c) { c->t_coast = kNaN; }, FSW_E_CONFIG},
      {"dt_cycle zero", [](FswThrMomentumConfig* c) { c->dt_cycle = 0; }, FSW_E_CONFIG},
      {"dt_cycle NaN", [](FswThrMomentumConfig* c) { c->dt_cycle = kNaN; }, FSW_E_CONFIG},
      {"dt_cycle above FSW_THR_MOM_DT_MAX", [](FswThrMomentumConfig* c) { c->dt_cycle = FSW_R(2000.0); },
       FSW_E_CONFIG},
      {"F_max zero", [](FswThrMomentumConfig* c) { c->F_max[1] = 0; }, FSW_E_CONFIG},
      {"F_max NaN", [](FswThrMomentumConfig* c) { c->F_max[0] = kNaN; }, FSW_E_CONFIG},
      {"F_max above FSW_THR_MOM_F_MAX", [](FswThrMomentumConfig* c) { c->F_max[0] = FSW_THR_MOM_F_MAX * 2; },
       FSW_E_CONFIG},
      {"Isp zero", [](FswThrMomentumConfig* c) { c->Isp = 0; }, FSW_E_CONFIG},
      {"Isp negative", [](FswThrMomentumConfig* c) { c->Isp = FSW_R(-200.0); }, FSW_E_CONFIG},
      {"Isp NaN", [](FswThrMomentumConfig* c) { c->Isp = kNaN; }, FSW_E_CONFIG},
      {"Isp above FSW_THR_MOM_ISP_MAX", [](FswThrMomentumConfig* c) { c->Isp = FSW_THR_MOM_ISP_MAX * 2; },
       FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = rwt::make0<Fixture>();
    ASSERT_EQ(fsw_thr_momentum_check(f->cfg.get()), FSW_OK);
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_thr_momentum_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->st->ready, 0) << row.why;
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT) << row.why;
    expect_out_eq(FswThrMomentumOut{}, *f->out, row.why);
  }
  // boundary values that are accepted: h_lower = 0, t_coast = 0,
  // t_min_pulse = t_pulse_max, a band of exactly one minimum pulse
  auto f = rwt::make0<Fixture>();
  f->cfg->h_lower = 0;
  f->cfg->t_coast = 0;
  EXPECT_EQ(fsw_thr_momentum_check(f->cfg.get()), FSW_OK);
  f->cfg->t_min_pulse = f->cfg->t_pulse_max;
  EXPECT_EQ(fsw_thr_momentum_check(f->cfg.get()), FSW_OK);
  f->cfg->t_min_pulse = FSW_R(0.25);
  f->cfg->h_lower = FSW_R(1.0);
  f->cfg->h_upper = FSW_R(1.0) + FSW_R(0.00390625);  // 1 + 1/256: exact in both types
  EXPECT_EQ(fsw_thr_momentum_check(f->cfg.get()), FSW_OK);
}

// ---- wheel momentum ---------------------------------------------------------

// Pyramid g_i = (sx, sy, 1)/sqrt3, (sx, sy) = (+,+), (-,+), (-,-), (+,-);
// J = (0.1, 0.2, 0.3, 0.4), Omega = (100, -50, 20, 10): J Omega = (10, -10, 6, 4),
// h = (10 + 10 - 6 + 4, 10 - 10 - 6 - 4, 10 - 10 + 6 + 4)/sqrt3 = (18, -10, 10)/sqrt3,
// |h| = sqrt(524/3).  Wheel 3 unavailable (Omega NaN, not read):
// J Omega = (10, -10, 0, 4) -> h = (24, -4, 4)/sqrt3.
// Verifies: REQ-THRMOM-002
TEST(ThrMomentumWheels, PyramidMomentumByHand)
{
  auto f = rwt::make0<Fixture>();
  const double J[4] = {0.1, 0.2, 0.3, 0.4}, Om[4] = {100, -50, 20, 10};
  for (int i = 0; i < 4; i++) {
    f->cfg->J_s[i] = static_cast<fsw_real>(J[i]);
    f->in->Omega[i] = static_cast<fsw_real>(Om[i]);
  }
  f->cfg->h_upper = FSW_R(100.0);  // no dump
  ASSERT_EQ(f->init(), FSW_OK);
  const double s3 = std::sqrt(3.0);
  ASSERT_EQ(f->update(), FSW_OK);
  const double want[3] = {18 / s3, -10 / s3, 10 / s3};
  for (int k = 0; k < 3; k++) EXPECT_NEAR(f->out->h_w_B[k], want[k], kt::tol(1e-13, 1e-5)) << k;
  EXPECT_NEAR(f->out->h_norm, std::sqrt(524.0 / 3.0), kt::tol(1e-13, 1e-5));
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE);
  for (int k = 0; k < 3; k++) EXPECT_EQ(f->out->L_thr_B[k], 0.0);

  f->in->avail[2] = FSW_UNAVAILABLE;
  f->in->Omega[2] = kNaN;
  f->in->t_ns = kDtNs;
  ASSERT_EQ(f->update(), FSW_OK);
  const double want2[3] = {24 / s3, -4 / s3, 4 / s3};
  for (int k = 0; k < 3; k++) EXPECT_NEAR(f->out->h_w_B[k], want2[k], kt::tol(1e-13, 1e-5)) << k;
  // no wheel available: h = 0
  for (int i = 0; i < 4; i++) f->in->avail[i] = FSW_UNAVAILABLE;
  f->in->t_ns = 2 * kDtNs;
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->h_norm, 0.0);
}

// ---- hysteresis and Delta_H -------------------------------------------------

// Verifies: REQ-THRMOM-003
TEST(ThrMomentumHysteresis, NoDumpInsideTheBandDumpAboveNoRestartUntilAboveAgain)
{
  auto f = ready();
  double h[3];
  uint64_t t = 0;
  auto step = [&](double m) {
    scaled_dir(h, m);
    f->set_h(h);
    f->in->t_ns = t;
    t += kDtNs;
    return f->update();
  };
  for (double m : {0.5, 1.0, 1.2, 1.29, 1.299}) {
    ASSERT_EQ(step(m), FSW_OK);
    EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE) << m;
    EXPECT_EQ(norm3(f->out->L_thr_B), 0.0) << m;
  }
  // above h_upper: a dump starts in this cycle
  ASSERT_EQ(step(1.31), FSW_OK);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  EXPECT_NEAR(norm3(f->out->L_thr_B), kLdump, kt::tol(1e-15, 1e-8));
  EXPECT_EQ(f->out->pulses, 1u);
  // Delta_H = 0.31 in 10 pulses (9 of 1/32 = 0.28125 and one of 0.02875):
  // run it to the end with the test's plant
  double hh[3];
  scaled_dir(hh, 1.31);
  for (int k = 0; k < 3; k++) hh[k] += double(f->out->L_thr_B[k]) * kDt;
  std::vector<Cycle> log = simulate(*f, hh, 400, t);
  int end = -1;
  for (size_t c = 0; c < log.size(); c++)
    if (log[c].phase == FSW_THR_MOM_IDLE) {
      end = static_cast<int>(c);
      break;
    }
  ASSERT_GE(end, 0);
  EXPECT_EQ(f->out->dumps, 1u);
  EXPECT_NEAR(norm3(hh), kHlo, kLdump * kTmin);
  // back inside the band: no dump
  t += 400 * kDtNs;
  for (double m : {1.0, 1.1, 1.29, 1.2999}) {
    ASSERT_EQ(step(m), FSW_OK);
    EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE) << m;
    EXPECT_EQ(f->out->dumps, 1u);
  }
  // above again: the next dump
  ASSERT_EQ(step(1.4), FSW_OK);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
}

// h = (2, -1, 2) N*m*s, |h| = 3, h_upper = 2.5, h_lower = 1:
// Delta_H = -h (1 - 1/3) = (-4/3, 2/3, -4/3), |Delta_H| = 2; the first cycle
// commands L_dump along -h/3 and leaves 2 - L_dump dt = 2 - 1/512.
// Verifies: REQ-THRMOM-003
TEST(ThrMomentumDump, DeltaHIsTheExactFormula)
{
  auto f = rwt::make0<Fixture>();
  f->cfg->h_upper = FSW_R(2.5);
  ASSERT_EQ(f->init(), FSW_OK);
  const double h[3] = {2, -1, 2};
  f->set_h(h);
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  const double dH[3] = {-4.0 / 3, 2.0 / 3, -4.0 / 3};
  const double rem = 2.0 - 1.0 / 512;
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(f->out->dH_B[k], dH[k], kt::tol(1e-14, 1e-6)) << k;
    EXPECT_NEAR(f->out->L_thr_B[k], kLdump * dH[k] / 2, kt::tol(1e-16, 1e-8)) << k;
    EXPECT_NEAR(f->out->dH_rem_B[k], rem * dH[k] / 2, kt::tol(1e-14, 1e-6)) << k;
  }
  EXPECT_EQ(f->out->t_dump, 0.0);
  EXPECT_EQ(f->out->dumps, 0u);
}

// The closed loop: |h| = 1.35 along (0.36, 0.48, 0.8), so |Delta_H| = 0.35.
// Pulses of at most 1/32: 0.35 * 32 = 11.2 -> ceil = 12 pulses, eleven of
// 16 full cycles and one of 0.35 - 11/32 = 0.00625 = 3.2 cycles (3 full and
// one at 0.2 L_dump).  Each pulse's last command is followed by 12 coast
// cycles (1.5 s / 0.125 s) of zero torque, so a full pulse starts every 28
// cycles: pulse 12 at cycle 308, its commands at 308..311, coast 312..323,
// IDLE at cycle 324, t_dump = 324 / 8 = 40.5 s.  The wheels end at |h| = 1
// along the same direction (the whole Delta_H is delivered: the last pulse
// is 1.6 minimum pulses long).
// Verifies: REQ-THRMOM-004
TEST(ThrMomentumDump, ClosedLoopDumpPulsesCoastsAndEndsAtTheLowerThreshold)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 1.35);
  const std::vector<Cycle> log = simulate(*f, h, 340);

  // pulses and coasts from the log
  std::vector<int> pulse_cycles, coast_cycles;
  std::vector<double> pulse_impulse;
  int idle_at = -1;
  for (size_t c = 0; c < log.size(); c++) {
    const Cycle& r = log[c];
    ASSERT_EQ(r.s, FSW_OK) << c;
    const double L = norm3(r.L);
    EXPECT_LE(L, kLdump * (1 + kt::tol(1e-12, 1e-6))) << c;
    if (r.phase != FSW_THR_MOM_PULSE) EXPECT_EQ(L, 0.0) << c;
    if (c > 0 && log[c - 1].phase != FSW_THR_MOM_IDLE && r.phase != FSW_THR_MOM_IDLE)
      EXPECT_LE(r.rem, log[c - 1].rem) << c;  // never grows
    if (r.phase == FSW_THR_MOM_PULSE) {
      if (c == 0 || log[c - 1].phase != FSW_THR_MOM_PULSE) {
        pulse_cycles.push_back(0);
        pulse_impulse.push_back(0.0);
      }
      pulse_cycles.back()++;
      pulse_impulse.back() += L * kDt;
    } else if (r.phase == FSW_THR_MOM_COAST) {
      if (log[c - 1].phase != FSW_THR_MOM_COAST) coast_cycles.push_back(0);
      coast_cycles.back()++;
    } else if (idle_at < 0 && c > 0) {
      idle_at = static_cast<int>(c);
    }
  }
  const int n_pulses = static_cast<int>(std::ceil(0.35 / (kLdump * kTpulse)));
  ASSERT_EQ(n_pulses, 12);
  ASSERT_EQ(static_cast<int>(pulse_cycles.size()), n_pulses);
  ASSERT_EQ(static_cast<int>(coast_cycles.size()), n_pulses);
  for (int p = 0; p < n_pulses; p++) {
    EXPECT_EQ(pulse_cycles[p], p < 11 ? 16 : 4) << p;
    EXPECT_LE(pulse_impulse[p], kLdump * kTpulse * (1 + kt::tol(1e-12, 1e-6))) << p;  // no longer than t_pulse_max
    EXPECT_GE(pulse_impulse[p], kLdump * kTmin) << p;                    // never below the minimum
    EXPECT_EQ(coast_cycles[p] * kDt, kTcoast) << p;
  }
  EXPECT_NEAR(pulse_impulse[11], 0.00625, kt::tol(1e-14, 1e-6));
  EXPECT_EQ(idle_at, 324);
  EXPECT_EQ(f->out->dumps, 1u);
  EXPECT_EQ(f->out->pulses, 12u);
  EXPECT_NEAR(f->out->t_dump, 40.5, kt::tol(1e-12, 1e-5));
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE);
  // the wheels: from 1.35 (above h_upper) to h_lower, within one minimum
  // pulse impulse (here to rounding), along the same direction
  EXPECT_GT(norm3(log[0].h), kHup);
  EXPECT_NEAR(norm3(h), kHlo, kLdump * kTmin);
  EXPECT_NEAR(norm3(h), kHlo, kt::tol(1e-12, 2e-5));
  for (int k = 0; k < 3; k++) EXPECT_NEAR(h[k], kHlo * kDir[k], kt::tol(1e-12, 2e-5)) << k;
}

// A remainder below one minimum pulse is left: |Delta_H| = 1/32 + 1/512
// (one full pulse and a half-cycle crumb, below 1/256 = one minimum pulse):
// one pulse of 16 cycles, its coast, IDLE; the wheels end 1/512 above h_lower.
// Verifies: REQ-THRMOM-004
TEST(ThrMomentumDump, RemainderBelowOneMinimumPulseIsNotCommanded)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, kHlo + 1.0 / 32 + 1.0 / 512);
  f->cfg->h_upper = FSW_R(1.03);
  ASSERT_EQ(f->init(), FSW_OK);
  const std::vector<Cycle> log = simulate(*f, h, 40);
  int pulses = 0;
  for (const Cycle& r : log) pulses += r.phase == FSW_THR_MOM_PULSE;
  EXPECT_EQ(pulses, 16);
  EXPECT_EQ(log[16 + 12].phase, FSW_THR_MOM_IDLE);
  EXPECT_EQ(log[16 + 11].phase, FSW_THR_MOM_COAST);
  EXPECT_EQ(f->out->dumps, 1u);
  EXPECT_NEAR(norm3(h), kHlo + 1.0 / 512, kt::tol(1e-12, 2e-6));
}

// t_pulse_max not a multiple of dt: 0.3 s at dt = 0.125 s is two full
// cycles and one at 0.4 L_dump; t_coast = 0: the next pulse starts in the
// cycle after the last command (that command's period is the only gap-free
// hand-over); with t_coast = 0.25 s two COAST cycles come between.
// Verifies: REQ-THRMOM-004
TEST(ThrMomentumDump, PulseEndsWithAReducedCycleAndZeroCoast)
{
  auto f = rwt::make0<Fixture>();
  f->cfg->t_pulse_max = FSW_R(0.3);
  f->cfg->t_min_pulse = FSW_R(0.125);
  f->cfg->t_coast = 0;
  ASSERT_EQ(f->init(), FSW_OK);
  double h[3];
  scaled_dir(h, 1.35);
  const std::vector<Cycle> log = simulate(*f, h, 8);
  const double want[8] = {1, 1, 0.4, 1, 1, 0.4, 1, 1};
  for (int c = 0; c < 8; c++) {
    EXPECT_NEAR(norm3(log[c].L), want[c] * kLdump, kt::tol(1e-15, 1e-8)) << c;
    EXPECT_EQ(log[c].phase, FSW_THR_MOM_PULSE) << c;
  }
  f->cfg->t_coast = FSW_R(0.25);
  ASSERT_EQ(f->init(), FSW_OK);
  scaled_dir(h, 1.35);
  const std::vector<Cycle> log2 = simulate(*f, h, 8);
  const double want2[8] = {1, 1, 0.4, 0, 0, 1, 1, 0.4};
  const int phase2[8] = {1, 1, 1, 2, 2, 1, 1, 1};
  for (int c = 0; c < 8; c++) {
    EXPECT_NEAR(norm3(log2[c].L), want2[c] * kLdump, kt::tol(1e-15, 1e-8)) << c;
    EXPECT_EQ(log2[c].phase, phase2[c]) << c;
  }
}

// One dump removes at most 2e6 full cycles: L_dump = 1e-6 N*m, dt = 1/8 s
// -> cap 0.25 N*m*s (h_upper = 0.1 <= 1e6 cycles = 0.125).  |h| = 1 with
// h_lower = 0.05 would need 0.95: the dump takes 0.25 along -h/|h|.
// Verifies: REQ-THRMOM-004
TEST(ThrMomentumDump, OneDumpIsCappedAtTwoMillionCycles)
{
  auto f = rwt::make0<Fixture>();
  f->cfg->L_dump = FSW_R(1e-6);
  f->cfg->h_upper = FSW_R(0.1);
  f->cfg->h_lower = FSW_R(0.05);
  ASSERT_EQ(f->init(), FSW_OK);
  double h[3];
  scaled_dir(h, 1.0);
  f->set_h(h);
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(f->out->dH_B[k], -0.25 * kDir[k], kt::tol(1e-14, 1e-7)) << k;
  f->cfg->h_upper = FSW_R(0.2);  // beyond 1e6 cycles: refused
  EXPECT_EQ(fsw_thr_momentum_check(f->cfg.get()), FSW_E_CONFIG);
}

// ---- propellant --------------------------------------------------------------

// F_max = (1, 2) N, Isp = 200 s, t_on_prev = (0.05, 0.1) s every call:
// dm = (0.05 + 0.2) / (200 g0) per attributed cycle.  The dump of
// ClosedLoop... (|Delta_H| = 0.35) is active in the calls 0..323; the on-times
// reported by calls 1..324 belong to them: 324 cycles.  Calls before the
// dump (previous call IDLE) and after it count nothing.
// Verifies: REQ-THRMOM-005
TEST(ThrMomentumPropellant, ClosedFormForConstantOnTimes)
{
  auto f = ready();
  f->in->t_on_prev[0] = FSW_R(0.05);
  f->in->t_on_prev[1] = FSW_R(0.1);
  f->in->t_on_prev[2] = FSW_R(5.0);  // beyond num_thr: not read
  const double dm = 0.25 / (200.0 * kG0);
  // three IDLE cycles first (below the band)
  double h[3];
  scaled_dir(h, 0.5);
  (void)simulate(*f, h, 3);
  EXPECT_EQ(f->out->prop_total, 0.0);
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 340, 3 * kDtNs);
  EXPECT_EQ(f->out->dumps, 1u);
  EXPECT_NEAR(f->out->prop_dump, 324 * dm, kt::tol(1e-14, 2e-6));
  EXPECT_NEAR(f->out->prop_total, 324 * dm, kt::tol(1e-14, 2e-6));
  // a second dump: prop_dump starts again, prop_total adds
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 340, 400 * kDtNs);
  EXPECT_EQ(f->out->dumps, 2u);
  EXPECT_NEAR(f->out->prop_dump, 324 * dm, kt::tol(1e-14, 2e-6));
  EXPECT_NEAR(f->out->prop_total, 648 * dm, kt::tol(1e-14, 4e-6));
}

// One cycle by hand: F = (1, 2) N, t_on_prev = (0.02, 0.0) s, Isp = 220 s:
// dm = 0.02 / (220 * 9.80665) = 9.2701e-6 kg.
// Verifies: REQ-THRMOM-005
TEST(ThrMomentumPropellant, OneCycleByHand)
{
  auto f = ready();
  f->cfg->Isp = FSW_R(220.0);
  ASSERT_EQ(f->init(), FSW_OK);
  double h[3];
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 1);  // the dump starts; nothing reported yet
  EXPECT_EQ(f->out->prop_dump, 0.0);
  f->in->t_on_prev[0] = FSW_R(0.02);
  (void)simulate(*f, h, 1, kDtNs);
  EXPECT_NEAR(f->out->prop_dump, 9.2701e-6, 1e-10);
  EXPECT_NEAR(f->out->prop_dump, 0.02 / (220 * kG0), kt::tol(1e-18, 1e-12));
}

// ---- enable, force, rate -------------------------------------------------------

// Verifies: REQ-THRMOM-006
TEST(ThrMomentumModes, DisableAbortsAndBlocksForceStartsInsideTheBand)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 5);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  // disable: aborted in this cycle
  f->in->enable = 0;
  (void)simulate(*f, h, 1, 5 * kDtNs);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE);
  EXPECT_EQ(norm3(f->out->L_thr_B), 0.0);
  EXPECT_EQ(f->out->aborts, 1u);
  EXPECT_EQ(f->out->dumps, 0u);
  EXPECT_NEAR(f->out->t_dump, 5 * kDt, kt::tol(1e-15, 1e-7));
  // still above h_upper, but disabled: no dump, also not forced
  f->in->force_dump = 1;
  (void)simulate(*f, h, 3, 6 * kDtNs);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE);
  // enabled again: a new dump
  f->in->enable = 1;
  f->in->force_dump = 0;
  (void)simulate(*f, h, 1, 9 * kDtNs);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  EXPECT_EQ(f->out->t_dump, 0.0);

  // force inside the band: |h| = 1.2 -> Delta_H = 0.2
  auto g = ready();
  scaled_dir(h, 1.2);
  (void)simulate(*g, h, 1);
  EXPECT_EQ(g->out->phase, FSW_THR_MOM_IDLE);
  g->in->force_dump = 1;
  (void)simulate(*g, h, 1, kDtNs);
  EXPECT_EQ(g->out->phase, FSW_THR_MOM_PULSE);
  EXPECT_NEAR(norm3(g->out->dH_B), 0.2, kt::tol(1e-14, 1e-6));
  // force with less than one minimum pulse above h_lower: ignored
  auto k = ready();
  scaled_dir(h, kHlo + 0.5 / 256);
  k->in->force_dump = 1;
  (void)simulate(*k, h, 2);
  EXPECT_EQ(k->out->phase, FSW_THR_MOM_IDLE);
  EXPECT_EQ(k->out->pulses, 0u);
}

// Verifies: REQ-THRMOM-006
TEST(ThrMomentumModes, RateWarningAfterACommandedCycleOnly)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 0.5);
  f->set_h(h);
  f->in->t_ns = 0;
  ASSERT_EQ(f->update(), FSW_OK);
  f->in->t_ns = 3 * kDtNs;  // irregular but nothing commanded before
  ASSERT_EQ(f->update(), FSW_OK);
  scaled_dir(h, 1.35);
  f->set_h(h);
  f->in->t_ns = 4 * kDtNs;
  ASSERT_EQ(f->update(), FSW_OK);  // the dump starts
  f->in->t_ns = 4 * kDtNs + kDtNs * 102 / 100;
  ASSERT_EQ(f->update(), FSW_W_RATE);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);
  EXPECT_NEAR(norm3(f->out->L_thr_B), kLdump, kt::tol(1e-15, 1e-8));
  EXPECT_EQ(f->st->health.rate, 1u);
  f->in->t_ns += kDtNs * 1005 / 1000;  // within 1 %
  EXPECT_EQ(f->update(), FSW_OK);
}

// ---- errors ----------------------------------------------------------------------

// Verifies: REQ-THRMOM-007
TEST(ThrMomentumBadInput, SafeOutputAndNoStateChange)
{
  struct Row {
    const char* why;
    void (*spoil)(FswThrMomentumIn*);
  };
  static const Row rows[] = {
      {"Omega NaN", [](FswThrMomentumIn* in) { in->Omega[1] = kNaN; }},
      {"Omega Inf", [](FswThrMomentumIn* in) { in->Omega[3] = -kInf; }},
      {"Omega beyond FSW_RW_OMEGA_MAX", [](FswThrMomentumIn* in) { in->Omega[0] = FSW_RW_OMEGA_MAX * FSW_R(1.01); }},
      {"mask 2", [](FswThrMomentumIn* in) { in->avail[2] = 2; }},
      {"t_on_prev negative", [](FswThrMomentumIn* in) { in->t_on_prev[0] = FSW_R(-0.01); }},
      {"t_on_prev NaN", [](FswThrMomentumIn* in) { in->t_on_prev[1] = kNaN; }},
      {"t_on_prev above FSW_THR_MOM_T_ON_MAX", [](FswThrMomentumIn* in) { in->t_on_prev[1] = FSW_THR_MOM_T_ON_MAX * 2; }},
      {"enable 2", [](FswThrMomentumIn* in) { in->enable = 2; }},
      {"force_dump 7", [](FswThrMomentumIn* in) { in->force_dump = 7; }},
  };
  for (const Row& row : rows) {
    auto f = ready();
    double h[3];
    scaled_dir(h, 1.35);
    f->in->t_on_prev[0] = FSW_R(0.01);
    (void)simulate(*f, h, 20);  // mid-dump: 16 pulse cycles, 4 coast
    ASSERT_EQ(f->out->phase, FSW_THR_MOM_COAST);
    const FswThrMomentumOut last = *f->out;
    const auto before = state_copy(*f->st, FswHealth{});
    f->set_h(h);
    f->in->t_ns = 20 * kDtNs;
    row.spoil(f->in.get());
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row.why;
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(f->out->L_thr_B[k], 0.0) << row.why;
      EXPECT_EQ(f->out->h_w_B[k], 0.0) << row.why;
      EXPECT_EQ(f->out->dH_rem_B[k], last.dH_rem_B[k]) << row.why;
      EXPECT_EQ(f->out->dH_B[k], last.dH_B[k]) << row.why;
    }
    EXPECT_EQ(f->out->h_norm, 0.0);
    EXPECT_EQ(f->out->phase, last.phase) << row.why;
    EXPECT_EQ(f->out->pulses, last.pulses);
    EXPECT_EQ(f->out->prop_dump, last.prop_dump);
    EXPECT_EQ(f->out->prop_total, last.prop_total);
    EXPECT_EQ(f->out->t_dump, last.t_dump);
    EXPECT_EQ(f->st->health.bad_input, 1u);
    const auto after = state_copy(*f->st, FswHealth{});
    EXPECT_EQ(0, std::memcmp(before.get(), after.get(), sizeof *before)) << row.why;
  }
  // an unavailable wheel's speed is not read
  auto f = ready();
  f->in->avail[1] = FSW_UNAVAILABLE;
  f->in->Omega[1] = kNaN;
  EXPECT_EQ(f->update(), FSW_OK);
}

// A bad call inside a dump changes nothing: the same sequence with bad
// calls (and time errors) interleaved gives bit-identical outputs.
// Verifies: REQ-THRMOM-007
TEST(ThrMomentumBadInput, InterleavedErrorsDoNotChangeTheDump)
{
  auto a = ready();
  auto b = ready();
  double ha[3], hb[3];
  scaled_dir(ha, 1.35);
  scaled_dir(hb, 1.35);
  a->in->t_on_prev[1] = b->in->t_on_prev[1] = FSW_R(0.03);
  for (int c = 0; c < 200; c++) {
    const uint64_t t = static_cast<uint64_t>(c) * kDtNs;
    if (c % 7 == 3) {
      b->in->t_ns = t;
      b->set_h(hb);
      b->in->Omega[0] = kNaN;
      EXPECT_EQ(b->update(), FSW_E_BAD_INPUT);
      if (c > 0) {
        b->in->t_ns = t - kDtNs;  // not after the previous call
        b->set_h(hb);
        EXPECT_EQ(b->update(), FSW_E_TIME);
        EXPECT_EQ(norm3(b->out->L_thr_B), 0.0);
      }
    }
    a->in->t_ns = b->in->t_ns = t;
    a->set_h(ha);
    b->set_h(hb);
    ASSERT_EQ(a->update(), b->update()) << c;
    expect_out_eq(*a->out, *b->out, "cycle " + std::to_string(c));
    for (int k = 0; k < 3; k++) {
      ha[k] += double(a->out->L_thr_B[k]) * kDt;
      hb[k] += double(b->out->L_thr_B[k]) * kDt;
    }
  }
  EXPECT_GT(b->st->health.bad_input, 0u);
  EXPECT_GT(b->st->health.bad_time, 0u);
}

// Verifies: REQ-THRMOM-007
TEST(ThrMomentumBadInput, SameTimeStampIsATimeError)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 3);
  const auto before = state_copy(*f->st, FswHealth{});
  f->in->t_ns = 2 * kDtNs;
  f->garbage();
  EXPECT_EQ(f->update(), FSW_E_TIME);
  EXPECT_EQ(norm3(f->out->L_thr_B), 0.0);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_PULSE);  // the last accepted call's
  const auto after = state_copy(*f->st, FswHealth{});
  EXPECT_EQ(0, std::memcmp(before.get(), after.get(), sizeof *before));
  EXPECT_EQ(f->st->health.bad_time, 1u);
}

// ---- reset, repeatability ---------------------------------------------------------

// Verifies: REQ-THRMOM-008
TEST(ThrMomentumReset, ForgetsTheDumpAndTheTotals)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 1.35);
  f->in->t_on_prev[0] = FSW_R(0.05);
  (void)simulate(*f, h, 400);
  ASSERT_EQ(f->out->dumps, 1u);
  scaled_dir(h, 1.35);
  (void)simulate(*f, h, 30, 400 * kDtNs);  // mid-dump
  fsw_thr_momentum_reset(f->st.get());
  auto fresh = ready();
  const auto a = state_copy(*f->st, FswHealth{}), b = state_copy(*fresh->st, FswHealth{});
  EXPECT_EQ(0, std::memcmp(a.get(), b.get(), sizeof *a));
  // right after reset a bad input reports zeros, not the values before it
  f->in->avail[0] = 9;
  f->garbage();
  EXPECT_EQ(f->update(), FSW_E_BAD_INPUT);
  expect_out_eq(FswThrMomentumOut{}, *f->out, "bad input right after reset");
  // first good call after reset: any time stamp (here earlier than before)
  f->in->avail[0] = 0;
  f->set_h(h);
  f->in->t_ns = 0;
  EXPECT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->dumps, 0u);
  EXPECT_EQ(f->out->prop_total, 0.0);
}

// Verifies: REQ-THRMOM-008
TEST(ThrMomentumReset, SameSequenceAfterResetGivesIdenticalOutputs)
{
  auto f = ready();
  std::vector<FswThrMomentumOut> first;
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(38);
    double h[3];
    scaled_dir(h, 1.6);
    for (int c = 0; c < 300; c++) {
      f->in->t_ns = static_cast<uint64_t>(c) * kDtNs + static_cast<uint64_t>(r.uniform(0, 1e6));
      f->in->t_on_prev[0] = static_cast<fsw_real>(r.uniform(0, 0.1));
      f->in->t_on_prev[1] = static_cast<fsw_real>(r.uniform(0, 0.1));
      f->in->avail[3] = c % 50 == 7 ? FSW_UNAVAILABLE : FSW_AVAILABLE;
      f->set_h(h);
      (void)f->update();
      for (int k = 0; k < 3; k++) h[k] += double(f->out->L_thr_B[k]) * kDt + 1e-4 * kDir[k];
      if (pass == 0)
        first.push_back(*f->out);
      else
        expect_out_eq(first[static_cast<size_t>(c)], *f->out, "cycle " + std::to_string(c));
    }
    fsw_thr_momentum_reset(f->st.get());
  }
}

// ---- planning helpers ---------------------------------------------------------------

// Band 20 - 5 = 15 N*m*s under 1e-4 N*m: 150 000 s between dump starts.
// 15 N*m*s with 1 N of thrust per N*m (lever 1 m), Isp 220 s:
// m = 15 / (220 * 9.80665) = 6.9527e-3 kg.
// Verifies: REQ-THRMOM-009
TEST(ThrMomentumPlanning, IntervalAndPropellantByHand)
{
  EXPECT_NEAR(fsw_thr_momentum_dump_interval(FSW_R(20.0), FSW_R(5.0), FSW_R(1e-4)), 150000.0,
              kt::tol(1e-9, 2e-2));
  EXPECT_NEAR(fsw_thr_momentum_dump_interval(FSW_R(20.0), FSW_R(5.0), FSW_R(-1e-4)), 150000.0,
              kt::tol(1e-9, 2e-2));
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(20.0), FSW_R(5.0), FSW_R(0.0)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(5.0), FSW_R(5.0), FSW_R(1e-4)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(5.0), FSW_R(-1.0), FSW_R(1e-4)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_dump_interval(kNaN, FSW_R(1.0), FSW_R(1e-4)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(5.0), FSW_R(1.0), kInf), 0.0);
  const fsw_real tiny = std::numeric_limits<fsw_real>::denorm_min();
  EXPECT_EQ(fsw_thr_momentum_dump_interval(std::numeric_limits<fsw_real>::max(), FSW_R(0.0), tiny), 0.0);

  EXPECT_NEAR(fsw_thr_momentum_prop_per_dump(FSW_R(15.0), FSW_R(1.0), FSW_R(220.0)), 15.0 / (220 * kG0),
              kt::tol(1e-17, 1e-9));
  EXPECT_NEAR(fsw_thr_momentum_prop_per_dump(FSW_R(15.0), FSW_R(1.0), FSW_R(220.0)), 6.9527e-3, 1e-7);
  EXPECT_NEAR(fsw_thr_momentum_prop_per_dump(FSW_R(-15.0), FSW_R(0.5), FSW_R(220.0)), 30.0 / (220 * kG0),
              kt::tol(1e-17, 1e-9));
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(15.0), FSW_R(0.0), FSW_R(220.0)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(15.0), FSW_R(1.0), FSW_R(-1.0)), 0.0);
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(kNaN, FSW_R(1.0), FSW_R(220.0)), 0.0);
}

// The interval helper against the module: a constant body-fixed disturbance
// of 2e-4 N*m along the wheels' momentum; after the first dump the dump
// starts are (h_upper - h_lower)/|L_dist| = 0.3 / 2e-4 = 1500 s apart
// (12 000 cycles), to within one cycle of threshold crossing: each dump
// removes 0.3 (+ at most Ld dt), and 0.3 = 9 pulses of 1/32 and one of
// 0.01875 (more than a minimum pulse), so nothing is left behind.
// Verifies: REQ-THRMOM-009
TEST(ThrMomentumPlanning, SimulatedDumpIntervalMatchesTheHelper)
{
  auto f = ready();
  double h[3];
  scaled_dir(h, 1.2);
  const double Ld = 2e-4;
  std::vector<long> starts;
  int prev_phase = FSW_THR_MOM_IDLE;
  for (long c = 0; c < 60000; c++) {
    f->in->t_ns = static_cast<uint64_t>(c) * kDtNs;
    f->set_h(h);
    ASSERT_EQ(f->update(), FSW_OK);
    if (prev_phase == FSW_THR_MOM_IDLE && f->out->phase == FSW_THR_MOM_PULSE) starts.push_back(c);
    prev_phase = f->out->phase;
    for (int k = 0; k < 3; k++) h[k] += (double(f->out->L_thr_B[k]) + Ld * kDir[k]) * kDt;
  }
  ASSERT_EQ(starts.size(), 5u);  // near 500, 2000, 3500, 5000, 6500 s
  const double T = double(fsw_thr_momentum_dump_interval(f->cfg->h_upper, f->cfg->h_lower, FSW_R(2e-4)));
  EXPECT_NEAR(T, 1500.0, kt::tol(1e-9, 1e-3));
  for (size_t i = 1; i < starts.size(); i++) {
    const double interval = double(starts[i] - starts[i - 1]) * kDt;
    EXPECT_NEAR(interval, T, 2 * kDt) << i;
  }
}

// ---- NULL arguments --------------------------------------------------------------------

// Verifies: REQ-GEN-007
TEST(ThrMomentumNullArgs, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("thr_momentum", fsw_thr_momentum_check, fsw_thr_momentum_init, fsw_thr_momentum_reset,
                       fsw_thr_momentum_update);
}

// MC/DC (docs/coverage.md): an upper threshold of exactly 0 is inside
// [0, FSW_THR_MOM_H_MAX] but not > 0, and is refused by that condition alone
// (with h_lower 0 too, so that no later check could be what refuses it).
// Verifies: REQ-THRMOM-001
TEST(ThrMomentumConfig, McdcUpperThresholdZeroIsRefused)
{
  Fixture ok;
  EXPECT_EQ(fsw_thr_momentum_check(ok.cfg.get()), FSW_OK);
  Fixture f;
  f.cfg->h_upper = FSW_R(0.0);
  f.cfg->h_lower = FSW_R(0.0);
  EXPECT_EQ(fsw_thr_momentum_check(f.cfg.get()), FSW_E_CONFIG);
  EXPECT_EQ(fsw_thr_momentum_init(f.st.get(), f.cfg.get()), FSW_E_CONFIG);
}

// MC/DC (docs/coverage.md): a forced dump at or below h_lower has nothing to
// dump: the force alone does not trigger (the trigger's third condition).
// Verifies: REQ-THRMOM-006
TEST(ThrMomentumModes, McdcForcedDumpBelowTheLowerThresholdDoesNothing)
{
  double h[3];
  auto f = ready();
  scaled_dir(h, kHlo * 0.5);
  f->in->force_dump = 1;
  (void)simulate(*f, h, 3);
  EXPECT_EQ(f->out->phase, FSW_THR_MOM_IDLE);
  EXPECT_EQ(f->out->pulses, 0u);
  EXPECT_EQ(f->out->dumps, 0u);
  EXPECT_EQ(norm3(f->out->L_thr_B), 0.0);
}
