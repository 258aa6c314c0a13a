// run_program: `kestrel run` as the program runs it (the cli room; included
// by main.cpp only).  The live view's library (harness_live) is linked into
// the kestrel program alone, not into the libraries the tests and the Python
// module link, so what owns a LiveServer is compiled with the program.
#ifndef HARNESS_SRC_CLI_RUN_PROGRAM_H
#define HARNESS_SRC_CLI_RUN_PROGRAM_H

#include <unistd.h>

#include <memory>
#include <ostream>

#include "harness/cli/commands.h"
#ifdef KESTREL_HAVE_LIVE
#include "live/live_server.h"
#endif

namespace harness {

#ifdef KESTREL_HAVE_LIVE
// After the run: the live view's counters, then the page stays served for
// --live-linger s (it shows the end and links the report; not when nothing
// ran, nor after Ctrl-C).
inline void end_live_view(LiveServer& live, const RunCommand& c, int code, std::ostream& out)
{
  const LiveCounters n = live.counters();
  out << "live view: " << n.published << " frames published, " << n.dropped_busy + n.dropped_unread << " dropped ("
      << n.dropped_busy << " while a page read, " << n.dropped_unread << " unread); " << n.commands_applied
      << " commands applied, " << n.commands_refused << " refused; " << n.requests_unauthorised
      << " requests without the token and " << n.requests_refused << " too large or compressed refused unread; "
      << n.connections << " connections (" << n.connections_closed << " closed idle, slow or at the limit); paused "
      << n.paused_s << " s of wall time; waited " << n.waited_s << " s for a page" << std::endl;
  if (c.live.linger > 0 && c.stop->load() == 0 && (code == kExitOk || code == kExitRunFailed)) {
    out << "live view: the page stays at " << live.url() << " for " << c.live.linger << " s (Ctrl-C ends it)"
        << std::endl;
    live.linger(c.live.linger, c.stop);
  }
}

// cmd_run with the live view of c.live served while the run goes.
inline int cmd_run_live(RunCommand c, std::ostream& out, std::ostream& err)
{
  LiveOptions lo;
  lo.host = c.live.host;
  lo.port = c.live.port;
  lo.start_paused = c.live.paused;
  lo.wait_unpaced = c.live.wait >= 0.0 ? c.live.wait : LiveServer::kDefaultPageWait;
  lo.wait_paced = c.live.wait >= 0.0 ? c.live.wait : 0.0;
  std::unique_ptr<LiveServer> live;
  try {
    live = std::make_unique<LiveServer>(lo);
  } catch (const std::exception& e) {
    err << "kestrel: " << e.what() << "\n";
    return kExitUsage;
  }
  out << "live view: " << live->url() << std::endl;
  const double wait = c.realtime ? lo.wait_paced : lo.wait_unpaced;
  if (wait > 0.0 && !lo.start_paused)
    out << "live view: the run waits at t = 0 for a page to connect, at most " << wait << " s (--live-wait)"
        << std::endl;
  c.control = live.get();
  const int code = cmd_run(c, out, err);
  end_live_view(*live, c, code, out);
  return code;
}
#endif

// `kestrel run`: a progress bar on a terminal, SIGINT/SIGTERM stop the run
// (stop_on_signals), the live view when asked (--live).
inline int cmd_run_program(RunCommand c, std::ostream& out, std::ostream& err)
{
  c.progress = isatty(STDERR_FILENO) != 0;
  c.stop = stop_on_signals();
  if (!c.live.on) return cmd_run(c, out, err);
#ifdef KESTREL_HAVE_LIVE
  return cmd_run_live(c, out, err);
#else
  err << "kestrel: this build has no live view (cpp-httplib was missing at build time)\n";
  return kExitUsage;
#endif
}

}  // namespace harness

#endif  // HARNESS_SRC_CLI_RUN_PROGRAM_H
