// magnetorquer_drive.cpp: the PWM drive of the magnetorquer rods.
#include "core/magnetorquer_drive.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace harness {

MtqPwmDriver::MtqPwmDriver(sim::MagneticEffector& mag, int64_t period_ns) : mag_(mag), period_ns_(period_ns)
{
  if (period_ns_ <= 0) throw std::invalid_argument("magnetorquer_drive.pwm_period must be > 0");
}

void MtqPwmDriver::command(const sim::MagnetorquerArray& m_cmd, int64_t t_ns)
{
  start_ns_ = t_ns;
  for (int i = 0; i < mag_.num_rods(); ++i) {
    const auto u = static_cast<size_t>(i);
    const double m_max = mag_.rod(i).params().m_max;
    const double c = std::isfinite(m_cmd[u]) ? m_cmd[u] : 0.0;
    const double duty = std::min(std::fabs(c) / m_max, 1.0);
    on_ns_[u] = static_cast<int64_t>(std::llround(duty * static_cast<double>(period_ns_)));
    level_[u] = c > 0.0 ? m_max : c < 0.0 ? -m_max : 0.0;
  }
}

void MtqPwmDriver::at_instant(int64_t t_ns)
{
  if (start_ns_ < 0 || t_ns < start_ns_) return;
  const int64_t phase = (t_ns - start_ns_) % period_ns_;
  for (int i = 0; i < mag_.num_rods(); ++i) {
    const auto u = static_cast<size_t>(i);
    out_[u] = phase < on_ns_[u] ? level_[u] : 0.0;
  }
  mag_.command_dipoles(out_);  // failed and stuck rods ignore theirs
}

int64_t MtqPwmDriver::next_cut_ns(int64_t t_ns) const
{
  int64_t cut = std::numeric_limits<int64_t>::max();
  if (start_ns_ < 0 || t_ns < start_ns_) return cut;
  const int64_t cycle = t_ns - (t_ns - start_ns_) % period_ns_;
  bool switching = false;
  for (int i = 0; i < mag_.num_rods(); ++i) {
    const int64_t on = on_ns_[static_cast<size_t>(i)];
    if (on <= 0 || on >= period_ns_) continue;  // on or off for the whole cycle
    switching = true;
    if (cycle + on > t_ns) cut = std::min(cut, cycle + on);
  }
  return switching ? std::min(cut, cycle + period_ns_) : cut;
}

}  // namespace harness
