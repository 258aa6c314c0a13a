// mc_journal: a campaign's finished runs, kept on disk as they finish
// (docs/monte-carlo.md, "Interrupted campaigns, --resume").
//
// Each finished run's record goes to records/NNNNNN.json in the campaign's
// working folder: written to a temporary file, flushed to the disk (fsync),
// renamed into place and the folder flushed, so a campaign killed at any
// point (SIGKILL, power loss) keeps every record it finished, whole, and
// none half-written.  A record file has the form of mc_runs.json holding
// one record.  The journal is what `kestrel mc --resume` starts from, and
// what the summary files are written from (one record in memory at a time).
#ifndef HARNESS_MC_JOURNAL_H
#define HARNESS_MC_JOURNAL_H

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/mc/monte_carlo.h"

namespace harness {

// dir/records/NNNNNN.json
std::filesystem::path mc_record_path(const std::filesystem::path& dir, uint64_t index);

// `text` into `path` durably: a temporary file beside it, fsync, rename,
// fsync of the folder.  Throws OutputError.
void write_file_durably(const std::filesystem::path& path, const std::string& text);

// Run r's record into dir/records (replacing an earlier one of the same run).
void write_mc_record(const std::filesystem::path& dir, const McRecord& r);

// The record in `file` (throws std::runtime_error naming the file).
McRecord read_mc_record(const std::filesystem::path& file);

// The runs with a record in dir/records, sorted (temporary files skipped).
std::vector<uint64_t> mc_journal_indices(const std::filesystem::path& dir);

// dir/records removed (once the summary holds every record).
void remove_mc_journal(const std::filesystem::path& dir);

// What the summary and the outcome need of a run, without its values.
McRunState mc_run_state(const McRecord& r);

// The records of a journal, read one at a time (McRecordSource).
class McJournalRecords : public McRecordSource {
 public:
  // states: the runs to read, sorted by index (each has a record in dir)
  McJournalRecords(std::filesystem::path dir, std::vector<McRunState> states)
      : dir_(std::move(dir)), states_(std::move(states)) {}
  size_t size() const override { return states_.size(); }
  const McRunState& state(size_t i) const override { return states_[i]; }
  McRecord record(size_t i) const override { return read_mc_record(mc_record_path(dir_, states_[i].index)); }

 private:
  std::filesystem::path dir_;
  std::vector<McRunState> states_;
};

}  // namespace harness

#endif  // HARNESS_MC_JOURNAL_H
