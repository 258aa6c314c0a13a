// libFuzzer harness: a shard's mc_runs.json -> read_mc_records for a
// campaign of 6 runs, 3 drawn values, 4 metrics and 6 series samples per
// record (the seeds have that shape).  Either a refusal naming the file and
// the field, or records of exactly that shape, indices below 6, values
// finite or NaN (series within float range), a reason within its bound,
// and each record's hash computable.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_mc_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string file = "shard/mc_runs.json";
  harness::McRecordShape shape;
  shape.runs = 6;
  shape.drawn = 3;
  shape.metrics = 4;
  shape.series = 6;
  std::vector<harness::McRecord> recs;
  try {
    recs = harness::read_mc_records(text, file, shape);
  } catch (const harness::McShardError& e) {
    kestrel_fuzz::check_refusal(e, file);
    return 0;
  }
  if (recs.size() > shape.runs) kestrel_fuzz::finding("more records than runs");
  for (const harness::McRecord& r : recs) {
    if (r.index >= shape.runs || r.drawn.size() != shape.drawn || r.metrics.size() != shape.metrics ||
        r.series.size() != shape.series || r.reason.size() > harness::kMaxMcReason)
      kestrel_fuzz::finding("a record outside its shape");
    for (double v : r.drawn)
      if (std::isinf(v)) kestrel_fuzz::finding("an infinite drawn value");
    for (double v : r.metrics)
      if (std::isinf(v)) kestrel_fuzz::finding("an infinite metric");
    for (float v : r.series)
      if (std::isinf(v)) kestrel_fuzz::finding("an infinite series sample");
    if (!(r.wall_seconds >= 0.0)) kestrel_fuzz::finding("a negative wall time");
    if (!kestrel_fuzz::is_hash(harness::mc_record_hash(r))) kestrel_fuzz::finding("a record without a hash");
  }
  return 0;
}
