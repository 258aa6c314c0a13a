// KESTREL_ACS core (apps/cfs/kestrel_acs/fsw/src/kestrel_acs_core.c), the
// logic of the cFS application, without cFS.  The configuration is the
// committed default table (scenario S1's image, compiled from
// fsw/tables/kestrel_acs_cfg.c with a stand-in cfe_tbl_filedef.h).
//   table:    S1 accepted; bad fields refused with the field named, counted,
//             the configuration in force kept; truncated, corrupted, foreign
//             and oversized images refused;
//   commands: each command code applied at the next cycle, checked against
//             fsw_acs_cycle run here on a command built by hand; wrong
//             lengths, unknown codes and out-of-range values refused with
//             nothing applied; counters (u8, wrapping) and reset;
//   link:     a sensor packet (fsw_link_encode_sensor) runs one cycle whose
//             actuator and health packets equal those of fsw_acs_cycle and
//             the encoders called here on the same inputs; ICD command
//             packets applied from the next cycle; damaged packets refused
//             and counted with one event per run; cycle-error events once
//             per run; mode-change events;
//   housekeeping: the 24 bytes at the offsets of docs/cfs.md, by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fsw/fsw_acs.h"
#include "fsw/fsw_link.h"
#include "kestrel_acs_core.h"

extern "C" {
extern KestrelAcsConfigTable KESTREL_ACS_Config; // fsw/tables/kestrel_acs_cfg.c
}

namespace {

using Bytes = std::vector<uint8_t>;

std::unique_ptr<KestrelAcsCore> make_core()
{
  auto c = std::make_unique<KestrelAcsCore>();
  kestrel_acs_core_init(c.get());
  return c;
}

std::unique_ptr<FswAcsConfig> s1_config()
{
  auto cfg = std::make_unique<FswAcsConfig>();
  EXPECT_EQ(fsw_link_config_decode(KESTREL_ACS_Config.image, KESTREL_ACS_Config.image_length, cfg.get(), nullptr),
            FSW_OK);
  return cfg;
}

std::unique_ptr<KestrelAcsConfigTable> table_of(const FswAcsConfig& cfg)
{
  auto t = std::make_unique<KestrelAcsConfigTable>();
  std::memset(t.get(), 0, sizeof *t);
  size_t len = 0;
  EXPECT_EQ(fsw_link_config_encode(&cfg, t->image, sizeof t->image, &len, nullptr), FSW_OK);
  t->image_length = static_cast<uint32_t>(len);
  return t;
}

bool has_event(const KestrelAcsCore& c, uint16_t id)
{
  for (int i = 0; i < c.num_events; ++i)
    if (c.events[i].id == id) return true;
  return false;
}

const KestrelAcsEvent* event(const KestrelAcsCore& c, uint16_t id)
{
  for (int i = 0; i < c.num_events; ++i)
    if (c.events[i].id == id) return &c.events[i];
  return nullptr;
}

int n_css(const FswAcsConfig& cfg) { return cfg.css.num_css; }
int n_rw(const FswAcsConfig& cfg) { return cfg.has_wheels != 0 ? cfg.rw_map.num_rw : 0; }
int n_thr(const FswAcsConfig& cfg) { return cfg.has_thrusters != 0 ? cfg.thr_map.num_thr : 0; }
int n_mtq(const FswAcsConfig& cfg) { return cfg.has_mtq != 0 ? cfg.mtq_map.num_mtq : 0; }

// A plausible sensor sample for S1 at cycle k: a small attitude and rate,
// the Sun near +z of the body, wheels spinning slowly.
FswAcsSensorMsg sample(const FswAcsConfig& cfg, int k)
{
  FswAcsSensorMsg m;
  std::memset(&m, 0, sizeof m);
  m.t_ns = 100000000ull * static_cast<uint64_t>(k + 1); // 10 Hz
  m.sigma_BN[0] = static_cast<fsw_real>(0.05);
  m.sigma_BN[1] = static_cast<fsw_real>(-0.02);
  m.sigma_BN[2] = static_cast<fsw_real>(0.01 * k);
  m.att_valid = 1;
  m.omega_BN_B[0] = static_cast<fsw_real>(0.001);
  m.omega_BN_B[1] = static_cast<fsw_real>(-0.002);
  m.omega_BN_B[2] = static_cast<fsw_real>(0.0005);
  const double s[3] = {0.3, -0.2, 0.93};
  for (int i = 0; i < n_css(cfg); ++i) {
    double d = 0;
    for (int j = 0; j < 3; ++j) d += s[j] * static_cast<double>(cfg.css.n_hat_B[i][j]);
    m.css[i] = static_cast<fsw_real>(d > 0 ? d : 0.0);
  }
  for (int i = 0; i < n_rw(cfg); ++i) m.Omega[i] = static_cast<fsw_real>(10.0 + i);
  return m;
}

Bytes sensor_packet(const FswAcsConfig& cfg, const FswAcsSensorMsg& m, uint16_t seq)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  EXPECT_EQ(fsw_link_encode_sensor(&m, static_cast<uint8_t>(n_rw(cfg)), static_cast<uint8_t>(n_css(cfg)), seq,
                                   b.data(), b.size(), &len, nullptr),
            FSW_OK);
  b.resize(len);
  return b;
}

