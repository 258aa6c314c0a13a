// mc_journal.cpp: see harness/mc/mc_journal.h.
#include "harness/mc/mc_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "harness/output/outputs.h"

namespace harness {

namespace fs = std::filesystem;

namespace {

std::string sys_error() { return std::strerror(errno); }

// The whole of `text` to descriptor fd.
bool write_all(int fd, const std::string& text)
{
  size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = ::write(fd, text.data() + at, text.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<size_t>(n);
  }
  return true;
}

void sync_folder(const fs::path& d)
{
  const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw OutputError(d.string() + ": cannot open the folder to flush it: " + sys_error());
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw OutputError(d.string() + ": cannot flush the folder: " + sys_error());
}

fs::path temp_beside(const fs::path& path) { return path.parent_path() / ("." + path.filename().string() + ".tmp"); }

// `text` into the temporary file beside `path`, left open (its descriptor).
int write_temp(const fs::path& path, const std::string& text)
{
  const fs::path tmp = temp_beside(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(tmp.string() + ": cannot open for writing: " + sys_error());
  if (!write_all(fd, text)) {
    const std::string why = sys_error();
    ::close(fd);
    ::unlink(tmp.c_str());
    throw OutputError(path.string() + ": write failed (disk full?): " + why);
  }
  return fd;
}

// The temporary file of `path` (open as fd) flushed, closed and renamed
// into place (the folder not flushed).
void sync_into_place(int fd, const fs::path& path)
{
  const fs::path tmp = temp_beside(path);
  const bool ok = ::fsync(fd) == 0;
  const std::string why = ok ? "" : sys_error();
  if (::close(fd) != 0 || !ok) {
    ::unlink(tmp.c_str());
    throw OutputError(path.string() + ": write failed (disk full?)" + (why.empty() ? "" : ": " + why));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string e = sys_error();
    ::unlink(tmp.c_str());
    throw OutputError(path.string() + ": cannot move into place: " + e);
  }
}

}  // namespace

fs::path mc_record_path(const fs::path& dir, uint64_t index)
{
  char b[40];
  std::snprintf(b, sizeof b, "%06llu.json", static_cast<unsigned long long>(index));
  return dir / "records" / b;
}

void write_file_durably(const fs::path& path, const std::string& text)
{
  sync_into_place(write_temp(path, text), path);
  sync_folder(path.parent_path());
}

McJournalWriter::McJournalWriter(fs::path dir, double commit_seconds, size_t max_held)
    : dir_(std::move(dir)), commit_s_(commit_seconds), max_held_(std::max<size_t>(1, max_held)),
      last_(std::chrono::steady_clock::now())
{
  std::error_code ec;
  fs::create_directories(dir_ / "records", ec);
}

McJournalWriter::~McJournalWriter()
{
  for (const Held& h : held_) ::close(h.fd);
}

void McJournalWriter::add(const McRecord& r)
{
  const fs::path path = mc_record_path(dir_, r.index);
  const int fd = write_temp(path, mc_records_json({r}));
  std::lock_guard<std::mutex> g(mu_);
  held_.push_back({fd, temp_beside(path), path});
  const double age = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
  if (held_.size() >= max_held_ || age >= commit_s_) commit_locked();
}

void McJournalWriter::commit()
{
  std::lock_guard<std::mutex> g(mu_);
  commit_locked();
}

size_t McJournalWriter::held() const
{
  std::lock_guard<std::mutex> g(mu_);
  return held_.size();
}

void McJournalWriter::commit_locked()
{
  last_ = std::chrono::steady_clock::now();
  if (held_.empty()) return;
  std::vector<Held> group;
  group.swap(held_);
  size_t i = 0;
  try {
    for (; i < group.size(); ++i) sync_into_place(group[i].fd, group[i].path);
  } catch (...) {  // the rest closed, left as temporary files (not listed)
    for (++i; i < group.size(); ++i) ::close(group[i].fd);
    throw;
  }
  sync_folder(dir_ / "records");
}

void write_mc_record(const fs::path& dir, const McRecord& r)
{
  std::error_code ec;
  fs::create_directories(dir / "records", ec);
  write_file_durably(mc_record_path(dir, r.index), mc_records_json({r}));
}

McRecord read_mc_record(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  std::vector<McRecord> r;
  try {
    r = mc_records_from_json(s.str());
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  if (r.size() != 1) throw std::runtime_error(file.string() + ": holds " + std::to_string(r.size()) + " records, not 1");
  return std::move(r.front());
}

std::vector<uint64_t> mc_journal_indices(const fs::path& dir)
{
  std::vector<uint64_t> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir / "records", ec)) {
    const std::string n = e.path().filename().string();
    // NNNNNN.json: digits, then ".json" (".NNNNNN.json.tmp" is a write cut short)
    const size_t dot = n.find('.');
    if (dot == 0 || dot == std::string::npos || dot > 12 || n.substr(dot) != ".json") continue;
    if (n.find_first_not_of("0123456789") != dot || !e.is_regular_file(ec)) continue;
    out.push_back(std::stoull(n.substr(0, dot)));
  }
  std::sort(out.begin(), out.end());
  return out;
}

void remove_mc_journal(const fs::path& dir)
{
  std::error_code ec;
  fs::remove_all(dir / "records", ec);
}

McRunState mc_run_state(const McRecord& r)
{
  McRunState s;
  s.index = r.index;
  s.pass = r.pass;
  s.invalid = r.invalid;
  s.full = r.full;
  return s;
}

McMemoryRecords::McMemoryRecords(const std::vector<McRecord>& records) : recs_(records)
{
  states_.reserve(records.size());
  for (const McRecord& r : records) states_.push_back(mc_run_state(r));
}

}  // namespace harness
