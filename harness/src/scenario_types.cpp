// scenario_types.cpp: the parts of the Scenario types that a run needs
// without the YAML schema (harness_core): problems, tick arithmetic, names.
#include <cmath>

#include "harness/scenario.h"

namespace harness {

std::string ScenarioIssue::str() const
{
  std::string s = file;
  if (!where.empty()) s += ": " + where;
  else if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(column);
  return s + ": " + key + ": " + message;
}

namespace {
std::string join_issues(const std::vector<ScenarioIssue>& v)
{
  std::string s;
  for (const auto& is : v) s += (s.empty() ? "" : "\n") + is.str();
  return s;
}
}  // namespace

ScenarioError::ScenarioError(std::vector<ScenarioIssue> issues)
    : std::runtime_error(join_issues(issues)), issues_(std::move(issues))
{
}

uint64_t Scenario::tick_ns() const { return static_cast<uint64_t>(std::llround(rates.dt * 1e9)); }
uint64_t Scenario::num_ticks() const
{
  return static_cast<uint64_t>(std::llround(duration / rates.dt));
}

const char* to_string(FswMode m) { return m == FswMode::Inertial ? "inertial" : "sun_safe"; }
const char* to_string(RwMapMode m) { return m == RwMapMode::MinNorm ? "min_norm" : "power"; }
const char* to_string(ThrPulseMode m) { return m == ThrPulseMode::Remainder ? "remainder" : "schmitt"; }
const char* to_string(ThrTransient m) { return m == ThrTransient::Instant ? "instant" : "first_order"; }
const char* to_string(Actuation m) { return m == Actuation::Wheels ? "wheels" : "thrusters"; }
const char* to_string(ThrMapMode m) { return m == ThrMapMode::MinNorm ? "min_norm" : "nnls"; }
const char* wheel_model_key(sim::WheelModel m)
{
  switch (m) {
    case sim::WheelModel::Balanced: return "balanced";
    case sim::WheelModel::SimpleJitter: return "simple_jitter";
    case sim::WheelModel::FullyCoupled: return "fully_coupled";
  }
  return "balanced";
}

}  // namespace harness