// The reference: fsw_acs_cycle and the encoders called here.
struct Reference {
  std::unique_ptr<FswAcsState> st = std::make_unique<FswAcsState>();
  FswAcsActuatorMsg act{};
  FswAcsHealthMsg hlth{};
  uint16_t seq = 0;
  explicit Reference(const FswAcsConfig& cfg) { EXPECT_EQ(fsw_acs_init(st.get(), &cfg, nullptr), FSW_OK); }
  FswStatus cycle(const FswAcsConfig& cfg, const FswAcsSensorMsg& m, const FswAcsCmdMsg* cmd, Bytes* act_pkt,
                  Bytes* hlth_pkt)
  {
    const FswStatus s = fsw_acs_cycle(st.get(), &cfg, &m, cmd, &act, &hlth);
    act_pkt->assign(FSW_LINK_MAX_PACKET, 0);
    hlth_pkt->assign(FSW_LINK_MAX_PACKET, 0);
    size_t la = 0, lh = 0;
    EXPECT_EQ(fsw_link_encode_actuator(&act, static_cast<uint8_t>(n_rw(cfg)), static_cast<uint8_t>(n_thr(cfg)),
                                       static_cast<uint8_t>(n_mtq(cfg)), m.t_ns, seq, act_pkt->data(),
                                       act_pkt->size(), &la, nullptr),
              FSW_OK);
    EXPECT_EQ(fsw_link_encode_health(&hlth, m.t_ns, seq, hlth_pkt->data(), hlth_pkt->size(), &lh, nullptr), FSW_OK);
    act_pkt->resize(la);
    hlth_pkt->resize(lh);
    ++seq;
    return s;
  }
};

Bytes core_act(const KestrelAcsCore& c) { return Bytes(c.act_pkt, c.act_pkt + c.act_len); }
Bytes core_hlth(const KestrelAcsCore& c) { return Bytes(c.hlth_pkt, c.hlth_pkt + c.hlth_len); }

void put_f64(uint8_t* p, double d)
{
  uint64_t u;
  std::memcpy(&u, &d, 8);
  for (int i = 0; i < 8; ++i) p[i] = static_cast<uint8_t>(u >> (56 - 8 * i));
}

uint32_t be32(const uint8_t* p)
{
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// ---- table ------------------------------------------------------------------

TEST(KestrelAcsTable, DefaultS1ImageAccepted)
{
  auto core = make_core();
  auto scratch = std::make_unique<FswAcsConfig>();
  const char* field = "x";
  ASSERT_EQ(KESTREL_ACS_Config.image_length, fsw_link_config_size());
  EXPECT_LE(fsw_link_config_size(), size_t{KESTREL_ACS_CONFIG_IMAGE_MAX});
  EXPECT_EQ(kestrel_acs_core_table_check(&KESTREL_ACS_Config, scratch.get(), &field), FSW_OK);
  EXPECT_EQ(field, nullptr);
  EXPECT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  EXPECT_EQ(core->config_loaded, 1u);
  EXPECT_EQ(core->table_rejects, 0u);
  const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_TBL_OK);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->b, static_cast<int32_t>(fsw_link_config_size()));
  auto cfg = s1_config();
  EXPECT_EQ(core->num_rw, n_rw(*cfg));
  EXPECT_EQ(core->num_thr, n_thr(*cfg));
  EXPECT_EQ(core->acs.mode, cfg->initial_mode);
}

struct BadField {
  const char* field;
  void (*mutate)(FswAcsConfig&);
};

TEST(KestrelAcsTable, BadFieldsRefusedWithTheFieldNamed)
{
  const BadField cases[] = {
      {"initial_mode", [](FswAcsConfig& c) { c.initial_mode = 9; }},
      {"has_wheels", [](FswAcsConfig& c) { c.has_wheels = 2; }},
      {"mrp_fb", [](FswAcsConfig& c) { c.mrp_fb.K = static_cast<fsw_real>(-1.0); }},
      {"use_lpf", [](FswAcsConfig& c) { c.use_lpf = 3; }},
      {"sunsafe", [](FswAcsConfig& c) { c.sunsafe.s_cmd_B[0] = c.sunsafe.s_cmd_B[1] = c.sunsafe.s_cmd_B[2] = 0; }},
  };
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  auto before = std::make_unique<FswAcsConfig>(core->cfg);
  auto scratch = std::make_unique<FswAcsConfig>();
  uint32_t n = 0;
  for (const BadField& bf : cases) {
    SCOPED_TRACE(bf.field);
    auto cfg = s1_config();
    bf.mutate(*cfg);
    auto t = table_of(*cfg);
    const char* field = nullptr;
    EXPECT_EQ(kestrel_acs_core_table_check(t.get(), scratch.get(), &field), FSW_E_CONFIG);
    ASSERT_NE(field, nullptr);
    EXPECT_STREQ(field, bf.field);
    kestrel_acs_core_clear_events(core.get());
    EXPECT_EQ(kestrel_acs_core_configure(core.get(), t.get()), FSW_E_CONFIG);
    ++n;
    EXPECT_EQ(core->table_rejects, n);
    const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_TBL_BAD);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->type, KESTREL_ACS_EV_ERROR);
    EXPECT_STREQ(e->text, bf.field);
    EXPECT_EQ(e->a, FSW_E_CONFIG);
    // the configuration in force is kept
    EXPECT_EQ(core->config_loaded, 1u);
    EXPECT_EQ(std::memcmp(&core->cfg, before.get(), sizeof core->cfg), 0);
  }
}

