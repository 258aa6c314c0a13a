// mc_shard_read.cpp: the readers of a shard's mc_manifest.json and
// mc_runs.json and the hashes the manifest carries (mc_validate.h).  Pure
// text to values: fuzzed alone (test/fuzz/harness, fuzz_mc_manifest and
// fuzz_mc_records).
#include "mc/mc_validate.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>

#include "scenario/scenario_limits.h"
#include "sim/rng.h"

namespace harness {

using json = nlohmann::json;

namespace {

constexpr size_t kMaxDepth = 64;            // [-] JSON nesting of a manifest or records file
constexpr size_t kMaxOverrides = 4096;      // [-] --set overrides of a campaign

[[noreturn]] void refuse(const std::string& file, const std::string& field, const std::string& message)
{
  throw McShardError(file, field, message);
}

// Nesting deeper than kMaxDepth is refused before parsing (no recursion
// on hostile text: comparing, dumping and freeing a json recurse).
void check_depth(const std::string& text, const std::string& file)
{
  size_t depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) refuse(file, "(text)", "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

json parse(const std::string& text, const std::string& file)
{
  check_depth(text, file);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    refuse(file, "(text)", std::string("not JSON: ") + e.what());
  }
}

const json& member(const json& obj, const char* key, const std::string& file, const std::string& prefix = "")
{
  const auto it = obj.find(key);
  if (it == obj.end()) refuse(file, prefix + key, "missing");
  return *it;
}

std::string not_a(const char* what, const json& v) { return std::string("must be ") + what + ", not " + v.type_name(); }

uint64_t as_u64(const json& v, const std::string& file, const std::string& field)
{
  if (!v.is_number_unsigned()) refuse(file, field, not_a("a non-negative integer", v));
  return v.get<uint64_t>();
}

bool as_bool(const json& v, const std::string& file, const std::string& field)
{
  if (!v.is_boolean()) refuse(file, field, not_a("true or false", v));
  return v.get<bool>();
}

std::string as_string(const json& v, const std::string& file, const std::string& field, size_t max_bytes)
{
  if (!v.is_string()) refuse(file, field, not_a("a string", v));
  const std::string& s = v.get_ref<const std::string&>();
  if (s.size() > max_bytes) refuse(file, field, "longer than " + std::to_string(max_bytes) + " bytes");
  return s;
}

const json& as_array(const json& v, const std::string& file, const std::string& field)
{
  if (!v.is_array()) refuse(file, field, not_a("an array", v));
  return v;
}

bool is_hash_text(const std::string& s)
{
  return s.size() == 16 && s.find_first_not_of("0123456789abcdef") == std::string::npos;
}


void read_partition(const json& p, const std::string& file, McShardManifest& m)
{
  if (p.is_null()) return;
  if (!p.is_object()) refuse(file, "partition", not_a("null or an object", p));
  m.partitioned = true;
  m.shards = as_u64(member(p, "shards", file, "partition."), file, "partition.shards");
  m.shard = as_u64(member(p, "shard", file, "partition."), file, "partition.shard");
  if (m.shards < 1 || m.shards > 100000) refuse(file, "partition.shards", "must be in [1, 100000]");
  if (m.shard >= m.shards) refuse(file, "partition.shard", "must be below partition.shards");
}

void read_only(const json& a, const std::string& file, McShardManifest& m)
{
  as_array(a, file, "only");
  if (a.size() > m.runs) refuse(file, "only", "lists more runs than the campaign has");
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string f = "only[" + std::to_string(i) + "]";
    const uint64_t k = as_u64(a[i], file, f);
    if (k >= m.runs) refuse(file, f, "run " + std::to_string(k) + " is beyond the campaign's runs");
    if (!m.only.empty() && k <= m.only.back()) refuse(file, f, "not in increasing order");
    m.only.push_back(k);
  }
}

void read_record_hashes(const json& a, const std::string& file, McShardManifest& m)
{
  as_array(a, file, "record_fnv1a64");
  if (a.size() != m.runs_done)
    refuse(file, "record_fnv1a64", "holds " + std::to_string(a.size()) + " hashes for runs_done = " +
                                       std::to_string(m.runs_done) + " records");
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string f = "record_fnv1a64[" + std::to_string(i) + "]";
    if (!a[i].is_array() || a[i].size() != 2) refuse(file, f, "must be [run index, hash]");
    const uint64_t k = as_u64(a[i][0], file, f + "[0]");
    const std::string h = as_string(a[i][1], file, f + "[1]", 16);
    if (k >= m.runs) refuse(file, f + "[0]", "run " + std::to_string(k) + " is beyond the campaign's runs");
    if (!is_hash_text(h)) refuse(file, f + "[1]", "must be 16 lowercase hex digits");
    m.record_hashes.emplace_back(k, h);
  }
}

