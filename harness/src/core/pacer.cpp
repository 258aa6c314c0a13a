// pacer.cpp: absolute-deadline pacing on CLOCK_MONOTONIC (pacer.h).
#include "harness/core/pacer.h"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace harness {

namespace {

int64_t now_ns()
{
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

void sleep_until(int64_t t_ns)
{
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t_ns / 1000000000LL);
  ts.tv_nsec = static_cast<long>(t_ns % 1000000000LL);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

constexpr double kMaxDeadlineNs = 1e18;  // 31 years from t0: "never", and far from int64's end

int bin_of(int64_t late_ns)
{
  const double s = static_cast<double>(late_ns) * 1e-9;
  if (s <= Pacer::kFirstEdge) return 0;
  const int b = static_cast<int>(std::ceil(std::log10(s / Pacer::kFirstEdge) * Pacer::kBinsPerDecade - 1e-9));
  return b >= Pacer::kBins - 1 ? Pacer::kBins - 1 : b;
}

}  // namespace

double pacer_bin_edge(int b)
{
  if (b >= Pacer::kBins - 1) return std::numeric_limits<double>::infinity();
  return Pacer::kFirstEdge * std::pow(10.0, static_cast<double>(b) / Pacer::kBinsPerDecade);
}

std::string Pacer::check_scale(double scale)
{
  if (scale >= kMinScale && scale <= kMaxScale) return "";
  return "a real-time scale is in [1e-6, 1e6] (times real time)";
}

Pacer::Pacer(uint64_t tick_ns, double scale) : tick_ns_(tick_ns), scale_(scale)
{
  if (tick_ns == 0) throw std::invalid_argument("pacing needs a tick > 0");
  const std::string why = check_scale(scale);
  if (!why.empty()) throw std::invalid_argument("pacing: " + why);
}

std::string Pacer::request_realtime()
{
  sched_param sp{};
  sp.sched_priority = 50;
  const bool fifo = sched_setscheduler(0, SCHED_FIFO, &sp) == 0;
  const int fifo_err = errno;
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  const int lock_err = errno;
  rt_ = fifo && locked;
  if (rt_) return "";
  std::string w = "real-time pacing without";
  if (!fifo) w += std::string(" SCHED_FIFO (") + std::strerror(fifo_err) + ")";
  if (!fifo && !locked) w += " and without";
  if (!locked) w += std::string(" locked memory (") + std::strerror(lock_err) + ")";
  return w + ": lateness may be larger; run as root or grant CAP_SYS_NICE and CAP_IPC_LOCK";
}

void Pacer::restart(double scale)
{
  const std::string why = check_scale(scale);
  if (!why.empty()) throw std::invalid_argument("pacing: " + why);
  scale_ = scale;
  t0_ns_ = -1;  // wait_for fixes it again
}

int64_t Pacer::deadline_ns(uint64_t k) const
{
  // t0 is a monotonic time (years at most) and the offset is held at 1e18:
  // the sum stays far inside int64
  const double off = std::min(static_cast<double>(k) * static_cast<double>(tick_ns_) / scale_, kMaxDeadlineNs);
  return t0_ns_ + static_cast<int64_t>(std::llround(off));
}

bool Pacer::wait_for(uint64_t k)
{
  if (t0_ns_ < 0) {  // the first paced tick is due now
    t0_ns_ = 0;
    t0_ns_ = now_ns() - deadline_ns(k);
  }
  const int64_t d = deadline_ns(k);
  const int64_t slice = static_cast<int64_t>(kSlice * 1e9);
  for (int64_t now = now_ns(); now < d; now = now_ns()) {
    if (stop_ && stop_->load() != 0) return false;
    sleep_until(stop_ && d - now > slice ? now + slice : d);
  }
  const int64_t late = now_ns() - d;
  last_late_ns_ = late > 0 ? late : 0;
  if (last_late_ns_ > max_late_ns_) max_late_ns_ = last_late_ns_;
  hist_[static_cast<size_t>(bin_of(last_late_ns_))]++;
  ++ticks_;
  return true;
}

double Pacer::seconds_to(uint64_t k) const
{
  if (t0_ns_ < 0) return std::numeric_limits<double>::infinity();
  return static_cast<double>(deadline_ns(k) - now_ns()) * 1e-9;
}

void Pacer::done(uint64_t k)
{
  if (now_ns() > deadline_ns(k + 1)) ++overruns_;
}

uint64_t Pacer::take_new_overruns()
{
  const uint64_t n = overruns_ - reported_overruns_;
  reported_overruns_ = overruns_;
  return n;
}

PacingStats Pacer::stats() const
{
  PacingStats s;
  s.scale = scale_;
  s.ticks = ticks_;
  s.overruns = overruns_;
  s.lateness_max_s = static_cast<double>(max_late_ns_) * 1e-9;
  s.drift_s = static_cast<double>(last_late_ns_) * 1e-9;
  s.realtime_priority = rt_;
  auto percentile = [this](double q) {
    if (ticks_ == 0) return 0.0;
    const uint64_t want = static_cast<uint64_t>(std::ceil(q * static_cast<double>(ticks_)));
    uint64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += hist_[static_cast<size_t>(b)];
      if (seen >= want) return std::min(pacer_bin_edge(b), static_cast<double>(max_late_ns_) * 1e-9);
    }
    return static_cast<double>(max_late_ns_) * 1e-9;
  };
  s.lateness_p50_s = percentile(0.5);
  s.lateness_p99_s = percentile(0.99);
  return s;
}

}  // namespace harness