TEST(KestrelAcsTable, DamagedImagesRefused)
{
  auto scratch = std::make_unique<FswAcsConfig>();
  const size_t size = fsw_link_config_size();
  struct Case {
    const char* field;
    void (*mutate)(KestrelAcsConfigTable&, size_t);
  };
  const Case cases[] = {
      {"image: short", [](KestrelAcsConfigTable& t, size_t n) { t.image_length = static_cast<uint32_t>(n - 1); }},
      {"image: short", [](KestrelAcsConfigTable& t, size_t) { t.image_length = 100; }},
      {"image: length", [](KestrelAcsConfigTable& t, size_t n) { t.image_length = static_cast<uint32_t>(n + 1); }},
      {"image: CRC", [](KestrelAcsConfigTable& t, size_t n) { t.image[n / 2] ^= 0x10u; }},
      {"image: CRC", [](KestrelAcsConfigTable& t, size_t n) { t.image[n - 1] ^= 0x01u; }},
      {"image: header", [](KestrelAcsConfigTable& t, size_t) { t.image[0] = 'X'; }},
      {"image: header", [](KestrelAcsConfigTable& t, size_t) { t.image[12] ^= 0xFFu; }}, // capacity FSW_MAX_RW
      {"image_length", [](KestrelAcsConfigTable& t, size_t) { t.image_length = 0; }},
      {"image_length", [](KestrelAcsConfigTable& t, size_t) { t.image_length = KESTREL_ACS_CONFIG_IMAGE_MAX + 1; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.field);
    auto t = std::make_unique<KestrelAcsConfigTable>(KESTREL_ACS_Config);
    c.mutate(*t, size);
    const char* field = nullptr;
    const FswStatus s = kestrel_acs_core_table_check(t.get(), scratch.get(), &field);
    EXPECT_TRUE(fsw_status_is_error(s));
    ASSERT_NE(field, nullptr);
    EXPECT_STREQ(field, c.field);
    auto core = make_core();
    EXPECT_EQ(kestrel_acs_core_configure(core.get(), t.get()), s);
    EXPECT_EQ(core->config_loaded, 0u);
    EXPECT_EQ(core->table_rejects, 1u);
  }
}

TEST(KestrelAcsTable, NewTableReinitialisesTheFsw)
{
  auto core = make_core();
  auto cfg = s1_config();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  for (int k = 0; k < 3; ++k) {
    Bytes p = sensor_packet(*cfg, sample(*cfg, k), static_cast<uint16_t>(k));
    ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  }
  EXPECT_EQ(core->acs.cycles, 3u);
  // a changed gain: a new table; the FSW state starts afresh (an earlier t_ns is accepted again)
  cfg->mrp_fb.K = static_cast<fsw_real>(2.0 * static_cast<double>(cfg->mrp_fb.K));
  auto t = table_of(*cfg);
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), t.get()), FSW_OK);
  EXPECT_EQ(core->acs.cycles, 0u);
  EXPECT_EQ(static_cast<double>(core->cfg.mrp_fb.K), static_cast<double>(cfg->mrp_fb.K));
  Bytes p = sensor_packet(*cfg, sample(*cfg, 0), 3);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  EXPECT_FALSE(fsw_status_is_error(core->last_status)) << core->last_status;
  EXPECT_EQ(core->acs.cycles, 1u);
}

// ---- ground commands -------------------------------------------------------

struct CmdCase {
  uint8_t cc;
  Bytes payload;
  FswAcsCmdMsg expect; // the pending command the core must pass to fsw_acs_cycle
  Bytes mode_first{};  // a SET_MODE payload sent before (empty: none)
};

// One command at the next cycle: the core's packets equal fsw_acs_cycle's
// with the command built here by hand, and differ from those without it.
void check_applied_next_cycle(const CmdCase& cc)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Reference ref(*cfg), plain(*cfg);
  Bytes ra, rh, pa, ph;
  // one cycle without the command
  FswAcsSensorMsg m0 = sample(*cfg, 0);
  Bytes p0 = sensor_packet(*cfg, m0, 0);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p0.data(), p0.size()), 2);
  ref.cycle(*cfg, m0, nullptr, &ra, &rh);
  plain.cycle(*cfg, m0, nullptr, &pa, &ph);
  EXPECT_EQ(core_act(*core), ra);
  // the command
  kestrel_acs_core_clear_events(core.get());
  uint8_t n = 1;
  if (!cc.mode_first.empty()) {
    EXPECT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_SET_MODE_CC, cc.mode_first.data(), 4), 1);
    ++n;
  }
  EXPECT_EQ(kestrel_acs_core_ground_cmd(core.get(), cc.cc, cc.payload.data(), cc.payload.size()), 1);
  EXPECT_EQ(core->command_count, n);
  EXPECT_EQ(core->command_error_count, 0u);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_CMD_ACCEPTED));
  // the comparison run: without the set command (the same mode request)
  FswAcsCmdMsg plain_cmd = cc.expect;
  plain_cmd.set_ref = plain_cmd.set_gains = plain_cmd.set_policy = 0;
  const bool is_set = cc.cc == KESTREL_ACS_SET_REFERENCE_CC || cc.cc == KESTREL_ACS_SET_GAINS_CC;
  // the next cycles
  for (int k = 1; k < 4; ++k) {
    FswAcsSensorMsg m = sample(*cfg, k);
    Bytes p = sensor_packet(*cfg, m, static_cast<uint16_t>(k));
    ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
    EXPECT_EQ(ref.cycle(*cfg, m, &cc.expect, &ra, &rh), core->last_status);
    plain.cycle(*cfg, m, is_set ? &plain_cmd : nullptr, &pa, &ph);
    EXPECT_EQ(core_act(*core), ra) << "cycle " << k;
    EXPECT_EQ(core_hlth(*core), rh) << "cycle " << k;
    if (k == 1) EXPECT_TRUE(core_act(*core) != pa || core_hlth(*core) != ph) << "the command changed nothing";
  }
}

FswAcsCmdMsg base_cmd(const FswAcsConfig& cfg)
{
  FswAcsCmdMsg m;
  std::memset(&m, 0, sizeof m);
  m.mode = cfg.initial_mode;
  m.actuation = cfg.initial_actuation;
  m.policy = cfg.initial_policy;
  return m;
}

