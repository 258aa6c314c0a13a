// mc_journal: a campaign's finished runs, kept on disk as they finish
// (docs/monte-carlo.md, "Interrupted campaigns, --resume").
//
// Each finished run's record goes to records/NNNNNN.json in the campaign's
// working folder: written to a temporary file, flushed to the disk (fsync),
// renamed into place and the folder flushed, so that a record file is never
// half-written and a campaign killed at any point (SIGKILL, power loss)
// keeps every record it committed.  The first pass commits its records in
// groups (McJournalWriter): those of the runs finished since the last
// commit (less than a second after it, at most 256) are lost by a crash
// and run again, with the same results, by --resume.  A record file has the form
// of mc_runs.json holding one record.  The journal is what `kestrel mc --resume` starts from, and
// what the summary files are written from (one record in memory at a time).
#ifndef HARNESS_MC_JOURNAL_H
#define HARNESS_MC_JOURNAL_H

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <mutex>
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

// The first pass's records, committed in groups (group commit).  add()
// writes the record to its temporary file in records/ and holds it open;
// a commit flushes every held file (fsync), renames each into place and
// flushes the folder once.  add() commits when the last commit is
// `commit_seconds` old or `max_held` records are held, so a campaign of
// runs longer than commit_seconds commits each record as it finishes, and
// one of short runs about once per commit_seconds.  Until its commit a
// record is only a temporary file, which the journal does not list: a
// crash loses it, never leaves it half-written.  Thread-safe.
class McJournalWriter {
 public:
  explicit McJournalWriter(std::filesystem::path dir, double commit_seconds = 1.0, size_t max_held = 256);
  ~McJournalWriter();  // the held records closed, not committed (the loss of a crash)
  McJournalWriter(const McJournalWriter&) = delete;
  McJournalWriter& operator=(const McJournalWriter&) = delete;

  void add(const McRecord& r);  // throws OutputError
  void commit();                // every held record into place, durably; throws OutputError
  size_t held() const;

 private:
  struct Held {
    int fd;
    std::filesystem::path tmp, path;
  };
  void commit_locked();

  const std::filesystem::path dir_;
  const double commit_s_;
  const size_t max_held_;
  mutable std::mutex mu_;
  std::vector<Held> held_;
  std::chrono::steady_clock::time_point last_;
};

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
