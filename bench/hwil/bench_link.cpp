// Lockstep FSW cycles per second through the FSW link (docs/hwil.md): the
// harness end (RemoteFsw) drives kestrel-fsw, started here, with S1's FSW
// configuration, one sensor packet per cycle and a wait for its actuator and
// health packets.  Over loopback UDP and over a socat pty pair (when socat
// is installed).  Then the whole S1 scenario in process and in lockstep over
// UDP, wall times side by side.  Prints figures; not a pass/fail test.
//
//   bench_link [CYCLES]      (default 20000)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "harness/link/remote_fsw.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "hwil_support.hpp"

extern "C" void fsw_assert_failed(const char* file, int line)
{
  std::fprintf(stderr, "bench_link: FSW assertion failed at %s:%d\n", file, line);
}

namespace {

using Clock = std::chrono::steady_clock;
const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::unique_ptr<hwil::Child> start(const std::vector<std::string>& args, std::string& ready)
{
  std::vector<std::string> argv{KESTREL_FSW_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  auto c = std::make_unique<hwil::Child>(argv);
  ready = c->line(60.0);
  if (ready.empty()) throw std::runtime_error("kestrel-fsw did not start");
  return c;
}

// cycles of a fixed sensor message with advancing time stamps
double cycles_per_second(harness::RemoteFsw& fsw, int n)
{
  FswAcsSensorMsg s;
  std::memset(&s, 0, sizeof s);
  s.att_valid = 1;
  s.omega_BN_B[0] = 0.01;
  s.css[0] = 0.9;
  FswAcsActuatorMsg a;
  FswAcsHealthMsg h;
  for (int k = 0; k < 100; ++k) {  // warm-up
    s.t_ns = static_cast<uint64_t>(k + 1) * 100000000ull;
    fsw.cycle(s, a, h);
  }
  const auto t0 = Clock::now();
  for (int k = 0; k < n; ++k) {
    s.t_ns = static_cast<uint64_t>(k + 101) * 100000000ull;
    fsw.cycle(s, a, h);
  }
  return n / seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv)
{
  const int n = argc > 1 ? std::atoi(argv[1]) : 20000;
  const harness::Scenario sc = harness::load_scenario(kS1, {});
  const FswAcsConfig cfg = harness::fsw_acs_config_of(sc);
  hwil::TempDir tmp;
  const std::string img = (tmp.p / "s1.img").string();
  {
    std::vector<uint8_t> b(fsw_link_config_size());
    size_t len = 0;
    fsw_link_config_encode(&cfg, b.data(), b.size(), &len, nullptr);
    std::ofstream(img, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<long>(len));
  }
  std::string ready;
  harness::LinkOptions lo;
  lo.timeout_s = 30.0;
  std::string udp;
  {
    auto fsw = start({"--udp", "127.0.0.1:0", "--config", img, "--quiet"}, ready);
    udp = "udp:" + ready.substr(std::strlen("kestrel-fsw: ready udp "));
    harness::RemoteFsw r(harness::open_link_transport(udp), cfg, lo);
    std::printf("lockstep over loopback UDP: %.0f FSW cycles/s (%d cycles, S1 configuration)\n",
                cycles_per_second(r, n), n);
  }
  const char* socat = std::getenv("SOCAT") != nullptr ? std::getenv("SOCAT") : "/usr/bin/socat";
  if (std::ifstream(socat).good()) {
    hwil::PtyPair pty(socat, tmp.p, 60.0);
    auto fsw = start({"--serial", pty.end_a() + ":115200", "--config", img, "--quiet"}, ready);
    harness::RemoteFsw r(harness::open_link_transport("serial:" + pty.end_b() + ":115200"), cfg, lo);
    std::printf("lockstep over a pty pair (socat): %.0f FSW cycles/s (%d cycles)\n", cycles_per_second(r, n / 4),
                n / 4);
  } else {
    std::printf("lockstep over a pty pair: skipped (no %s)\n", socat);
  }
  // the whole S1 scenario, in process and over UDP
  auto t0 = Clock::now();
  harness::Run local(sc);
  local.step_ticks(local.total_ticks());
  const double t_local = seconds_since(t0);
  auto fsw = start({"--udp", "127.0.0.1:0", "--config", img, "--quiet"}, ready);
  harness::RunConfig rc;
  rc.fsw = std::make_unique<harness::RemoteFsw>(
      harness::open_link_transport("udp:" + ready.substr(std::strlen("kestrel-fsw: ready udp "))), cfg, lo);
  t0 = Clock::now();
  harness::Run linked(sc, std::move(rc));
  linked.step_ticks(linked.total_ticks());
  const double t_linked = seconds_since(t0);
  std::printf("S1 (%.0f s, %llu ticks, 6001 FSW cycles): in process %.2f s wall (%.0fx real time), "
              "lockstep over UDP %.2f s wall (%.0fx real time)%s\n",
              sc.duration, static_cast<unsigned long long>(local.total_ticks()), t_local, sc.duration / t_local,
              t_linked, sc.duration / t_linked, linked.failure().empty() ? "" : " FAILED");
  return 0;
}
