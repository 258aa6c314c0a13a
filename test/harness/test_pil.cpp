// Processor in the loop (docs/pil.md): S1, shortened, with the FSW running
// cross-compiled on an emulated processor and the harness closing the loop
// through the FSW link, against the in-process run, per telemetry column:
//
//   aarch64-linux, armhf-linux   kestrel-fsw under qemu-user, UDP    bit for bit
//   cortex-m4f (double)          bare metal on qemu-system-arm, UART bit for bit
//   cortex-m4f-float             bare metal, fsw_real = float        bounded, below
//
// and the robustness of start-up and shutdown: an emulator that never gets
// ready, one that ends at once and one that never answers each fail the run
// with a message naming the FSW side, within the time-out, and leave no
// process behind.  host-release only (label pil); a target whose cross
// compiler or emulator was missing when the build was configured is skipped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "harness/drive/run_scenario.h"
#include "harness/link/pil.h"
#include "harness/link/remote_fsw.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "hwil_support.hpp"

namespace {

namespace fs = std::filesystem;
using hwil::TempDir;
const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";
// Generous: a loaded 2-core machine can stall QEMU for seconds.
constexpr double kTimeout = 60.0;  // [s] start-up and lockstep reply

const harness::PilTarget* target(const std::string& name)
{
  for (const auto& t : harness::pil_targets())
    if (t.name == name) return &t;
  return nullptr;
}

// S1 cut to `seconds` of simulated time (the FSW runs at 10 Hz: 10 cycles
// per second through the link).
harness::Scenario s1(double seconds)
{
  return harness::load_scenario(kS1, {harness::parse_override("duration=" + std::to_string(seconds))});
}

uint64_t bits(double x)
{
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

struct Linked {
  harness::MemorySink mem;
  harness::LinkCounters link;
  double wall_s = 0;
};

// Runs sc with its FSW on the emulated target.
bool run_pil(const std::string& name, const harness::Scenario& sc, Linked& out, const std::string& key_file = "")
{
  harness::LinkOptions lo;
  lo.timeout_s = kTimeout;
  lo.key_file = key_file;
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  auto r = std::make_unique<harness::RemoteFsw>(harness::open_pil_transport("pil:" + name, cfg, lo), cfg, lo);
  harness::RemoteFsw* link = r.get();
  harness::RunConfig rc;
  rc.fsw = std::move(r);
  harness::Run run(sc, std::move(rc));
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = run.step_ticks(run.total_ticks());
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(ok) << run.failure();
  out.link = link->counters();
  out.mem = run.memory();
  return ok;
}

// Largest |difference| per column (NaN-aware: NaN against NaN is equal).
// Rows [0, rows) (all when rows is 0).
std::map<std::string, double> column_differences(const harness::MemorySink& a, const harness::MemorySink& b,
                                                 size_t& differing_values, uint64_t rows = 0)
{
  std::map<std::string, double> d;
  differing_values = 0;
  if (rows == 0 || rows > a.rows()) rows = a.rows();
  for (size_t c = 0; c < a.num_columns(); ++c)
    for (uint64_t r = 0; r < rows; ++r) {
      const double x = a.at(r, c), y = b.at(r, c);
      if (bits(x) == bits(y)) continue;
      ++differing_values;
      const double e = std::isnan(x) || std::isnan(y) ? INFINITY : std::fabs(x - y);
      double& m = d[a.columns()[c].name];
      m = std::max(m, e);
    }
  return d;
}

void print_differences(const std::string& name, const std::map<std::string, double>& d, size_t n)
{
  std::printf("PIL %s: %zu values differ from the in-process run in %zu columns\n", name.c_str(), n, d.size());
  for (const auto& [col, e] : d) std::printf("  %-28s max |diff| %.3e\n", col.c_str(), e);
}

// Error model for a FSW whose arithmetic differs from the in-process one
// (a float build, or another maths library), over a run of T seconds of S1:
//  - each torque the FSW outputs is off by at most du = C * eps * U, with
//    eps the unit roundoff of its arithmetic, U = K * 1 + P * |omega|max
//    the largest torque request of S1's law (|sigma| <= 1 for a shadow-set
//    MRP; K = 3.5 N m, P = 30 N m s, |omega| <= 0.05 rad/s: the initial
//    0.0316 rad/s tumble and the wheels' at most 4 * 0.2 N m * T / 600 kg m2
//    of spin-up), and C = 100 roundings of that size along css_sun ->
//    guid_sunsafe -> mrp_fb -> rw_map (each stage a few tens of operations
//    on quantities no larger than U; rw_map's minimum-norm map of the 40 deg
//    pyramid has 2-norm gain 1 / sqrt(4 cos^2(40 deg) / 2) = 0.92 < 1);
//  - the loop feeds state differences back (P * d_omega + K * d_sigma), so
//    the body-rate difference grows at most like Gronwall's bound
//    d_omega(T) <= 4 du / J (e^{aT} - 1) / a, with a = 4 (P + K T / 4) / J
//    (J = 600 kg m2 the smallest principal inertia, 4 wheels, d_sigma <=
//    d_omega T / 4);
//  - attitude: d_sigma <= d_omega T / 4, the pointing error's angle (4 atan
//    |sigma|) d_theta <= d_omega T; wheel speed: d_Omega <= (du + P d_omega
//    + K d_sigma) T / J_s, J_s = 0.0796 kg m2.
struct Bounds {
  double du, d_omega, d_sigma, d_theta_deg, d_wheel_rpm;
};

Bounds bounds(double eps, double T)
{
  const double K = 3.5, P = 30.0, J = 600.0, Js = 0.0795775, U = K * 1.0 + P * 0.05, C = 100.0;
  Bounds b{};
  b.du = C * eps * U;
  const double a = 4.0 * (P + K * T / 4.0) / J;
  b.d_omega = 4.0 * b.du / J * std::expm1(a * T) / a;
  b.d_sigma = b.d_omega * T / 4.0;
  b.d_theta_deg = b.d_omega * T * 180.0 / M_PI;
  const double du_total = b.du + P * b.d_omega + K * b.d_sigma;  // the torque difference with feedback
  b.d_wheel_rpm = du_total * T / Js * 60.0 / (2.0 * M_PI);
  b.du = du_total;
  return b;
}

void expect_within(const std::map<std::string, double>& d, const std::string& prefix, double bound)
{
  for (const auto& [col, e] : d)
    if (col.rfind(prefix, 0) == 0) {
      EXPECT_LE(e, bound) << col;
    }
}

// S1 for `seconds` with its FSW on the emulated target, against the
// in-process run, per telemetry column: within the error model above for
// eps, and bit for bit when `identical` (same C code, compiled for the
// target with -ffp-contract=off, fed the same binary64 inputs: reals cross
// the link as binary64; IEEE-754 double arithmetic; maths functions that
// give the same bits, see the tests).
void pil_against_in_process(const std::string& name, double seconds, double eps, bool identical)
{
  const harness::PilTarget* t = target(name);
  ASSERT_NE(t, nullptr);
  if (t->default_bin.empty()) GTEST_SKIP() << name << " not built (cross compiler or emulator missing)";
  const harness::Scenario sc = s1(seconds);
  harness::Run local(sc);
  ASSERT_TRUE(local.step_ticks(local.total_ticks())) << local.failure();
  Linked l;
  ASSERT_TRUE(run_pil(name, sc, l));
  ASSERT_EQ(local.memory().rows(), l.mem.rows());
  ASSERT_EQ(local.memory().num_columns(), l.mem.num_columns());
  size_t n = 0;
  const auto d = column_differences(local.memory(), l.mem, n);
  print_differences(name, d, n);
  std::printf("PIL %s: %llu FSW cycles in %.2f s wall = %.0f cycles/s (start-up included)\n", name.c_str(),
              (unsigned long long)l.link.cycles, l.wall_s, static_cast<double>(l.link.cycles) / l.wall_s);
  if (identical) {
    EXPECT_EQ(n, 0u);
  }
  {
    // the model (Gronwall, no credit for the loop's damping) is useful over
    // the first 10 s; beyond that it grows without bound, so longer runs are
    // held to it over their first 10 s (and to the pointing requirement)
    const double T = std::min(seconds, 10.0);
    const auto tt = local.memory().column("t");
    uint64_t rows = 0;
    while (rows < tt.size() && tt[rows] <= T + 1e-9) ++rows;
    size_t nw = 0;
    const auto dw = column_differences(local.memory(), l.mem, nw, rows);
    const auto& d = dw;
    const Bounds b = bounds(eps, T);
    std::printf("PIL %s: %zu values differ in the first %.0f s; bounds for eps %.3g: torque %.3g N m, rate %.3g "
                "rad/s, MRP %.3g, pointing %.3g deg, wheel speed %.3g rpm\n",
                name.c_str(), nw, T, eps, b.du, b.d_omega, b.d_sigma, b.d_theta_deg, b.d_wheel_rpm);
    for (const char* c : {"wheel_cmd_", "wheel_torque_", "Lr_B_"}) expect_within(d, c, b.du);
    for (const char* c : {"omega_BN_B_", "meas_omega_BN_B_"}) expect_within(d, c, b.d_omega);
    for (const char* c : {"sigma_BN_", "meas_sigma_BN_"}) expect_within(d, c, b.d_sigma);
    expect_within(d, "pointing_error_deg", b.d_theta_deg);
    for (const char* c : {"wheel_speed_rpm_", "meas_wheel_speed_rpm_"}) expect_within(d, c, b.d_wheel_rpm);
    // nothing else may differ in kind: no NaN, no status or flag column
    for (const auto& [col, e] : d) {
      EXPECT_TRUE(std::isfinite(e)) << col;
      EXPECT_EQ(col.find("status"), std::string::npos) << col;
      EXPECT_EQ(col.find("valid"), std::string::npos) << col;
      EXPECT_EQ(col.find("safe"), std::string::npos) << col;
    }
  }
  // S1's pointing requirement (test_closed_loop.cpp): Sun within 0.5 deg of
  // +z_B from t = 450 s, when the run is that long
  if (seconds >= 450.0) {
    const auto tt = l.mem.column("t"), err = l.mem.column("pointing_error_deg");
    double worst = 0.0;
    for (size_t i = 0; i < tt.size(); ++i)
      if (tt[i] >= 450.0) worst = std::max(worst, err[i]);
    std::printf("PIL %s: worst pointing error after 450 s %.4f deg\n", name.c_str(), worst);
    EXPECT_LT(worst, 0.5);
  }
  EXPECT_EQ(l.link.replies, l.link.cycles);
  EXPECT_EQ(l.link.cycles, static_cast<uint64_t>(std::llround(seconds * 10.0)) + 1u);
  EXPECT_EQ(l.link.missing + l.link.rejected, 0u);
  // a reply slower than the 0.25 s retransmission time (an emulator on a
  // loaded machine): the packet again, answered again, counted stale
  EXPECT_LE(l.link.stale, 2 * l.link.retransmits);
  EXPECT_LE(l.link.fsw.rx_stale, l.link.retransmits);
  EXPECT_EQ(l.link.fsw.rx_crc + l.link.fsw.rx_rejected + l.link.fsw.missed, 0u);
  EXPECT_EQ(l.link.fsw.cycles, l.link.cycles);
}

// Running (a zombie that its new parent has not reaped yet counts as gone).
bool process_exists(pid_t pid)
{
  if (::kill(pid, 0) != 0 && errno == ESRCH) return false;
  std::ifstream st("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(st, line)) return false;
  const auto rp = line.rfind(')');  // "pid (comm) S ...": the state follows the name
  return rp == std::string::npos || rp + 2 >= line.size() || line[rp + 2] != 'Z';
}

// A fake emulator (shell script): writes its pid, then does what `body`
// says.  exec keeps the pid.
std::string fake_emulator(const fs::path& dir, const std::string& body)
{
  const fs::path p = dir / "fake-emulator.sh";
  std::ofstream(p) << "#!/bin/sh\necho $$ > " << (dir / "pid").string() << "\n" << body << "\n";
  fs::permissions(p, fs::perms::owner_all);
  return p.string();
}

pid_t read_pid(const fs::path& dir)
{
  long pid = -1;
  std::ifstream(dir / "pid") >> pid;
  return static_cast<pid_t>(pid);
}

// Runs S1 with the fake emulator; returns the run's error message.
std::string failing_run(const std::string& name, const std::string& emulator, double timeout_s, double& took_s)
{
  const harness::Scenario sc = s1(5.0);
  harness::LinkOptions lo;
  lo.timeout_s = timeout_s;
  lo.pil_emulator = emulator;
  lo.pil_bin = KESTREL_SOURCE_DIR "/README.md";  // any file: the fake ignores it
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  const auto t0 = std::chrono::steady_clock::now();
  std::string msg;
  try {
    harness::RunConfig rc;
    rc.fsw = std::make_unique<harness::RemoteFsw>(harness::open_pil_transport("pil:" + name, cfg, lo), cfg, lo);
    harness::Run run(sc, std::move(rc));
    EXPECT_FALSE(run.step_ticks(run.total_ticks()));
    msg = run.failure();
  } catch (const std::exception& e) {
    msg = e.what();
  }
  took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return msg;
}

}  // namespace

// glibc's double maths functions (the FSW calls sqrt, acos, atan, tan) give
// the same bits on x86-64 and aarch64 only when the x86-64 CPU has FMA:
// glibc then runs variants of acos/atan/tan compiled with fused multiply-add
// (ifunc), as its aarch64 build is; without FMA (GLIBC_TUNABLES=
// glibc.cpu.hwcaps=-FMA, or an old CPU) x86-64 gives the bits of Armv7,
// whose VFPv3 has no FMA.  Checked over 10^6 arguments (docs/pil.md).  So
// the Linux targets are bit for bit where the host's libm takes the same
// path, and within double's roundoff model (eps = 2^-53) in any case.
bool host_fma() { return __builtin_cpu_supports("fma") != 0; }

// The Linux targets are fast enough (thousands of cycles/s under qemu-user)
// for the whole 600 s of S1, with its pointing requirement.
TEST(Pil, S1OnAarch64LinuxEqualsInProcess) { pil_against_in_process("aarch64-linux", 600.0, 0x1p-53, host_fma()); }
TEST(Pil, S1OnArmhfLinuxMatchesInProcess) { pil_against_in_process("armhf-linux", 600.0, 0x1p-53, !host_fma()); }

// The magnetic modes through the emulated aarch64 FSW: 60 s of S3's
// detumble (B-dot on the rods: magnetometer in, rod dipoles out, ICD
// version 2) and 60 s of nadir pointing with magnetorquer desaturation and
// wheel bias, each bit for bit the in-process run where the host's libm
// takes aarch64's path (as for S1 above).
TEST(Pil, S3DetumbleAndNadirOnAarch64LinuxEqualInProcess)
{
  const harness::PilTarget* t = target("aarch64-linux");
  ASSERT_NE(t, nullptr);
  if (t->default_bin.empty()) GTEST_SKIP() << "aarch64-linux not built (cross compiler or emulator missing)";
  const std::string file = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s3_detumble_hold.yaml";
  for (const char* mode : {"detumble", "nadir"}) {
    const harness::Scenario sc = harness::load_scenario(
        file, {harness::parse_override("duration=60"), harness::parse_override(std::string("fsw.mode=") + mode)});
    harness::Run local(sc);
    ASSERT_TRUE(local.step_ticks(local.total_ticks())) << local.failure();
    Linked l;
    ASSERT_TRUE(run_pil("aarch64-linux", sc, l));
    ASSERT_EQ(local.memory().rows(), l.mem.rows());
    size_t n = 0;
    const auto d = column_differences(local.memory(), l.mem, n);
    print_differences(std::string("aarch64-linux S3 ") + mode, d, n);
    if (host_fma()) {
      EXPECT_EQ(n, 0u) << mode;
    }
    const auto m = l.mem.column("mtq_dipole_0");
    double peak = 0.0;
    for (double x : m) peak = std::max(peak, std::fabs(x));
    EXPECT_GT(peak, 0.0) << mode << ": the emulated FSW commanded no rod";
  }
}
// Packet authentication through the emulated aarch64 kestrel-fsw: the
// harness gives it the key file (--key) and keys its own end; S1 over 60 s
// equals the in-process run as the unkeyed PIL run does (bit for bit with
// FMA on the host, see above).  The bare-metal targets (a UART stream)
// refuse a key with a message.
TEST(Pil, S1OnAarch64LinuxWithASharedKeyEqualsInProcess)
{
  const harness::PilTarget* t = target("aarch64-linux");
  ASSERT_NE(t, nullptr);
  if (t->default_bin.empty()) GTEST_SKIP() << "aarch64-linux not built (cross compiler or emulator missing)";
  const harness::Scenario sc = s1(60.0);
  harness::Run local(sc);
  ASSERT_TRUE(local.step_ticks(local.total_ticks())) << local.failure();
  TempDir tmp;
  const fs::path key = tmp.p / "link.key";
  std::ofstream(key) << "00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff\n";
  fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write);
  Linked l;
  ASSERT_TRUE(run_pil("aarch64-linux", sc, l, key.string()));
  size_t n = 0;
  const auto d = column_differences(local.memory(), l.mem, n);
  print_differences("aarch64-linux S1 with a key", d, n);
  if (host_fma()) {
    EXPECT_EQ(n, 0u);
  }
  EXPECT_EQ(l.link.replies, l.link.cycles);
  EXPECT_EQ(l.link.rejected, 0u);
  EXPECT_EQ(l.link.fsw.cycles, l.link.cycles);
  harness::LinkOptions lo;
  lo.key_file = key.string();
  try {
    harness::open_pil_transport("pil:cortex-m4f", harness::fsw_acs_config_of(sc), lo);
    ADD_FAILURE() << "a key on the bare-metal target was accepted";
  } catch (const harness::FswEndpointError& e) {
    EXPECT_NE(std::string(e.what()).find("UART link has no packet authentication"), std::string::npos) << e.what();
  }
}

// The Cortex-M4F over the emulated UART does 20-45 cycles/s: 10 s of S1.
// The double build is not bit for bit: its maths functions come from
// picolibc (fdlibm-derived, within 1 ulp but not always glibc's last bit),
// so differences of an ulp enter: bounded with eps = 2^-53.
TEST(Pil, S1OnCortexM4fDoubleWithinRoundoffOfInProcess)
{
  pil_against_in_process("cortex-m4f", 10.0, 0x1p-53, false);
}
// The float build (fsw_real = float, the M4F's single-precision FPU): every
// FSW quantity rounded to 24 bits, so eps = 2^-24.
TEST(Pil, S1OnCortexM4fFloatWithinRoundoffOfInProcess)
{
  pil_against_in_process("cortex-m4f-float", 10.0, 0x1p-24, false);
}

// Runs the fake emulator `body` as target `name` with a 2 s time-out: the
// run fails with a message holding every `expected` piece, within the
// time-out plus at most the 2 s SIGTERM grace (sleep ends at once on
// SIGTERM) plus 1 s of slack, and the emulator is gone afterwards.
void expect_time_out_and_stop(const std::string& name, const std::string& body,
                              const std::vector<std::string>& expected)
{
  TempDir tmp;
  double took = 0;
  const std::string msg = failing_run(name, fake_emulator(tmp.p, body), 2.0, took);
  for (const std::string& e : expected) EXPECT_NE(msg.find(e), std::string::npos) << msg;
  const pid_t pid = read_pid(tmp.p);
  ASSERT_GT(pid, 0);
  EXPECT_FALSE(process_exists(pid)) << "emulator pid " << pid << " left running";
  EXPECT_LT(took, 2.0 + 2.0 + 1.0);
}

// An emulator that never reports ready: the start-up fails within the
// time-out, naming the FSW side, and the emulator is gone afterwards.
TEST(Pil, EmulatorThatNeverGetsReadyTimesOutAndIsStopped)
{
  expect_time_out_and_stop("aarch64-linux", "exec sleep 300", {"PIL (FSW side)", "did not report ready within"});
}

// A board whose UART never opens (the emulator hangs before it listens).
TEST(Pil, BoardWhoseUartNeverOpensTimesOutAndIsStopped)
{
  expect_time_out_and_stop("cortex-m4f", "exec sleep 300", {"PIL (FSW side)", "did not open its UART socket"});
}

// Ready, then silent: the lockstep time-out fails the run, the message says
// the FSW side is running but did not answer, and the process is stopped.
// Port 9 (discard): nothing answers on loopback.
TEST(Pil, EmulatedFswThatNeverAnswersTimesOutAndIsStopped)
{
  expect_time_out_and_stop("aarch64-linux", "echo 'kestrel-fsw: ready udp 127.0.0.1:9'; exec sleep 300",
                           {"no reply to the sensor packet",
                            "FSW side: the emulated FSW is still running but did not answer"});
}

// An emulator that ends at once: reported at once with its status and output.
TEST(Pil, EmulatorThatEndsIsReportedWithItsStatus)
{
  TempDir tmp;
  double took = 0;
  const std::string msg =
      failing_run("aarch64-linux", fake_emulator(tmp.p, "echo 'guest: bad ELF' >&2; exit 3"), 30.0, took);
  EXPECT_NE(msg.find("PIL (FSW side)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exited with status 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("guest: bad ELF"), std::string::npos) << msg;
  // noticed when it ended, not at the 30 s time-out: stdout closes at the
  // exit, then at most the 2 s wait for the reaping, plus 1 s of slack
  EXPECT_LT(took, 3.0);
}

// `kestrel run` (the CLI) with the M4F: Ctrl-C (SIGINT) stops the run at a
// tick boundary and the emulator with it; SIGKILL of the harness takes the
// emulator down through PR_SET_PDEATHSIG.  The emulator is wrapped in a
// script that records its pid and execs QEMU (same pid).
pid_t spawn_kestrel(const fs::path& dir, const std::string& wrapper)
{
  const std::vector<std::string> argv = {KESTREL_EXE, "run", kS1, "-o", (dir / "run").string(), "--fsw",
                                         "pil:cortex-m4f-float", "--pil-emulator", wrapper};
  std::vector<char*> av;
  for (const auto& a : argv) av.push_back(const_cast<char*>(a.c_str()));
  av.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, (dir / "out.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 2, (dir / "err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, av[0], &fa, nullptr, av.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

// Waits (bounded) until the wrapper has written its pid and the run has
// been going for a while.
pid_t wait_for_emulator(const fs::path& dir)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(kTimeout);
  pid_t pid = -1;
  while (pid <= 0 && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    pid = read_pid(dir);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // some cycles through the link
  return pid;
}

bool gone_within(pid_t pid, double seconds)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (process_exists(pid) && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return !process_exists(pid);
}

std::string qemu_wrapper(const fs::path& dir)
{
  return fake_emulator(dir, "echo \"$@\" > " + (dir / "args").string() +
                                "; exec qemu-system-arm -M mps2-an386 -cpu cortex-m4 \"$@\"");
}

std::string read_text(const fs::path& p)
{
  std::ifstream f(p);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// Starts `kestrel run` with the M4F behind the wrapper, sends `sig` to it
// once the run is going, and reaps it: its wait status and the emulator's
// pid (-1 when the emulator never started).
pid_t run_and_signal(const fs::path& dir, int sig, int& status)
{
  const pid_t k = spawn_kestrel(dir, qemu_wrapper(dir));
  if (k <= 0) return -1;
  const pid_t emu = wait_for_emulator(dir);
  EXPECT_TRUE(emu > 0 && process_exists(emu));
  ::kill(k, sig);
  EXPECT_EQ(::waitpid(k, &status, 0), k);
  return emu;
}

TEST(Pil, CtrlCStopsTheRunAndTheEmulator)
{
  if (target("cortex-m4f-float")->default_bin.empty()) GTEST_SKIP() << "cortex-m4f-float not built";
  TempDir tmp;
  int st = 0;
  const pid_t emu = run_and_signal(tmp.p, SIGINT, st);
  ASSERT_GT(emu, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 128 + SIGINT);  // kestrel's "interrupted by SIGINT" exit code
  EXPECT_FALSE(process_exists(emu)) << "emulator pid " << emu << " left running";
  const std::string err = read_text(tmp.p / "err.txt");
  EXPECT_NE(err.find("interrupted by SIGINT"), std::string::npos) << err;
}

TEST(Pil, KilledHarnessTakesTheEmulatorDown)
{
  if (target("cortex-m4f-float")->default_bin.empty()) GTEST_SKIP() << "cortex-m4f-float not built";
  TempDir tmp;
  int st = 0;
  const pid_t emu = run_and_signal(tmp.p, SIGKILL, st);
  ASSERT_GT(emu, 0);
  EXPECT_TRUE(WIFSIGNALED(st));
  // the kernel delivers SIGKILL to the emulator when its parent dies; it
  // becomes a child of init (or of a subreaper), so only its end is seen
  EXPECT_TRUE(gone_within(emu, 10.0)) << "emulator pid " << emu << " left running";
  // its temporary folder is left behind (nobody ran the cleanup; docs/pil.md):
  // the wrapper recorded QEMU's arguments, which name it
  const std::string args = read_text(tmp.p / "args");
  const auto at = args.find("path=/tmp/kestrel-pil-"), slash = args.find("/uart0.sock");
  ASSERT_NE(at, std::string::npos) << args;
  ASSERT_NE(slash, std::string::npos) << args;
  const fs::path left = args.substr(at + 5, slash - at - 5);
  EXPECT_TRUE(fs::is_directory(left)) << left;
  std::error_code ec;
  fs::remove_all(left, ec);
}

// The bare-metal program checks its configuration image before it starts
// the link: an image with one flipped body byte (the wrapper hands QEMU's
// loader that file instead of the harness's) makes it stop with exit
// status 1 and say why; the harness reports the FSW side at once.
TEST(Pil, BoardRefusesACorruptConfigurationImage)
{
  if (target("cortex-m4f-float")->default_bin.empty()) GTEST_SKIP() << "cortex-m4f-float not built";
  TempDir tmp;
  const harness::Scenario sc = s1(5.0);
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  std::vector<uint8_t> img(fsw_link_config_size());
  size_t len = 0;
  ASSERT_EQ(fsw_link_config_encode(&cfg, img.data(), img.size(), &len, nullptr), FSW_OK);
  img[FSW_LINK_CONFIG_HEADER + 100] ^= 0x10u;
  const fs::path bad = tmp.p / "bad.img";
  std::ofstream(bad, std::ios::binary).write(reinterpret_cast<const char*>(img.data()), static_cast<long>(len));
  const std::string wrapper = fake_emulator(
      tmp.p, "exec qemu-system-arm -M mps2-an386 -cpu cortex-m4 $(echo \"$@\" | sed 's|loader,file=[^,]*|loader,file=" +
                 bad.string() + "|')");
  harness::LinkOptions lo;
  lo.timeout_s = kTimeout;
  lo.pil_emulator = wrapper;
  std::string msg;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    harness::RunConfig rc;
    rc.fsw = std::make_unique<harness::RemoteFsw>(harness::open_pil_transport("pil:cortex-m4f-float", cfg, lo), cfg, lo);
    harness::Run run(sc, std::move(rc));
    EXPECT_FALSE(run.step_ticks(run.total_ticks()));
    msg = run.failure();
  } catch (const std::exception& e) {
    msg = e.what();
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(msg.find("PIL (FSW side)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exited with status 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("configuration image at 0x00380000 refused: CRC mismatch"), std::string::npos) << msg;
  EXPECT_LT(took, kTimeout);  // seen when QEMU ended, not at the reply time-out
}

// An unknown target and a missing program are refused before anything starts.
TEST(Pil, UnknownTargetAndMissingProgramAreRefused)
{
  const harness::Scenario sc = s1(1.0);
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  harness::LinkOptions lo;
  try {
    harness::open_pil_transport("pil:pdp11", cfg, lo);
    ADD_FAILURE() << "accepted an unknown target";
  } catch (const harness::FswEndpointError& e) {
    EXPECT_NE(std::string(e.what()).find("known: aarch64-linux"), std::string::npos) << e.what();
  }
  lo.pil_bin = "/nonexistent/kestrel-fsw";
  try {
    harness::open_pil_transport("pil:armhf-linux", cfg, lo);
    ADD_FAILURE() << "accepted a missing program";
  } catch (const harness::FswEndpointError& e) {
    EXPECT_NE(std::string(e.what()).find("no FSW program at /nonexistent"), std::string::npos) << e.what();
  }
}
