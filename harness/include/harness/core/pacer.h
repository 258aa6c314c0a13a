// pacer: runs ticks against the wall clock (real time, or a multiple of it)
// for hardware-in-the-loop and for watching a run.
//
// Tick k is released at the absolute deadline t0 + round(k * tick_ns /
// scale) on CLOCK_MONOTONIC (clock_nanosleep TIMER_ABSTIME): deadlines are
// computed from k, never by adding a step to the previous wake-up, so
// sleeping late never accumulates into drift.  Lateness = wake-up time -
// deadline, measured for every tick into a log-spaced histogram (10 bins per
// decade from 100 ns to 100 s, bounded memory for any duration; percentiles
// are reported as the upper edge of their bin, within 26 %), with the exact
// maximum.  An overrun is a tick whose work ends after the next tick's
// deadline.  With permission the process runs SCHED_FIFO with its memory
// locked (mlockall); without, a plain warning says so and it runs anyway.
//
// The scale is in [kMinScale, kMaxScale] (1e-6 to 1e6 times real time;
// outside it the constructor and restart() throw): a deadline past 10^18 ns
// (31 years) is held there, never overflowing.  With a stop flag
// (set_stop) the wait sleeps in slices of at most kSlice and returns as
// soon as the flag is set (a signal acts within kSlice whatever the scale).
#ifndef HARNESS_PACER_H
#define HARNESS_PACER_H

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace harness {

struct PacingStats {
  double scale = 0.0;            // real-time multiple (1: real time)
  uint64_t ticks = 0;            // ticks paced
  double lateness_p50_s = 0.0;   // [s] wake-up after deadline, median (bin upper edge)
  double lateness_p99_s = 0.0;   // [s] 99th percentile (bin upper edge)
  double lateness_max_s = 0.0;   // [s] exact maximum
  uint64_t overruns = 0;         // ticks whose work ended after the next deadline
  double drift_s = 0.0;          // [s] (wall time of the last tick - its deadline) at the end
  bool realtime_priority = false;  // SCHED_FIFO and mlockall granted
};

class Pacer {
 public:
  // scale > 0: ticks of tick_ns simulated ns take tick_ns / scale wall ns.
  Pacer(uint64_t tick_ns, double scale);
  // Asks for SCHED_FIFO and locked memory; returns "" or a warning.
  std::string request_realtime();
  static constexpr double kMinScale = 1e-6;
  static constexpr double kMaxScale = 1e6;
  static constexpr double kSlice = 0.05;  // [s] longest sleep without looking at the stop flag
  // "" when scale is a pacing scale, else why not (names the range).
  static std::string check_scale(double scale);
  // Sleeps until tick k's deadline (the first call fixes t0) and measures
  // the lateness.  false (nothing measured) when the stop flag was set
  // before the deadline.
  bool wait_for(uint64_t k);
  // A flag (a signal's number, 0: none) that ends a wait early.
  void set_stop(const std::atomic<int>* stop) { stop_ = stop; }
  // Marks the end of tick k's work (overrun accounting).
  void done(uint64_t k);
  // Wall time [s] left until tick k's deadline (negative: past it; +inf
  // before the first wait_for).  An FSW link bounds its waits with it.
  double seconds_to(uint64_t k) const;
  // Restarts the deadlines at `scale` (> 0): the next wait_for(k) is due at
  // once and later ticks follow from it (after a pause, or a new rate from
  // the live view).  The lateness histogram and the overruns are kept.
  void restart(double scale);
  double scale() const { return scale_; }
  // Overruns since the last call (for "cannot keep up" notices).
  uint64_t take_new_overruns();
  PacingStats stats() const;

  static constexpr int kBinsPerDecade = 10;
  static constexpr double kFirstEdge = 1e-7;  // [s] upper edge of the first bin
  static constexpr int kBins = 9 * kBinsPerDecade + 1;  // ... to 100 s, plus overflow

 private:
  int64_t deadline_ns(uint64_t k) const;
  uint64_t tick_ns_;
  double scale_;
  int64_t t0_ns_ = -1;
  uint64_t ticks_ = 0, overruns_ = 0, reported_overruns_ = 0;
  int64_t max_late_ns_ = 0, last_late_ns_ = 0;
  bool rt_ = false;
  const std::atomic<int>* stop_ = nullptr;
  std::array<uint64_t, kBins> hist_{};
};

// Upper edge [s] of histogram bin b (the last bin is unbounded: +inf).
double pacer_bin_edge(int b);

}  // namespace harness

#endif  // HARNESS_PACER_H