TEST(KestrelAcsCommands, SetModeAppliedAtTheNextCycle)
{
  auto cfg = s1_config();
  ASSERT_EQ(cfg->initial_mode, FSW_ACS_MODE_SUN_SAFE);
  CmdCase c{KESTREL_ACS_SET_MODE_CC, {FSW_ACS_MODE_INERTIAL, 0, 0, 0}, base_cmd(*cfg)};
  c.expect.mode = FSW_ACS_MODE_INERTIAL;
  check_applied_next_cycle(c);
  // and the mode-change event names both modes
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_SET_MODE_CC, c.payload.data(), 4), 1);
  Bytes p = sensor_packet(*cfg, sample(*cfg, 0), 0);
  kestrel_acs_core_clear_events(core.get());
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_MODE);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->a, FSW_ACS_MODE_SUN_SAFE);
  EXPECT_EQ(e->b, FSW_ACS_MODE_INERTIAL);
  // no event while the mode stays
  Bytes p2 = sensor_packet(*cfg, sample(*cfg, 1), 1);
  kestrel_acs_core_clear_events(core.get());
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p2.data(), p2.size()), 2);
  EXPECT_FALSE(has_event(*core, KESTREL_ACS_EID_MODE));
  EXPECT_EQ(core->acs.mode, FSW_ACS_MODE_INERTIAL);
}

TEST(KestrelAcsCommands, SetReferenceAppliedAtTheNextCycle)
{
  auto cfg = s1_config();
  CmdCase c{KESTREL_ACS_SET_REFERENCE_CC, Bytes(24), base_cmd(*cfg)};
  const double s[3] = {0.1, -0.2, 0.05};
  for (int i = 0; i < 3; ++i) {
    put_f64(&c.payload[static_cast<size_t>(8 * i)], s[i]);
    c.expect.sigma_R0N[i] = static_cast<fsw_real>(s[i]);
  }
  c.expect.set_ref = 1;
  // the reference acts in INERTIAL: command that mode too
  c.expect.mode = FSW_ACS_MODE_INERTIAL;
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  const uint8_t mode[4] = {FSW_ACS_MODE_INERTIAL, 0, 0, 0};
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_SET_MODE_CC, mode, 4), 1);
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), c.cc, c.payload.data(), 24), 1);
  EXPECT_EQ(std::memcmp(&core->cmd, &c.expect, sizeof c.expect), 0);
  Bytes p = sensor_packet(*cfg, sample(*cfg, 0), 0);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(static_cast<double>(core->acs.inertial_cfg.sigma_R0N[i]),
                                        static_cast<double>(static_cast<fsw_real>(s[i])));
  // against the reference, over cycles (in INERTIAL, where the reference acts)
  c.mode_first = {FSW_ACS_MODE_INERTIAL, 0, 0, 0};
  check_applied_next_cycle(c);
}

TEST(KestrelAcsCommands, SetGainsAppliedAtTheNextCycle)
{
  auto cfg = s1_config();
  CmdCase c{KESTREL_ACS_SET_GAINS_CC, Bytes(16), base_cmd(*cfg)};
  const double K = 2.5 * static_cast<double>(cfg->mrp_fb.K), P = 0.5 * static_cast<double>(cfg->mrp_fb.P);
  put_f64(&c.payload[0], K);
  put_f64(&c.payload[8], P);
  c.expect.set_gains = 1;
  c.expect.K = static_cast<fsw_real>(K);
  c.expect.P = static_cast<fsw_real>(P);
  check_applied_next_cycle(c);
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), c.cc, c.payload.data(), 16), 1);
  EXPECT_EQ(static_cast<double>(core->acs.mrp_cfg.K), static_cast<double>(cfg->mrp_fb.K)); // not before the cycle
  Bytes p = sensor_packet(*cfg, sample(*cfg, 0), 0);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  EXPECT_EQ(static_cast<double>(core->acs.mrp_cfg.K), static_cast<double>(static_cast<fsw_real>(K)));
  EXPECT_EQ(static_cast<double>(core->acs.mrp_cfg.P), static_cast<double>(static_cast<fsw_real>(P)));
}

TEST(KestrelAcsCommands, SetActuationAndPolicyPassedToTheCycle)
{
  auto cfg = s1_config();
  // actuation: the other chain if configured (S1 flies wheels; thrusters only if it has them)
  const int other = cfg->initial_actuation == FSW_ACS_ACT_WHEELS ? FSW_ACS_ACT_THRUSTERS : FSW_ACS_ACT_WHEELS;
  CmdCase a{KESTREL_ACS_SET_ACTUATION_CC, {static_cast<uint8_t>(other), 0, 0, 0}, base_cmd(*cfg)};
  a.expect.actuation = other;
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), a.cc, a.payload.data(), 4), 1);
  EXPECT_EQ(std::memcmp(&core->cmd, &a.expect, sizeof a.expect), 0);
  // policy NONE (always available)
  CmdCase p{KESTREL_ACS_SET_MOMENTUM_POLICY_CC, {FSW_ACS_MOM_NONE, 0, 0, 0}, base_cmd(*cfg)};
  p.expect.set_policy = 1;
  p.expect.policy = FSW_ACS_MOM_NONE;
  auto core2 = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core2.get(), &KESTREL_ACS_Config), FSW_OK);
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core2.get(), p.cc, p.payload.data(), 4), 1);
  EXPECT_EQ(std::memcmp(&core2->cmd, &p.expect, sizeof p.expect), 0);
  // both against fsw_acs_cycle over cycles (same packets, same statuses)
  for (const CmdCase* c : {&a, &p}) {
    auto k = make_core();
    ASSERT_EQ(kestrel_acs_core_configure(k.get(), &KESTREL_ACS_Config), FSW_OK);
    Reference ref(*cfg);
    Bytes ra, rh;
    ASSERT_EQ(kestrel_acs_core_ground_cmd(k.get(), c->cc, c->payload.data(), 4), 1);
    for (int j = 0; j < 3; ++j) {
      FswAcsSensorMsg m = sample(*cfg, j);
      Bytes pk = sensor_packet(*cfg, m, static_cast<uint16_t>(j));
      ASSERT_EQ(kestrel_acs_core_link(k.get(), 0, pk.data(), pk.size()), 2);
      EXPECT_EQ(ref.cycle(*cfg, m, &c->expect, &ra, &rh), k->last_status);
      EXPECT_EQ(core_act(*k), ra);
      EXPECT_EQ(core_hlth(*k), rh);
    }
  }
}

