// row_journal: the recorded rows of a run in a raw file, as the sinks were
// handed them, so that a run continued from a checkpoint can rebuild its
// result files whole (docs/checkpoint.md, "Continuing a kestrel run").
//
// The file: a 16-byte header (the magic KSTRLROW, u32 version 1, u32 number
// of columns), then one record per write the sinks were given: u64 rows n,
// then n x columns float64, all little-endian.  Only appended to; sync()
// makes it durable and says how far it goes (bytes, rows, FNV-1a 64 of
// those bytes): a checkpoint holds that mark, and a continued run checks it
// and cuts the file back to it.
#ifndef HARNESS_OUTPUT_ROW_JOURNAL_H
#define HARNESS_OUTPUT_ROW_JOURNAL_H

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "harness/core/recorder.h"

namespace harness {

class RowJournal : public RecordSink {
 public:
  // How far the journal goes (what sync() made durable).
  struct Mark {
    uint64_t bytes = 0;
    uint64_t rows = 0;
    uint64_t fnv = 0;
  };
  // `resume`: continue an existing journal (begin() opens it, replay() cuts
  // it back); else begin() creates it afresh.
  RowJournal(std::string path, bool resume);
  ~RowJournal() override;
  RowJournal(const RowJournal&) = delete;
  RowJournal& operator=(const RowJournal&) = delete;
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool complete) override;
  // Flushes the file to disk (fsync); its mark.  OutputError when it cannot.
  Mark sync();
  // Resuming: checks the journal's first m.bytes (length, rows, checksum;
  // CheckpointError naming the file when they differ), hands each record
  // to every sink of `sinks` in order, then cuts the file back to m.bytes
  // and appends from there.
  void replay(const Mark& m, const std::vector<RecordSink*>& sinks);

 private:
  void put(const void* p, size_t n);
  std::string path_;
  bool resume_ = false;
  FILE* f_ = nullptr;
  size_t nc_ = 0;
  Mark at_;
};

}  // namespace harness

#endif  // HARNESS_OUTPUT_ROW_JOURNAL_H
