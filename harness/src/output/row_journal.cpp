// row_journal.cpp: the raw rows of a run, for a run continued from a
// checkpoint (harness/output/row_journal.h).
#include "harness/output/row_journal.h"

#include <unistd.h>

#include <cstring>

#include "harness/core/checkpoint.h"
#include "harness/output/outputs.h"

namespace harness {

namespace {

constexpr char kMagic[8] = {'K', 'S', 'T', 'R', 'L', 'R', 'O', 'W'};
constexpr uint64_t kFnvStart = kFnv1a64Start;

uint64_t fnv1a64(uint64_t h, const void* p, size_t n) { return fnv1a64_bytes(h, p, n); }

uint64_t get_u64(const uint8_t* p)
{
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

// The 16-byte header: magic, version 1, number of columns.
std::vector<uint8_t> header(size_t nc)
{
  std::vector<uint8_t> h(kMagic, kMagic + 8);
  for (uint32_t v : {uint32_t{1}, static_cast<uint32_t>(nc)})
    for (int i = 0; i < 4; ++i) h.push_back(static_cast<uint8_t>(v >> (8 * i)));
  return h;
}

}  // namespace

RowJournal::RowJournal(std::string path, bool resume) : path_(std::move(path)), resume_(resume) {}

RowJournal::~RowJournal()
{
  if (f_) std::fclose(f_);
}

void RowJournal::put(const void* p, size_t n)
{
  if (std::fwrite(p, 1, n, f_) != n) throw OutputError(path_ + ": write failed (disk full?)");
  at_.bytes += n;
  at_.fnv = fnv1a64(at_.fnv, p, n);
}

void RowJournal::begin(const RecordLayout& layout, uint64_t)
{
  static_assert(sizeof(double) == 8, "the journal holds float64 values");
  nc_ = layout.columns.size();
  f_ = std::fopen(path_.c_str(), resume_ ? "r+b" : "wb");
  if (!f_) throw OutputError(path_ + ": cannot open " + (resume_ ? "the rows of the checkpointed run" : "for writing"));
  at_ = Mark{0, 0, kFnvStart};
  if (!resume_) {
    const std::vector<uint8_t> h = header(nc_);
    put(h.data(), h.size());
  }
}

void RowJournal::write(const double* rows, size_t n)
{
  if (!f_ || n == 0) return;
  uint8_t len[8];
  for (int i = 0; i < 8; ++i) len[i] = static_cast<uint8_t>(static_cast<uint64_t>(n) >> (8 * i));
  put(len, 8);
  put(rows, n * nc_ * sizeof(double));
  at_.rows += n;
}

void RowJournal::end(bool)
{
  if (!f_) return;
  const bool ok = std::ferror(f_) == 0;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok || !closed) throw OutputError(path_ + ": write failed (disk full?)");
}

RowJournal::Mark RowJournal::sync()
{
  if (!f_ || std::fflush(f_) != 0 || ::fsync(::fileno(f_)) != 0)
    throw OutputError(path_ + ": cannot flush the rows to disk");
  return at_;
}

void RowJournal::replay(const Mark& m, const std::vector<RecordSink*>& sinks)
{
  const auto refuse = [&](const std::string& why) {
    throw CheckpointError(path_ + ": " + why + "; the run cannot be continued from its checkpoint");
  };
  std::vector<uint8_t> h(16);
  if (m.bytes < 16 || std::fread(h.data(), 1, 16, f_) != 16) refuse("the rows file is shorter than its checkpoint says");
  if (h != header(nc_)) refuse("not the rows of this run (header: magic, version or columns differ)");
  at_ = Mark{0, 0, kFnvStart};
  at_.fnv = fnv1a64(at_.fnv, h.data(), 16);
  at_.bytes = 16;
  std::vector<double> rows;
  while (at_.bytes < m.bytes) {
    uint8_t len[8];
    if (m.bytes - at_.bytes < 8 || std::fread(len, 1, 8, f_) != 8) refuse("a record runs past the checkpoint's mark");
    const uint64_t n = get_u64(len);
    const uint64_t body = n * nc_ * sizeof(double);
    if (n == 0 || nc_ == 0 || body / n / nc_ != sizeof(double) || m.bytes - at_.bytes - 8 < body)
      refuse("a record runs past the checkpoint's mark");
    rows.resize(static_cast<size_t>(n * nc_));
    if (std::fread(rows.data(), 1, static_cast<size_t>(body), f_) != body) refuse("the rows file is cut short");
    at_.fnv = fnv1a64(fnv1a64(at_.fnv, len, 8), rows.data(), static_cast<size_t>(body));
    at_.bytes += 8 + body;
    at_.rows += n;
    for (RecordSink* s : sinks) s->write(rows.data(), static_cast<size_t>(n));
  }
  if (at_.rows != m.rows || at_.fnv != m.fnv) refuse("the rows differ from those the checkpoint was taken with");
  if (std::fflush(f_) != 0 || ::ftruncate(::fileno(f_), static_cast<off_t>(m.bytes)) != 0 ||
      std::fseek(f_, static_cast<long>(m.bytes), SEEK_SET) != 0)
    throw OutputError(path_ + ": cannot cut the rows back to the checkpoint");
}

}  // namespace harness