TEST(KestrelAcsCommands, NoopAndResetCounters)
{
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_NOOP_CC, nullptr, 0), 1);
  EXPECT_EQ(core->command_count, 1u);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_NOOP));
  EXPECT_EQ(core->have_cmd, 0u); // a NOOP leaves the pending command alone
  // u8 counters wrap as cFS counters do: 256 NOOPs in all -> 0
  for (int i = 1; i < 256; ++i) kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_NOOP_CC, nullptr, 0);
  EXPECT_EQ(core->command_count, 0u);
  kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_NOOP_CC, nullptr, 0);
  kestrel_acs_core_ground_cmd(core.get(), 99, nullptr, 0);
  core->cycles = 5;
  core->cycle_errors = 2;
  core->link_rejected = 3;
  core->table_rejects = 4;
  kestrel_acs_core_clear_events(core.get());
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_RESET_COUNTERS_CC, nullptr, 0), 1);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_RESET));
  EXPECT_EQ(core->command_count, 0u);
  EXPECT_EQ(core->command_error_count, 0u);
  EXPECT_EQ(core->cycles, 0u);
  EXPECT_EQ(core->cycle_errors, 0u);
  EXPECT_EQ(core->link_rejected, 0u);
  EXPECT_EQ(core->table_rejects, 0u);
}

TEST(KestrelAcsCommands, WrongLengthsRefusedNothingApplied)
{
  const size_t lens[KESTREL_ACS_NUM_CC] = {0, 0, 4, 4, 24, 16, 4};
  Bytes big(64, 1);
  for (uint8_t cc = 0; cc < KESTREL_ACS_NUM_CC; ++cc) {
    EXPECT_EQ(kestrel_acs_core_cmd_len(cc), static_cast<int>(lens[cc]));
    std::vector<size_t> wrong = {lens[cc] + 1, lens[cc] + 8};
    if (lens[cc] > 0) {
      wrong.push_back(lens[cc] - 1);
      wrong.push_back(0);
    }
    for (size_t len : wrong) {
      SCOPED_TRACE(std::to_string(cc) + "/" + std::to_string(len));
      auto core = make_core();
      ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
      core->cycles = 7;
      kestrel_acs_core_clear_events(core.get());
      EXPECT_EQ(kestrel_acs_core_ground_cmd(core.get(), cc, big.data(), len), 0);
      EXPECT_EQ(core->command_count, 0u);
      EXPECT_EQ(core->command_error_count, 1u);
      EXPECT_EQ(core->have_cmd, 0u);
      EXPECT_EQ(core->cycles, 7u); // RESET_COUNTERS with a wrong length resets nothing
      const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_CMD_LEN);
      ASSERT_NE(e, nullptr);
      EXPECT_EQ(e->type, KESTREL_ACS_EV_ERROR);
      EXPECT_EQ(e->a, cc);
      EXPECT_EQ(e->b, static_cast<int32_t>(len));
    }
  }
  EXPECT_EQ(kestrel_acs_core_cmd_len(7), -1);
}

TEST(KestrelAcsCommands, UnknownCodesAndBadValuesRefused)
{
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  for (uint8_t cc : {uint8_t{7}, uint8_t{8}, uint8_t{127}, uint8_t{255}}) {
    kestrel_acs_core_clear_events(core.get());
    EXPECT_EQ(kestrel_acs_core_ground_cmd(core.get(), cc, nullptr, 0), 0);
    const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_CMD_CC);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->a, cc);
  }
  EXPECT_EQ(core->command_error_count, 4u);
  struct V {
    uint8_t cc;
    Bytes payload;
    const char* field;
  };
  Bytes nan_ref(24), inf_gain(16), neg_gain(16), zero_p(16);
  put_f64(&nan_ref[8], std::numeric_limits<double>::quiet_NaN());
  put_f64(&inf_gain[0], std::numeric_limits<double>::infinity());
  put_f64(&inf_gain[8], 1.0);
  put_f64(&neg_gain[0], -1.0);
  put_f64(&neg_gain[8], 1.0);
  put_f64(&zero_p[0], 1.0);
  put_f64(&zero_p[8], 0.0);
  const V bad[] = {{KESTREL_ACS_SET_MODE_CC, {4, 0, 0, 0}, "mode"},
                   {KESTREL_ACS_SET_ACTUATION_CC, {2, 0, 0, 0}, "actuation"},
                   {KESTREL_ACS_SET_MOMENTUM_POLICY_CC, {3, 0, 0, 0}, "policy"},
                   {KESTREL_ACS_SET_REFERENCE_CC, nan_ref, "sigma_R0N"},
                   {KESTREL_ACS_SET_GAINS_CC, inf_gain, "K"},
                   {KESTREL_ACS_SET_GAINS_CC, neg_gain, "K"},
                   {KESTREL_ACS_SET_GAINS_CC, zero_p, "P"}};
  uint8_t errors = core->command_error_count;
  for (const V& v : bad) {
    SCOPED_TRACE(v.field);
    kestrel_acs_core_clear_events(core.get());
    EXPECT_EQ(kestrel_acs_core_ground_cmd(core.get(), v.cc, v.payload.data(), v.payload.size()), 0);
    EXPECT_EQ(core->command_error_count, ++errors);
    EXPECT_EQ(core->have_cmd, 0u);
    const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_CMD_VALUE);
    ASSERT_NE(e, nullptr);
    EXPECT_STREQ(e->text, v.field);
  }
  EXPECT_EQ(core->command_count, 0u);
}

