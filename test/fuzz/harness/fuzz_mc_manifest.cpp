// libFuzzer harness: a shard's mc_manifest.json -> read_mc_manifest (what
// `kestrel mc merge` reads first, docs/monte-carlo.md "What merge checks").
// Either a refusal naming the file and the field, or a manifest whose
// fields hold what the reader promises: runs in [1, 10^7], runs_done <=
// runs, one hash per record, a partition and `only` list inside the
// campaign, the scenario an object matching its hash.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_mc_common.h"
#include "scenario/scenario_limits.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string file = "shard/mc_manifest.json";
  harness::McShardManifest m;
  try {
    m = harness::read_mc_manifest(text, file);
  } catch (const harness::McShardError& e) {
    kestrel_fuzz::check_refusal(e, file);
    return 0;
  }
  if (m.runs < 1 || m.runs > harness::kMaxMcRuns || m.runs_done > m.runs) kestrel_fuzz::finding("runs out of range");
  if (m.record_hashes.size() != m.runs_done) kestrel_fuzz::finding("hashes != runs_done");
  for (const auto& h : m.record_hashes)
    if (h.first >= m.runs || !kestrel_fuzz::is_hash(h.second)) kestrel_fuzz::finding("a bad record hash entry");
  if (m.partitioned && (m.shards < 1 || m.shard >= m.shards)) kestrel_fuzz::finding("a bad partition");
  if (!std::is_sorted(m.only.begin(), m.only.end()) || (!m.only.empty() && m.only.back() >= m.runs))
    kestrel_fuzz::finding("a bad only list");
  if (!m.scenario.is_object() || harness::mc_scenario_hash(m.scenario) != m.scenario_hash)
    kestrel_fuzz::finding("a scenario not matching its hash");
  return 0;
}
