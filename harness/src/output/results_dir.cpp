// results_dir.cpp: lock, working folder and atomic swap of a results folder.
#include "harness/output/results_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

#include "harness/core/scenario_types.h"
#include "harness/output/outputs.h"

namespace harness {

namespace fs = std::filesystem;

namespace {

std::string sys_error(int err) { return std::strerror(err); }

fs::path beside(const fs::path& target, const std::string& suffix)
{
  return target.parent_path() / ("." + target.filename().string() + suffix);
}

std::string mib(uint64_t bytes)
{
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

bool ResultsDir::is_result_file_name(const std::string& name)
{
  static const std::array<const char*, 8> kNames = {"manifest.json",    "results.h5",  "telemetry.csv",
                                                    "report_data.json", "report.html", "dataflow.dot",
                                                    "fsw_health.txt",   "summary.txt"};
  for (const char* n : kNames)
    if (name == n) return true;
  return is_live_checkpoint_name(name);
}

bool ResultsDir::is_live_checkpoint_name(const std::string& name)
{
  const std::string head = "checkpoint-", tail = ".kckp";
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return false;
  const std::string tick = name.substr(head.size(), name.size() - head.size() - tail.size());
  return tick.size() <= 20 && tick.find_first_not_of("0123456789") == std::string::npos;
}

bool ResultsDir::is_campaign_file_name(const std::string& name)
{
  static const std::array<const char*, 7> kNames = {"mc_manifest.json", "summary.csv",  "summary.h5",
                                                    "mc_report_data.json", "mc_report.html", "mc_runs.json",
                                                    "mc.sbatch"};
  for (const char* n : kNames)
    if (name == n) return true;
  return false;
}

uint64_t free_bytes(const fs::path& p)
{
  struct statvfs s {};
  if (::statvfs(p.c_str(), &s) != 0) throw OutputError(p.string() + ": cannot read free space: " + sys_error(errno));
  return static_cast<uint64_t>(s.f_bavail) * static_cast<uint64_t>(s.f_frsize);
}

namespace {

// Step 2 of ResultsDir: what is at `t` already.  Absent, empty, or Kestrel
// result files (with force) are fine; anything else is refused.
void check_existing(const fs::path& t, const std::string& target, bool force)
{
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(t, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) {
      throw ResultsDirRefused(target + ": exists and is not a folder; not touching it");
    }
    std::string foreign;
    bool empty = true;
    // a Monte Carlo campaign's folder (docs/monte-carlo.md) also holds its
    // runs/ folder (run folders of result files), shards/ and records/ (the
    // finished runs of an interrupted campaign, for --resume)
    const bool campaign = fs::is_regular_file(t / "mc_manifest.json", ec);
    for (const fs::directory_entry& e : fs::directory_iterator(t, ec)) {
      empty = false;
      const std::string n = e.path().filename().string();
      const bool campaign_part =
          campaign && (ResultsDir::is_campaign_file_name(n) || ((n == "runs" || n == "shards" || n == "records") && e.is_directory()));
      if (!campaign_part && (!ResultsDir::is_result_file_name(n) || !e.is_regular_file())) {
        foreign = n;
        break;
      }
    }
    if (ec) {
      throw OutputError(target + ": cannot read the existing folder: " + ec.message());
    }
    if (!empty && !foreign.empty()) {
      throw ResultsDirRefused(target + ": exists and holds '" + foreign +
                              "', which is not a Kestrel result file; not replacing it (choose another -o)");
    }
    if (!empty && !force) {
      throw ResultsDirRefused(target +
                              ": already holds the results of a run; use --force to replace them whole, or "
                              "choose another -o");
    }
  }
}

}  // namespace

void ResultsDir::lock_target(const std::string& target)
{
  if (target.empty()) throw OutputError("no results folder given");
  fs::path t = fs::absolute(fs::path(target)).lexically_normal();
  if (!t.has_filename()) t = t.parent_path();  // "runs/s1/" -> "runs/s1"
  const std::string name = t.filename().string();
  if (name.empty() || name == "." || name == ".." || t == t.root_path())
    throw OutputError(target + ": not usable as a results folder");
  target_ = t;
  std::error_code ec;
  fs::create_directories(t.parent_path(), ec);
  if (ec || !fs::is_directory(t.parent_path()))
    throw OutputError(target + ": cannot create its parent folder " + t.parent_path().string() +
                      (ec ? ": " + ec.message() : ""));

  // 1. the lock (before looking at the target: another run may be swapping it)
  lock_path_ = beside(t, ".kestrel-lock");
  lock_.fd = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_.fd < 0)
    throw OutputError(target + ": cannot write in " + t.parent_path().string() + " (lock file " +
                      lock_path_.filename().string() + ": " + sys_error(errno) + ")");
  if (::flock(lock_.fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char buf[32] = {0};
    const ssize_t n = ::pread(lock_.fd, buf, sizeof buf - 1, 0);
    lock_.reset();
    if (err == EWOULDBLOCK) {
      const std::string pid = n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string("?");
      throw ResultsDirRefused(target + ": another kestrel run (pid " + pid.substr(0, pid.find('\n')) +
                              ") is writing these results; wait for it to end or choose another -o");
    }
    throw OutputError(target + ": cannot lock " + lock_path_.string() + ": " + sys_error(err));
  }
  const std::string me = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_.fd, 0) != 0 || ::pwrite(lock_.fd, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size())) {
    // the lock holds without the pid; only the refusal message is poorer
  }
}