// ---- link ---------------------------------------------------------------------

TEST(KestrelAcsLink, SensorPacketRunsTheCycleFswAcsRunsDirectly)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Reference ref(*cfg);
  Bytes ra, rh;
  for (int k = 0; k < 20; ++k) {
    FswAcsSensorMsg m = sample(*cfg, k);
    Bytes p = sensor_packet(*cfg, m, static_cast<uint16_t>(k));
    ASSERT_EQ(kestrel_acs_core_link(core.get(), KESTREL_ACS_LINK_CC, p.data(), p.size()), 2);
    const FswStatus s = ref.cycle(*cfg, m, nullptr, &ra, &rh);
    EXPECT_EQ(core->last_status, s);
    EXPECT_EQ(core_act(*core), ra) << "cycle " << k;
    EXPECT_EQ(core_hlth(*core), rh) << "cycle " << k;
  }
  EXPECT_EQ(core->cycles, 20u);
  EXPECT_GT(ref.st->cycles, 0u);
  // the actuator packet is the ICD's: APID 0x181, telemetry, t_ns of the sensor packet
  FswLinkPacket pk;
  ASSERT_EQ(fsw_link_parse(core->act_pkt, core->act_len, &pk, nullptr), FSW_OK);
  EXPECT_EQ(pk.apid, FSW_LINK_APID_ACTUATOR);
  EXPECT_EQ(pk.t_ns, sample(*cfg, 19).t_ns);
  EXPECT_EQ(pk.seq, 19u);
}

TEST(KestrelAcsLink, RetransmissionAnsweredAgainWithoutACycle)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Reference ref(*cfg);
  Bytes ra, rh;
  for (int k = 0; k < 4; ++k) {
    FswAcsSensorMsg m = sample(*cfg, k);
    Bytes p = sensor_packet(*cfg, m, static_cast<uint16_t>(k));
    ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
    ref.cycle(*cfg, m, nullptr, &ra, &rh);
    if (k == 1) {
      // the same packet again (a reply was lost): the same replies, no cycle
      ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
      EXPECT_EQ(core->resent, 1u);
    }
    EXPECT_EQ(core_act(*core), ra) << "cycle " << k;
    EXPECT_EQ(core_hlth(*core), rh) << "cycle " << k;
  }
  EXPECT_EQ(core->cycles, 4u);
  // the same time and sequence count with other contents is not a retransmission
  FswAcsSensorMsg m = sample(*cfg, 3);
  m.omega_BN_B[0] = static_cast<fsw_real>(0.002);
  Bytes p = sensor_packet(*cfg, m, 3);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  EXPECT_EQ(core->cycles, 5u);
  EXPECT_EQ(core->last_status, FSW_E_TIME);
}

TEST(KestrelAcsLink, IcdCommandPacketAppliedFromTheNextCycle)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Reference ref(*cfg);
  Bytes ra, rh;
  FswAcsCmdMsg cmd = base_cmd(*cfg);
  cmd.mode = FSW_ACS_MODE_INERTIAL;
  cmd.set_gains = 1;
  cmd.K = static_cast<fsw_real>(3.0);
  cmd.P = static_cast<fsw_real>(40.0);
  Bytes cp(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  ASSERT_EQ(fsw_link_encode_cmd(&cmd, 1, 0, cp.data(), cp.size(), &len, nullptr), FSW_OK);
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, cp.data(), len), 0);
  EXPECT_EQ(core->have_cmd, 1u);
  EXPECT_EQ(core->link_rejected, 0u);
  for (int k = 0; k < 3; ++k) {
    FswAcsSensorMsg m = sample(*cfg, k);
    Bytes p = sensor_packet(*cfg, m, static_cast<uint16_t>(k));
    ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
    ref.cycle(*cfg, m, &cmd, &ra, &rh);
    EXPECT_EQ(core_act(*core), ra);
    EXPECT_EQ(core_hlth(*core), rh);
  }
  EXPECT_EQ(core->acs.mode, FSW_ACS_MODE_INERTIAL);
}

