// scenario_rates.cpp: `rates` (the base tick and the rate-group divisors).
#include <cmath>

#include "scenario_schema.h"

namespace harness::schema {

namespace {
// dt is a whole number of nanoseconds (the tick clock counts them).
std::string whole_ns(double& dt)
{
  const double ns = dt * 1e9;
  const double rounded = std::round(ns);
  if (rounded < 1.0 || std::fabs(ns - rounded) > 1e-6 * std::max(1.0, rounded))
    return "must be a whole number of nanoseconds (>= 1 ns), got " + fmt(dt) + " s";
  dt = rounded * 1e-9;
  return "";
}
}  // namespace

const Section& rates_section()
{
  static const Section s{
      "rates",
      {
          real("dt", [](auto& sc, size_t) -> auto& { return sc.rates.dt; })
              .req("plant step [s]").bounds(positive("s")).then(whole_ns).unit("s"),
          integer("fsw_divisor", 1, kMaxDivisor, [](auto& sc, size_t) -> auto& { return sc.rates.fsw_divisor; })
              .unit("ticks"),
          integer("fsw_offset", 0, kMaxDivisor, [](auto& sc, size_t) -> auto& { return sc.rates.fsw_offset; })
              .unit("ticks"),
          integer("record_divisor", 1, kMaxDivisor, [](auto& sc, size_t) -> auto& { return sc.rates.record_divisor; })
              .unit("ticks"),
          integer("thruster_divisor", 1, kMaxDivisor,
                  [](auto& sc, size_t) -> auto& { return sc.rates.thruster_divisor; })
              .unit("ticks"),
      },
      {}};
  return s;
}

void read_rates(MapReader r, Scenario& sc)
{
  read_keys(r, rates_section(), sc);
  if (r.has("fsw_offset") && sc.rates.fsw_offset >= sc.rates.fsw_divisor) {
    r.error_at("fsw_offset", "must be < fsw_divisor (" + std::to_string(sc.rates.fsw_divisor) + ")");
    sc.rates.fsw_offset = 0;
  }
  r.finish();
}

}  // namespace harness::schema