void read_scenario(const json& j, const std::string& file, McShardManifest& m)
{
  m.scenario = member(j, "scenario", file);
  if (!m.scenario.is_object()) refuse(file, "scenario", not_a("an object", m.scenario));
  m.scenario_hash = as_string(member(j, "scenario_fnv1a64", file), file, "scenario_fnv1a64", 16);
  if (!is_hash_text(m.scenario_hash)) refuse(file, "scenario_fnv1a64", "must be 16 lowercase hex digits");
  if (mc_scenario_hash(m.scenario) != m.scenario_hash)
    refuse(file, "scenario", "does not match the manifest's scenario_fnv1a64 (changed after the campaign wrote it)");
}

}  // namespace

McShardManifest read_mc_manifest(const std::string& text, const std::string& file)
{
  const json j = parse(text, file);
  if (!j.is_object()) refuse(file, "(text)", not_a("an object", j));
  McShardManifest m;
  const uint64_t format = as_u64(member(j, "kestrel_mc_manifest", file), file, "kestrel_mc_manifest");
  if (format != static_cast<uint64_t>(kMcManifestFormat))
    refuse(file, "kestrel_mc_manifest",
           "format " + std::to_string(format) + ", this kestrel reads format " + std::to_string(kMcManifestFormat) +
               (format < static_cast<uint64_t>(kMcManifestFormat) ? " (written before manifests carried hashes: rerun the shard)" : ""));
  as_string(member(j, "kestrel_version", file), file, "kestrel_version", 256);
  m.source = as_string(member(j, "source", file), file, "source", 4096);
  const json& ov = as_array(member(j, "overrides", file), file, "overrides");
  if (ov.size() > kMaxOverrides) refuse(file, "overrides", "more than " + std::to_string(kMaxOverrides));
  for (size_t i = 0; i < ov.size(); ++i)  // each parsed as key=value by read_mc_shards
    m.overrides.push_back(as_string(ov[i], file, "overrides[" + std::to_string(i) + "]", 65536));
  m.master_seed = as_u64(member(j, "master_seed", file), file, "master_seed");
  m.runs = as_u64(member(j, "runs", file), file, "runs");
  if (m.runs < 1 || m.runs > kMaxMcRuns) refuse(file, "runs", "must be in [1, " + std::to_string(kMaxMcRuns) + "]");
  read_partition(member(j, "partition", file), file, m);
  read_only(member(j, "only", file), file, m);
  m.complete = as_bool(member(j, "complete", file), file, "complete");
  m.runs_done = as_u64(member(j, "runs_done", file), file, "runs_done");
  if (m.runs_done > m.runs) refuse(file, "runs_done", "exceeds the campaign's runs");
  if (!m.only.empty() && m.runs_done > m.only.size()) refuse(file, "runs_done", "exceeds the runs listed in `only`");
  if (j.contains("merged_from")) {
    const json& mf = as_array(j.at("merged_from"), file, "merged_from");
    for (size_t i = 0; i < mf.size(); ++i) as_string(mf[i], file, "merged_from[" + std::to_string(i) + "]", 4096);
  }
  read_scenario(j, file, m);
  read_record_hashes(member(j, "record_fnv1a64", file), file, m);
  return m;
}

McRecordShape mc_record_shape(const McPlan& plan)
{
  McRecordShape s;
  s.runs = plan.runs;
  s.drawn = plan.drawn.size();
  s.metrics = plan.metrics.size();
  s.series = plan.series_rows.size() * plan.series_columns.size();
  return s;
}

namespace {

// An array of exactly n numbers or nulls (NaN); floats: within float range.
template <class T>
std::vector<T> read_values(const json& a, size_t n, const std::string& file, const std::string& field)
{
  as_array(a, file, field);
  if (a.size() != n)
    refuse(file, field, "has " + std::to_string(a.size()) + " values, the campaign records " + std::to_string(n));
  std::vector<T> v;
  v.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const json& x = a[i];
    if (x.is_null()) {
      v.push_back(std::numeric_limits<T>::quiet_NaN());
      continue;
    }
    if (!x.is_number()) refuse(file, field + "[" + std::to_string(i) + "]", not_a("a number or null", x));
    const double d = x.get<double>();
    if (!std::isfinite(d) || (sizeof(T) == sizeof(float) && std::fabs(d) > FLT_MAX))
      refuse(file, field + "[" + std::to_string(i) + "]", "out of range");
    v.push_back(static_cast<T>(d));
  }
  return v;
}