TEST(KestrelAcsLink, DamagedPacketsRefusedCountedOneEventPerRun)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Bytes good = sensor_packet(*cfg, sample(*cfg, 0), 0);
  ASSERT_GT(good.size(), 20u);
  Bytes crc = good;
  const size_t last = good.size() - 1;
  crc[last] = static_cast<uint8_t>(crc[last] ^ 0x01u);
  kestrel_acs_core_clear_events(core.get());
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, crc.data(), crc.size()), 0);
  EXPECT_EQ(core->link_rejected, 1u);
  const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_LINK_REJECT);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->a, FSW_LINK_E_CRC);
  // more damage in the same run: counted, no new event
  Bytes body = good;
  body[20] ^= 0x40u;
  Bytes longer = good;
  longer.push_back(0);
  kestrel_acs_core_clear_events(core.get());
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, body.data(), body.size()), 0);
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, longer.data(), longer.size()), 0);
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, good.data(), 10), 0);
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, nullptr, 0), 0);
  EXPECT_EQ(core->link_rejected, 5u);
  EXPECT_EQ(core->num_events, 0);
  EXPECT_EQ(core->cycles, 0u);
  // a foreign APID (the FSW's own actuator packet sent back) is refused
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, good.data(), good.size()), 2);
  Bytes act = core_act(*core);
  kestrel_acs_core_clear_events(core.get());
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 0, act.data(), act.size()), 0);
  EXPECT_EQ(core->link_rejected, 6u);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_LINK_REJECT)); // a new run after the good packet
  // a wrong command code on the link message is a command error
  kestrel_acs_core_clear_events(core.get());
  EXPECT_EQ(kestrel_acs_core_link(core.get(), 1, good.data(), good.size()), 0);
  EXPECT_EQ(core->command_error_count, 1u);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_CMD_CC));
  EXPECT_EQ(core->cycles, 1u);
}

TEST(KestrelAcsLink, CycleErrorsReportedOncePerRun)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  Bytes p0 = sensor_packet(*cfg, sample(*cfg, 1), 0);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p0.data(), p0.size()), 2);
  ASSERT_FALSE(fsw_status_is_error(core->last_status));
  // cycle_errors counts error statuses only (a warning, e.g. a saturated
  // wheel, is counted in the health packet, not here)
  EXPECT_EQ(core->cycle_errors, 0u);
  // the same t_ns again: FSW_E_TIME, safe output, one event for the run
  for (int k = 0; k < 3; ++k) {
    Bytes p = sensor_packet(*cfg, sample(*cfg, 1), static_cast<uint16_t>(1 + k));
    kestrel_acs_core_clear_events(core.get());
    ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
    EXPECT_EQ(core->last_status, FSW_E_TIME);
    EXPECT_EQ(has_event(*core, KESTREL_ACS_EID_CYCLE_ERR), k == 0);
    FswAcsActuatorMsg act;
    uint8_t nrw, nthr, nmtq;
    FswLinkPacket pk;
    ASSERT_EQ(fsw_link_parse(core->act_pkt, core->act_len, &pk, nullptr), FSW_OK);
    ASSERT_EQ(fsw_link_decode_actuator(&pk, &act, &nrw, &nthr, &nmtq, nullptr), FSW_OK);
    EXPECT_EQ(act.wheels_active, 0u);
    EXPECT_EQ(act.thrusters_active, 0u);
    for (int i = 0; i < nrw; ++i) EXPECT_EQ(static_cast<double>(act.u_s[i]), 0.0);
  }
  EXPECT_EQ(core->cycle_errors, 3u);
  Bytes p = sensor_packet(*cfg, sample(*cfg, 2), 4);
  kestrel_acs_core_clear_events(core.get());
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  const KestrelAcsEvent* e = event(*core, KESTREL_ACS_EID_CYCLE_OK);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->a, 3);
  EXPECT_EQ(core->cycles, 5u);
}

TEST(KestrelAcsLink, NoConfigurationSafeOutput)
{
  auto cfg = s1_config();
  auto core = make_core();
  Bytes p = sensor_packet(*cfg, sample(*cfg, 0), 0);
  ASSERT_EQ(kestrel_acs_core_link(core.get(), 0, p.data(), p.size()), 2);
  EXPECT_EQ(core->last_status, FSW_E_NOT_INIT);
  EXPECT_TRUE(has_event(*core, KESTREL_ACS_EID_NO_CONFIG));
  FswLinkPacket pk;
  FswAcsActuatorMsg act;
  uint8_t nrw = 9, nthr = 9, nmtq = 9;
  ASSERT_EQ(fsw_link_parse(core->act_pkt, core->act_len, &pk, nullptr), FSW_OK);
  ASSERT_EQ(fsw_link_decode_actuator(&pk, &act, &nrw, &nthr, &nmtq, nullptr), FSW_OK);
  EXPECT_EQ(nrw + nthr + nmtq, 0);
  EXPECT_EQ(act.wheels_active + act.thrusters_active + act.mtq_active, 0);
}

