// scenario_rates.cpp: `rates` (the base tick and the rate-group divisors).
#include <cmath>

#include "scenario/scenario_schema.h"

namespace harness::schema {

namespace {
constexpr uint32_t kMaxSubsteps = 10000;  // [-] dt / 10^4: finer than any jitter study needs

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
          integer("plant_substeps", 1, kMaxSubsteps, [](auto& sc, size_t) -> auto& { return sc.rates.plant_substeps; })
              .unit("-"),
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
  // The plant's sub-step is a whole number of nanoseconds too (the tick
  // clock and the thruster latch instants count them).
  const auto tick_ns = static_cast<uint64_t>(std::llround(sc.rates.dt * 1e9));
  if (r.has("plant_substeps") && tick_ns > 0 && tick_ns % sc.rates.plant_substeps != 0) {
    r.error_at("plant_substeps", "dt (" + std::to_string(tick_ns) + " ns) must be a whole number of sub-steps of whole nanoseconds (" +
                                     std::to_string(sc.rates.plant_substeps) + " does not divide it)");
    sc.rates.plant_substeps = 1;
  }
  r.finish();
}

}  // namespace harness::schema
