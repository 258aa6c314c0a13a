// mc_validate: what `kestrel mc merge` reads from shards it did not write,
// checked field by field against the campaign (docs/monte-carlo.md, "What
// merge checks").  Private to the harness library.
//
//   read_mc_manifest / read_mc_records   types, sizes and ranges of every
//                                        field of mc_manifest.json / mc_runs.json
//   check_mc_shard                       the records against the campaign's
//                                        plan: indices, partition, seeds and
//                                        draws, pass/fail, the manifest's hashes
//   copy_mc_runs                         a shard's runs/ copied, no link followed
//
// Every refusal is an McShardError naming the file and the field.
#ifndef HARNESS_SRC_MC_VALIDATE_H
#define HARNESS_SRC_MC_VALIDATE_H

#include <cstdint>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/mc/monte_carlo.h"

namespace harness {

// Version of mc_manifest.json's layout: 2 carries the hashes.
constexpr int kMcManifestFormat = 2;
constexpr size_t kMaxMcReason = 65536;  // [B] a record's reason

class McShardError : public std::runtime_error {
 public:
  McShardError(const std::string& file, const std::string& field, const std::string& message)
      : std::runtime_error(file + ": " + field + ": " + message), file_(file), field_(field)
  {
  }
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_, field_;
};

// mc_manifest.json, every field typed and in range.
struct McShardManifest {
  std::string source;
  std::vector<std::string> overrides;
  uint64_t master_seed = 0;
  uint64_t runs = 0;
  bool partitioned = false;
  uint64_t shard = 0, shards = 1;
  std::vector<uint64_t> only;  // sorted, unique, < runs
  bool complete = false;
  uint64_t runs_done = 0;
  nlohmann::json scenario;     // an object
  std::string scenario_hash;   // mc_scenario_hash of it, as written
  std::vector<std::pair<uint64_t, std::string>> record_hashes;  // (index, mc_record_hash), as written
};
McShardManifest read_mc_manifest(const std::string& text, const std::string& file);

// What the campaign's records hold: runs, and per record the number of
// drawn values, metrics and thinned series samples.
struct McRecordShape {
  uint64_t runs = 0;
  size_t drawn = 0, metrics = 0, series = 0;
};
McRecordShape mc_record_shape(const McPlan& plan);

// mc_runs.json, every record typed and sized to `shape`, indices < runs.
std::vector<McRecord> read_mc_records(const std::string& text, const std::string& file, const McRecordShape& shape);

// The hashes the manifest carries: 64-bit FNV-1a, as 16 hex digits, of the
// scenario object's compact JSON text, and of a record's fields but its
// wall-clock time.  They tell a record or scenario changed or mixed up
// after the campaign wrote it; they are not a signature.
std::string mc_scenario_hash(const nlohmann::json& scenario);
std::string mc_record_hash(const McRecord& r);
nlohmann::json mc_record_hashes(const std::vector<McRecord>& records);

// One shard's records against the campaign (plan and the manifest's
// partition, `only` list and hashes): throws McShardError naming
// `runs_file` (a record) or `manifest_file` (the manifest).
void check_mc_shard(const McPlan& plan, const McShardManifest& m, const std::vector<McRecord>& records,
                    const std::string& manifest_file, const std::string& runs_file);

// A file of a shard, read without following a link (O_NOFOLLOW, a regular
// file of at most max_bytes).  Throws McShardError.
std::string read_shard_file(const std::filesystem::path& p, uint64_t max_bytes);

// The shard's runs/ into `to`: only folders named NNNNNN of the given run
// indices, holding regular files and folders; a link or any other entry
// anywhere is refused (McShardError naming it), none is followed.
void copy_mc_runs(const std::filesystem::path& shard, const std::set<uint64_t>& indices,
                  const std::filesystem::path& to);

// The shards of one campaign, read and checked as a whole: every manifest
// and record as above, the same campaign (scenario, master seed, runs),
// complete, every run (of the `only` list) in exactly one shard, and each
// shard's runs/ walked (nothing copied yet).  Throws McShardError, or
// ScenarioError when the manifests' scenario is not a valid campaign.
struct McShards {
  McShardManifest first;                  // the first shard's manifest
  McPlan plan;                            // the campaign, from it
  std::vector<McRecord> records;          // every shard's, by index
  std::vector<uint64_t> only;             // an `only` campaign's runs; empty: all
  std::vector<std::set<uint64_t>> runs;   // per shard: its run indices
};
McShards read_mc_shards(const std::vector<std::string>& shards);

}  // namespace harness

#endif  // HARNESS_SRC_MC_VALIDATE_H