// Arbitrary bytes (a fixed-seed generator, so the run repeats): link
// messages of random code, length and content, and valid sensor packets with
// one byte changed and the CRC made good again (so the decoder, not the CRC,
// judges them), and random ground commands.  Every link message is accounted
// for exactly once (a cycle, a retransmission, a kept command, a refusal or a
// command error), replies are whole ICD packets, the event list stays bounded.
TEST(KestrelAcsLink, ArbitraryBytesAccountedForAndNeverBreakTheCore)
{
  auto cfg = s1_config();
  auto core = make_core();
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  uint64_t x = 0x9E3779B97F4A7C15ull;
  auto rnd = [&x]() {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  uint32_t link_msgs = 0, kept = 0, bad_cc = 0;
  Bytes buf(400);
  for (int i = 0; i < 20000; ++i) {
    const int kind = static_cast<int>(rnd() % 3);
    size_t len = 0;
    uint8_t cc = 0;
    if (kind == 0) { // random bytes, random length, mostly cc 0
      len = static_cast<size_t>(rnd() % buf.size());
      for (size_t j = 0; j < len; ++j) buf[j] = static_cast<uint8_t>(rnd());
      cc = (rnd() % 8 == 0) ? static_cast<uint8_t>(rnd()) : 0;
    } else if (kind == 1) { // a sensor packet with one byte changed, CRC good again
      FswAcsSensorMsg m = sample(*cfg, i);
      Bytes p = sensor_packet(*cfg, m, static_cast<uint16_t>(i % 16384));
      const size_t at = static_cast<size_t>(rnd() % (p.size() - 2));
      p[at] = static_cast<uint8_t>(rnd());
      const uint16_t crc = fsw_link_crc16(p.data(), p.size() - 2, 0xFFFFu);
      p[p.size() - 2] = static_cast<uint8_t>(crc >> 8);
      p[p.size() - 1] = static_cast<uint8_t>(crc & 0xFFu);
      len = p.size();
      std::memcpy(buf.data(), p.data(), len);
    } else { // a ground command: random code and payload
      len = static_cast<size_t>(rnd() % 30);
      for (size_t j = 0; j < len; ++j) buf[j] = static_cast<uint8_t>(rnd());
      uint8_t gcc = static_cast<uint8_t>(rnd() % 10);
      if (gcc == KESTREL_ACS_RESET_COUNTERS_CC) gcc = KESTREL_ACS_NOOP_CC; // keep the totals below
      const uint8_t before = static_cast<uint8_t>(core->command_count + core->command_error_count);
      const int r = kestrel_acs_core_ground_cmd(core.get(), gcc, buf.data(), len);
      EXPECT_TRUE(r == 0 || r == 1);
      EXPECT_EQ(static_cast<uint8_t>(core->command_count + core->command_error_count),
                  static_cast<uint8_t>(before + 1));
      EXPECT_LE(core->num_events, KESTREL_ACS_MAX_EVENTS);
      kestrel_acs_core_clear_events(core.get());
      continue;
    }
    const uint32_t before = core->cycles + core->resent + core->link_rejected;
    const uint8_t errs = core->command_error_count;
    const int r = kestrel_acs_core_link(core.get(), cc, buf.data(), len);
    ++link_msgs;
    ASSERT_TRUE(r == 0 || r == 2);
    if (cc != 0) {
      EXPECT_EQ(r, 0);
      EXPECT_EQ(static_cast<uint8_t>(errs + 1), core->command_error_count);
      ++bad_cc;
    } else if (r == 2) {
      EXPECT_EQ(core->cycles + core->resent + core->link_rejected, before + 1);
      FswLinkPacket pk;
      EXPECT_EQ(fsw_link_parse(core->act_pkt, core->act_len, &pk, nullptr), FSW_OK);
      EXPECT_EQ(pk.apid, FSW_LINK_APID_ACTUATOR);
      EXPECT_EQ(fsw_link_parse(core->hlth_pkt, core->hlth_len, &pk, nullptr), FSW_OK);
      EXPECT_EQ(pk.apid, FSW_LINK_APID_HEALTH);
    } else if (core->cycles + core->resent + core->link_rejected == before) {
      EXPECT_EQ(core->have_cmd, 1u); // an ICD command packet, kept
      ++kept;
    } else {
      EXPECT_EQ(core->cycles + core->resent + core->link_rejected, before + 1);
    }
    EXPECT_LE(core->num_events, KESTREL_ACS_MAX_EVENTS);
    kestrel_acs_core_clear_events(core.get());
  }
  EXPECT_EQ(core->cycles + core->resent + core->link_rejected + kept + bad_cc, link_msgs);
  EXPECT_GT(core->cycles, 100u);      // the changed-byte packets that still decode ran cycles
  EXPECT_GT(core->link_rejected, 1000u);
  std::printf("arbitrary link messages: %u, cycles %u, refused %u, kept commands %u, wrong codes %u\n",
              link_msgs, core->cycles, core->link_rejected, kept, bad_cc);
}

// ---- housekeeping ---------------------------------------------------------

TEST(KestrelAcsHk, LayoutAtTheDocumentedOffsets)
{
  auto core = make_core();
  uint8_t hk[KESTREL_ACS_HK_LEN];
  std::memset(hk, 0xAA, sizeof hk);
  kestrel_acs_core_hk(core.get(), hk);
  for (uint8_t b : hk) EXPECT_EQ(b, 0u); // nothing loaded, nothing counted, status FSW_OK = 0
  ASSERT_EQ(kestrel_acs_core_configure(core.get(), &KESTREL_ACS_Config), FSW_OK);
  const uint8_t mode[4] = {FSW_ACS_MODE_INERTIAL, 0, 0, 0};
  ASSERT_EQ(kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_SET_MODE_CC, mode, 4), 1);
  kestrel_acs_core_ground_cmd(core.get(), KESTREL_ACS_NOOP_CC, nullptr, 0);
  kestrel_acs_core_ground_cmd(core.get(), 42, nullptr, 0);
  core->cycles = 0x01020304u;
  core->cycle_errors = 0xA0B0C0D0u;
  core->link_rejected = 7u;
  core->table_rejects = 0x00010000u;
  core->last_status = FSW_E_TIME; // -6
  core->acs.mode = FSW_ACS_MODE_INERTIAL;
  kestrel_acs_core_hk(core.get(), hk);
  const uint8_t want[KESTREL_ACS_HK_LEN] = {
      2, 1, 1, 1,             // command_count, command_error_count, mode, config_loaded
      0x01, 0x02, 0x03, 0x04, // cycles
      0xA0, 0xB0, 0xC0, 0xD0, // cycle_errors
      0, 0, 0, 7,             // link_rejected
      0xFF, 0xFF, 0xFF, 0xFA, // last_status -6 as u32
      0x00, 0x01, 0x00, 0x00  // table_rejects
  };
  for (size_t i = 0; i < KESTREL_ACS_HK_LEN; ++i) EXPECT_EQ(hk[i], want[i]) << "byte " << i;
  EXPECT_EQ(be32(hk + 4), 0x01020304u);
}

} // namespace