ResultsDir::ResultsDir(const std::string& target, bool force)
{
  const fs::path& t = target_;
  lock_target(target);

  // 2. what is there already
  check_existing(t, target, force);

  // 3. what killed runs left: with the lock held no other run writes these
  // results, so a working or set-aside folder of another pid is a leftover
  find_leftovers(t);

  // 4. the working folder (the writability check, before simulating)
  work_ = beside(t, ".kestrel-work-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(work_, ec);  // a stale one of a crashed run with our pid
  if (!fs::create_directory(work_, ec) || ec) {
    throw OutputError(target + ": cannot create the working folder " + work_.string() +
                      (ec ? ": " + ec.message() : ""));
  }
}

ResultsDir::ResultsDir(const std::string& target, const std::string& marker)
{
  lock_target(target);
  // what is there already may only be Kestrel results (a run started with
  // --force replaces them at its end, as it would have)
  check_existing(target_, target, true);
  adopt_work(target, marker);
  find_leftovers(target_);
}

void ResultsDir::adopt_work(const std::string& target, const std::string& marker)
{
  const std::string prefix = beside(target_, ".kestrel-work-").filename().string();
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(target_.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (n.size() > prefix.size() && n.compare(0, prefix.size(), prefix) == 0 &&
        fs::is_regular_file(it->path() / marker))
      found.push_back(it->path());
  }
  if (found.empty())
    throw ResultsDirRefused(
        target + ": nothing to resume: no unfinished run of these results left a checkpoint (" +
        (fs::exists(target_ / "manifest.json") ? "the folder holds a finished run's results, whose checkpoint is removed "
                                                  "when it ends"
                                                : "a run is continued only when started with --checkpoint-every") +
        ")");
  if (found.size() > 1)
    throw ResultsDirRefused(target + ": several killed runs left a checkpoint (" + found[0].filename().string() +
                            ", " + found[1].filename().string() + "); remove all but the one to continue");
  work_ = beside(target_, ".kestrel-work-" + std::to_string(::getpid()));
  if (found[0] != work_) {
    fs::remove_all(work_, ec);
    fs::rename(found[0], work_, ec);
    if (ec) throw OutputError(target + ": cannot take over " + found[0].string() + ": " + ec.message());
  }
}

void ResultsDir::find_leftovers(const fs::path& t)
{
  const std::string mine = std::to_string(::getpid());
  std::error_code ec;
  for (const char* kind : {".kestrel-work-", ".kestrel-old-"}) {
    const std::string prefix = beside(t, kind).filename().string();
    for (fs::directory_iterator it(t.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
      const std::string n = it->path().filename().string();
      if (n.size() <= prefix.size() || n.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid = n.substr(prefix.size());
      if (pid == mine || pid.find_first_not_of("0123456789") != std::string::npos) continue;
      std::string q = "'";  // the path quoted for a POSIX shell
      for (char ch : it->path().string()) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
      q += "'";
      notes_.push_back(escape_bytes(
          it->path().string() + " was left by an earlier run of " + t.filename().string() + " that was killed (pid " +
          pid + ", " + (std::string(kind) == ".kestrel-work-" ? "its unfinished results" : "the results it replaced") +
          "); nothing uses it: remove it with  rm -rf -- " + q));
    }
  }
}

void ResultsDir::Fd::reset()
{
  if (fd >= 0) ::close(fd);
  fd = -1;
}

ResultsDir::~ResultsDir()
{
  if (!committed_ && !work_.empty()) {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }
}

void ResultsDir::keep_work()
{
  committed_ = true;
}

void ResultsDir::require_free_space(uint64_t bytes) const
{
  const uint64_t have = free_bytes(work_);
  if (have < bytes)
    throw OutputError(target_.string() + ": not enough free space on its file system (the run needs about " +
                      mib(bytes) + ", " + mib(have) + " are available); nothing was simulated");
}

void ResultsDir::commit()
{
  std::error_code ec;
  fs::path old;
  if (fs::exists(fs::symlink_status(target_, ec))) {
    old = beside(target_, ".kestrel-old-" + std::to_string(::getpid()));
    fs::remove_all(old, ec);
    fs::rename(target_, old, ec);
    if (ec) throw OutputError(target_.string() + ": cannot move the previous results aside: " + ec.message());
  }
  fs::rename(work_, target_, ec);
  if (ec) {
    std::error_code ec2;
    if (!old.empty()) fs::rename(old, target_, ec2);  // put the previous results back
    throw OutputError(target_.string() + ": cannot move the results into place: " + ec.message());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace harness
