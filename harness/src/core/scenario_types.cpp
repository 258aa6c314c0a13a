// scenario_types.cpp: the parts of the Scenario types that a run needs
// without the YAML schema (harness_core): problems, tick arithmetic, names.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "harness/core/scenario_types.h"

namespace harness {

namespace {
// An issue is one line: every control byte is escaped, line feeds too.
bool is_control(unsigned char c) { return c < 0x20 || c == 0x7f; }

// Length of the valid UTF-8 sequence at s[i] (0: invalid).
size_t utf8_len(const std::string& s, size_t i)
{
  const unsigned char c = static_cast<unsigned char>(s[i]);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return 0;
  return n;
}

// The code point of the valid n-byte sequence at s[i].
uint32_t code_point(const std::string& s, size_t i, size_t n)
{
  const auto b = [&s, i](size_t k) { return static_cast<uint32_t>(static_cast<unsigned char>(s[i + k])); };
  if (n == 1) return b(0);
  uint32_t cp = b(0) & (0x7fu >> n);
  for (size_t k = 1; k < n; ++k) cp = (cp << 6) | (b(k) & 0x3fu);
  return cp;
}

// Shown escaped although valid: C1 controls, the format characters that
// reorder or hide text (bidirectional marks, embeddings, overrides and
// isolates, zero-width spaces and joiners, the byte-order mark) and the
// line and paragraph separators.  A message quoting user text then reads
// as it is stored: nothing in it reverses, hides or breaks the line.
bool is_hidden(uint32_t cp)
{
  return (cp >= 0x80 && cp <= 0x9f) || cp == 0xad || cp == 0x061c || cp == 0x180e || (cp >= 0x200b && cp <= 0x200f) ||
         (cp >= 0x2028 && cp <= 0x202e) || (cp >= 0x2060 && cp <= 0x2069) || cp == 0xfeff ||
         (cp >= 0xfff9 && cp <= 0xfffb);
}

}  // namespace

std::string escape_bytes(const std::string& s)
{
  std::string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8_len(s, i);
    if (n == 0 || (n == 1 && is_control(c))) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
      ++i;
    } else if (n > 1 && is_hidden(code_point(s, i, n))) {
      char buf[12];
      std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned>(code_point(s, i, n)));
      out += buf;
      i += n;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  return out;
}

std::string ScenarioIssue::str() const
{
  std::string s = file;
  if (!where.empty()) s += ": " + where;
  else if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(column);
  return escape_bytes(s + ": " + key + ": " + message);
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

bool Scenario::has_acs_thrusters() const
{
  for (const ThrusterSpec& t : thrusters)
    if (t.acs) return true;
  return false;
}

const char* to_string(FswMode m)
{
  switch (m) {
    case FswMode::Inertial: return "inertial";
    case FswMode::SunSafe: return "sun_safe";
    case FswMode::Detumble: return "detumble";
    default: return "nadir";
  }
}
const char* to_string(RwMapMode m) { return m == RwMapMode::MinNorm ? "min_norm" : "power"; }
const char* to_string(ThrPulseMode m) { return m == ThrPulseMode::Remainder ? "remainder" : "schmitt"; }
const char* to_string(ThrTransient m) { return m == ThrTransient::Instant ? "instant" : "first_order"; }
const char* to_string(Actuation m) { return m == Actuation::Wheels ? "wheels" : "thrusters"; }
const char* to_string(ThrMapMode m) { return m == ThrMapMode::MinNorm ? "min_norm" : "nnls"; }
const char* to_string(MtqDriveMode m) { return m == MtqDriveMode::Dipole ? "dipole" : "pwm"; }
const char* wheel_model_key(sim::WheelModel m)
{
  switch (m) {
    case sim::WheelModel::Balanced: return "balanced";
    case sim::WheelModel::SimpleJitter: return "simple_jitter";
    case sim::WheelModel::FullyCoupled: return "fully_coupled";
  }
  return "balanced";
}

const char* env_source_name(EnvSource s)
{
  switch (s) {
    case EnvSource::GravityGradient: return "gravity_gradient";
    case EnvSource::SolarPressure: return "solar_pressure";
    case EnvSource::Drag: return "drag";
    case EnvSource::Magnetic: return "magnetic";
  }
  return "gravity_gradient";
}

const EnvModelSpec& env_model(const EnvironmentSpec& e, EnvSource s)
{
  switch (s) {
    case EnvSource::GravityGradient: return e.gravity_gradient;
    case EnvSource::SolarPressure: return e.solar_pressure;
    case EnvSource::Drag: return e.drag;
    case EnvSource::Magnetic: return e.magnetic;
  }
  return e.gravity_gradient;
}

std::optional<sim::UtcEpoch> parse_utc_epoch(const std::string& text, std::string* why)
{
  sim::UtcEpoch e;
  int n = 0;
  char z = 0;
  const int got = std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%c%n", &e.year, &e.month, &e.day, &e.hour,
                              &e.minute, &e.second, &z, &n);
  if (got != 7 || z != 'Z' || static_cast<size_t>(n) != text.size() || text.size() < 20 || text[4] != '-' ||
      text[7] != '-' || text[13] != ':' || text[16] != ':') {
    *why = "expected a UTC date-time YYYY-MM-DDThh:mm:ssZ (seconds may have a fraction)";
    return std::nullopt;
  }
  try {
    sim::validate(e, "epoch");
  } catch (const std::invalid_argument& ex) {
    *why = ex.what();
    return std::nullopt;
  }
  return e;
}

}  // namespace harness