McRecord read_record(const json& x, const std::string& file, const std::string& f, const McRecordShape& shape)
{
  if (!x.is_object()) refuse(file, f, not_a("an object", x));
  McRecord r;
  r.index = as_u64(member(x, "index", file, f + "."), file, f + ".index");
  if (r.index >= shape.runs)
    refuse(file, f + ".index", "run " + std::to_string(r.index) + " in a campaign of " + std::to_string(shape.runs) + " runs");
  r.seed = as_u64(member(x, "seed", file, f + "."), file, f + ".seed");
  r.invalid = as_bool(member(x, "invalid", file, f + "."), file, f + ".invalid");
  r.complete = as_bool(member(x, "complete", file, f + "."), file, f + ".complete");
  r.pass = as_bool(member(x, "pass", file, f + "."), file, f + ".pass");
  r.full = as_bool(member(x, "full", file, f + "."), file, f + ".full");
  r.reason = as_string(member(x, "reason", file, f + "."), file, f + ".reason", kMaxMcReason);
  r.drawn = read_values<double>(member(x, "drawn", file, f + "."), shape.drawn, file, f + ".drawn");
  r.metrics = read_values<double>(member(x, "metrics", file, f + "."), shape.metrics, file, f + ".metrics");
  r.series = read_values<float>(member(x, "series", file, f + "."), shape.series, file, f + ".series");
  const json& w = member(x, "wall_seconds", file, f + ".");
  if (!w.is_number()) refuse(file, f + ".wall_seconds", not_a("a number", w));
  r.wall_seconds = w.get<double>();
  if (!(r.wall_seconds >= 0.0 && r.wall_seconds < 1e12)) refuse(file, f + ".wall_seconds", "out of range");
  return r;
}

}  // namespace

std::vector<McRecord> read_mc_records(const std::string& text, const std::string& file, const McRecordShape& shape)
{
  const json j = parse(text, file);
  if (!j.is_object()) refuse(file, "(text)", not_a("an object", j));
  if (as_u64(member(j, "kestrel_mc_runs", file), file, "kestrel_mc_runs") != 1)
    refuse(file, "kestrel_mc_runs", "format unknown to this kestrel (it reads 1)");
  const json& a = as_array(member(j, "records", file), file, "records");
  if (a.size() > shape.runs) refuse(file, "records", "more records than the campaign's runs");
  std::vector<McRecord> out;
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) out.push_back(read_record(a[i], file, "records[" + std::to_string(i) + "]", shape));
  return out;
}

std::string mc_scenario_hash(const json& scenario) { return hex64(sim::fnv1a64(scenario.dump())); }

namespace {
// A record's canonical bytes: the integers and flags, the reason's length
// and text, every value's IEEE-754 bits (any NaN or infinity as one quiet
// NaN: mc_runs.json writes them as null).  Not the wall-clock time.
template <class T>
void put(std::string& b, T v)
{
  char c[sizeof(T)];
  std::memcpy(c, &v, sizeof(T));
  b.append(c, sizeof(T));
}
template <class T>
void put_values(std::string& b, const std::vector<T>& v)
{
  put<uint64_t>(b, v.size());
  for (T x : v) put<T>(b, std::isfinite(x) ? x : std::numeric_limits<T>::quiet_NaN());
}
}  // namespace

std::string mc_record_hash(const McRecord& r)
{
  std::string b;
  put<uint64_t>(b, r.index);
  put<uint64_t>(b, r.seed);
  b += static_cast<char>((r.invalid ? 1 : 0) | (r.complete ? 2 : 0) | (r.pass ? 4 : 0) | (r.full ? 8 : 0));
  put<uint64_t>(b, r.reason.size());
  b += r.reason;
  put_values(b, r.drawn);
  put_values(b, r.metrics);
  put_values(b, r.series);
  return hex64(sim::fnv1a64(b));
}

json mc_record_hashes(const std::vector<McRecord>& records)
{
  json a = json::array();
  for (const McRecord& r : records) a.push_back(json::array({r.index, mc_record_hash(r)}));
  return a;
}

}  // namespace harness
