// mc_validate.cpp: a shard's records against the campaign, its runs/
// walked and copied without following a link, and the shards read as a
// whole (mc_validate.h; the text readers are in mc_shard_read.cpp).
#include "mc/mc_validate.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "harness/output/outputs.h"
#include "scenario/mc_draw.h"

namespace harness {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr unsigned kMaxRunDepth = 8;  // [-] folders inside runs/NNNNNN

[[noreturn]] void refuse(const std::string& file, const std::string& field, const std::string& message)
{
  throw McShardError(file, field, message);
}

}  // namespace

namespace {

bool same_value(double want, double got)
{
  return want == got || (!std::isfinite(want) && std::isnan(got));
}

// The record's own consistency: an invalid draw ran nothing; `pass` means
// complete, valid and every criterion met by its metrics; a reason iff not.
void check_verdict(const McPlan& plan, const McRecord& r, const std::string& file, const std::string& f)
{
  if (r.invalid && (r.complete || r.pass || r.full))
    refuse(file, f + (r.pass ? ".pass" : r.complete ? ".complete" : ".full"), "set on an invalid draw, which does not run");
  if (r.pass && !r.complete) refuse(file, f + ".pass", "set on a run that did not complete");
  if (r.pass != r.reason.empty())
    refuse(file, r.pass ? f + ".reason" : f + ".pass", r.pass ? "a passing run has no reason" : "a failing run needs its reason");
  if (!r.pass) return;
  for (size_t m = 0; m < plan.metrics.size(); ++m) {
    const McMetric& mt = plan.metrics[m];
    if (mt.criterion < 0) continue;
    const double v = r.metrics[m];
    if (!(mt.below ? v < mt.threshold : v > mt.threshold))
      refuse(file, f + ".pass",
             "set, but criterion " + mt.col.name + " is not met by metrics[" + std::to_string(m) + "]");
  }
}

// The record's seed and drawn values are those of run `index` of the campaign.
void check_draw(const McPlan& plan, const McRecord& r, const std::string& file, const std::string& f)
{
  const McDraw d = plan.bound ? draw_run(plan.nominal, *plan.bound, plan.master_seed, r.index)
                              : draw_run(plan.nominal, plan.master_seed, r.index);
  if (r.seed != d.sc.seed) refuse(file, f + ".seed", "not the seed of run " + std::to_string(r.index) + " of this campaign");
  for (size_t c = 0; c < d.drawn.size() && c < r.drawn.size(); ++c)
    if (!same_value(d.drawn[c], r.drawn[c]))
      refuse(file, f + ".drawn[" + std::to_string(c) + "]",
             "not the value drawn for run " + std::to_string(r.index) + " (" + plan.drawn[c].name + ")");
  if (!d.invalid.empty() && !r.invalid) refuse(file, f + ".invalid", "false, but the draw is not a valid spacecraft");
}

}  // namespace

void check_mc_shard(const McPlan& plan, const McShardManifest& m, const std::vector<McRecord>& records,
                    const std::string& manifest_file, const std::string& runs_file)
{
  if (records.size() != m.runs_done)
    refuse(manifest_file, "runs_done", std::to_string(m.runs_done) + ", but " + runs_file + " holds " +
                                           std::to_string(records.size()) + " records");
  std::map<uint64_t, std::string> hashes;
  for (size_t i = 0; i < m.record_hashes.size(); ++i)
    if (!hashes.insert(m.record_hashes[i]).second)
      refuse(manifest_file, "record_fnv1a64[" + std::to_string(i) + "]", "a second hash for one run");
  std::set<uint64_t> seen;
  for (size_t i = 0; i < records.size(); ++i) {
    const McRecord& r = records[i];
    const std::string f = "records[" + std::to_string(i) + "]";
    const std::string k = std::to_string(r.index);
    if (m.partitioned && r.index % m.shards != m.shard)
      refuse(runs_file, f + ".index", "run " + k + " is not in shard " + std::to_string(m.shard) + "/" +
                                          std::to_string(m.shards) + " (runs k with k mod " + std::to_string(m.shards) +
                                          " = " + std::to_string(m.shard) + ")");
    if (!m.only.empty() && !std::binary_search(m.only.begin(), m.only.end(), r.index))
      refuse(runs_file, f + ".index", "run " + k + " is not in the manifest's `only` list");
    if (!seen.insert(r.index).second) refuse(runs_file, f + ".index", "run " + k + " recorded twice");
    check_draw(plan, r, runs_file, f);
    check_verdict(plan, r, runs_file, f);
    const auto h = hashes.find(r.index);
    if (h == hashes.end()) refuse(manifest_file, "record_fnv1a64", "no hash for run " + k);
    if (h->second != mc_record_hash(r))
      refuse(runs_file, f, "run " + k + "'s record does not match its hash in the manifest (record_fnv1a64): "
                               "changed after the campaign wrote it");
  }
}

namespace {

struct Fd {
  int fd = -1;
  explicit Fd(int f) : fd(f) {}
  ~Fd()
  {
    if (fd >= 0) ::close(fd);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
};

// openat without following a link; a refusal names the path.
int open_nofollow(int dirfd, const std::string& name, int flags, const fs::path& shown)
{
  const int fd = ::openat(dirfd, name.c_str(), flags | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) return fd;
  if (errno == ELOOP) refuse(shown.string(), "runs/", "a symbolic link: merge never follows links");
  if (errno == ENOTDIR) refuse(shown.string(), "runs/", "not a folder");
  refuse(shown.string(), "runs/", std::string("cannot open: ") + std::strerror(errno));
}

std::vector<std::string> entries(int dirfd, const fs::path& shown)
{
  const int d2 = ::dup(dirfd);
  DIR* d = d2 >= 0 ? ::fdopendir(d2) : nullptr;
  if (!d) {
    if (d2 >= 0) ::close(d2);
    refuse(shown.string(), "runs/", std::string("cannot list: ") + std::strerror(errno));
  }
  std::vector<std::string> names;
  while (const dirent* e = ::readdir(d)) {
    const std::string n = e->d_name;
    if (n != "." && n != "..") names.push_back(n);
  }
  ::closedir(d);
  std::sort(names.begin(), names.end());
  return names;
}

void copy_file_fd(int src, const fs::path& to)
{
  Fd dst(::open(to.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
  if (dst.fd < 0) throw OutputError("cannot create " + to.string() + ": " + std::strerror(errno));
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(src, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) throw OutputError("cannot read for " + to.string() + ": " + std::strerror(errno));
    for (ssize_t off = 0; off < n;) {
      const ssize_t w = ::write(dst.fd, buf + off, static_cast<size_t>(n - off));
      if (w < 0) throw OutputError("cannot write " + to.string() + ": " + std::strerror(errno));
      off += w;
    }
  }
  if (::close(dst.fd) != 0) {
    dst.fd = -1;
    throw OutputError("cannot write " + to.string() + ": " + std::strerror(errno));
  }
  dst.fd = -1;
}

// The folder open as dirfd into `to` ("" : check only): regular files and
// folders, nothing else, no link followed.
void copy_tree(int dirfd, const fs::path& shown, const fs::path& to, unsigned depth)
{
  if (depth > kMaxRunDepth) refuse(shown.string(), "runs/", "folders nested too deep");
  if (!to.empty()) fs::create_directory(to);
  for (const std::string& n : entries(dirfd, shown)) {
    struct stat st;
    if (::fstatat(dirfd, n.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
      refuse((shown / n).string(), "runs/", std::string("cannot stat: ") + std::strerror(errno));
    if (S_ISLNK(st.st_mode)) refuse((shown / n).string(), "runs/", "a symbolic link: merge never follows links");
    if (S_ISDIR(st.st_mode)) {
      Fd sub(open_nofollow(dirfd, n, O_RDONLY | O_DIRECTORY, shown / n));
      copy_tree(sub.fd, shown / n, to.empty() ? fs::path() : to / n, depth + 1);
      continue;
    }
    if (!S_ISREG(st.st_mode)) refuse((shown / n).string(), "runs/", "not a regular file or a folder");
    Fd f(open_nofollow(dirfd, n, O_RDONLY, shown / n));
    struct stat fst;
    if (::fstat(f.fd, &fst) != 0 || !S_ISREG(fst.st_mode))
      refuse((shown / n).string(), "runs/", "not a regular file");
    if (!to.empty()) copy_file_fd(f.fd, to / n);
  }
}

bool run_folder_name(const std::string& n, uint64_t& k)
{
  if (n.size() < 6 || n.size() > 12 || n.find_first_not_of("0123456789") != std::string::npos) return false;
  k = std::stoull(n);
  char b[32];
  std::snprintf(b, sizeof b, "%06llu", static_cast<unsigned long long>(k));
  return n == b;
}

}  // namespace

std::string read_shard_file(const fs::path& p, uint64_t max_bytes)
{
  const std::string shown = p.string();
  Fd f(::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  if (f.fd < 0) {
    if (errno == ELOOP) refuse(shown, "(file)", "a symbolic link: merge never follows links");
    refuse(shown, "(file)", std::string("cannot read: ") + std::strerror(errno));
  }
  struct stat st;
  if (::fstat(f.fd, &st) != 0 || !S_ISREG(st.st_mode)) refuse(shown, "(file)", "not a regular file");
  if (static_cast<uint64_t>(st.st_size) > max_bytes)
    refuse(shown, "(file)", "larger than " + std::to_string(max_bytes) + " bytes");
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) refuse(shown, "(file)", std::string("cannot read: ") + std::strerror(errno));
    text.append(buf, static_cast<size_t>(n));
    if (text.size() > max_bytes) refuse(shown, "(file)", "larger than " + std::to_string(max_bytes) + " bytes");
  }
  return text;
}

void copy_mc_runs(const fs::path& shard, const std::set<uint64_t>& indices, const fs::path& to)
{
  Fd top(::open(shard.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (top.fd < 0) refuse(shard.string(), "(folder)", std::string("cannot open: ") + std::strerror(errno));
  const fs::path runs = shard / "runs";
  Fd rd(open_nofollow(top.fd, "runs", O_RDONLY | O_DIRECTORY, runs));
  std::set<uint64_t> found;
  for (const std::string& n : entries(rd.fd, runs)) {
    uint64_t k = 0;
    if (!run_folder_name(n, k) || !indices.count(k))
      refuse((runs / n).string(), "runs/", "not the folder of a run this shard recorded");
    struct stat st;
    if (::fstatat(rd.fd, n.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || S_ISLNK(st.st_mode))
      refuse((runs / n).string(), "runs/", "a symbolic link: merge never follows links");
    Fd sub(open_nofollow(rd.fd, n, O_RDONLY | O_DIRECTORY, runs / n));
    copy_tree(sub.fd, runs / n, to.empty() ? fs::path() : to / n, 0);
    found.insert(k);
  }
  for (uint64_t k : indices)
    if (!found.count(k)) {
      char b[32];
      std::snprintf(b, sizeof b, "%06llu", static_cast<unsigned long long>(k));
      refuse((runs / b).string(), "runs/", "missing: run " + std::to_string(k) + " is recorded but has no folder");
    }
}

namespace {

constexpr uint64_t kMaxManifestBytes = 1ULL << 30;  // [B] mc_manifest.json (a hash per run)

// A record's text is bounded by its values: the records file by the runs.
uint64_t max_records_bytes(const McRecordShape& s, uint64_t records)
{
  return (1ULL << 20) + records * (kMaxMcReason + 4096 + 40 * (s.drawn + s.metrics + s.series));
}

// The first shard's scenario as the campaign's plan (ScenarioError when it is not one).
McPlan plan_of(const McShardManifest& m, const std::string& file)
{
  const Scenario sc = load_scenario_text(json({{"kestrel_manifest", 1}, {"scenario", m.scenario}}).dump(), file);
  return make_mc_plan(sc, m.master_seed, m.runs);
}

// Shard j's manifest against the first one's.
void same_campaign(const McShardManifest& m, const McShardManifest& first, const std::string& file,
                   const std::string& first_file)
{
  const char* field = m.scenario_hash != first.scenario_hash || m.scenario != first.scenario ? "scenario"
                      : m.master_seed != first.master_seed                                 ? "master_seed"
                      : m.runs != first.runs                                               ? "runs"
                                                                                           : nullptr;
  if (field) refuse(file, field, "differs from " + first_file + ": a shard of another campaign");
  if (!m.complete) refuse(file, "complete", "false: the shard was interrupted; rerun it first");
}

// Every run (of the `only` lists, else of the campaign) is in some shard.
void check_complete(const McShards& set, const std::vector<char>& seen, bool any_only, const std::string& first_file)
{
  uint64_t missing = 0, first_missing = 0;
  auto want = [&](uint64_t k) {
    if (!seen[k] && missing++ == 0) first_missing = k;
  };
  if (any_only)
    for (uint64_t k : set.only) want(k);
  else
    for (uint64_t k = 0; k < set.plan.runs; ++k) want(k);
  if (missing)
    refuse(first_file, "runs", std::to_string(missing) + " runs are in no shard (first: " + std::to_string(first_missing) +
                                   "); give every shard of the campaign");
}

}  // namespace

McShards read_mc_shards(const std::vector<std::string>& shards)
{
  McShards set;
  std::vector<McShardManifest> ms;
  const std::string first_file = (fs::path(shards.at(0)) / "mc_manifest.json").string();
  for (const std::string& s : shards) {
    const std::string file = (fs::path(s) / "mc_manifest.json").string();
    ms.push_back(read_mc_manifest(read_shard_file(file, kMaxManifestBytes), file));
    same_campaign(ms.back(), ms.front(), file, first_file);
  }
  set.first = ms.front();
  for (size_t i = 0; i < set.first.overrides.size(); ++i) {
    try {
      parse_override(set.first.overrides[i]);
    } catch (const std::invalid_argument& e) {
      refuse(first_file, "overrides[" + std::to_string(i) + "]", std::string("not key=value: ") + e.what());
    }
  }
  set.plan = plan_of(set.first, first_file);
  const McRecordShape shape = mc_record_shape(set.plan);
  std::vector<char> seen(set.plan.runs, 0);
  std::set<uint64_t> only;
  bool any_only = false;
  for (size_t j = 0; j < shards.size(); ++j) {
    const McShardManifest& m = ms[j];
    const std::string mfile = (fs::path(shards[j]) / "mc_manifest.json").string();
    const std::string rfile = (fs::path(shards[j]) / "mc_runs.json").string();
    std::vector<McRecord> recs = read_mc_records(read_shard_file(rfile, max_records_bytes(shape, m.runs_done)), rfile, shape);
    check_mc_shard(set.plan, m, recs, mfile, rfile);
    set.runs.emplace_back();
    for (size_t i = 0; i < recs.size(); ++i) {
      if (seen[recs[i].index])
        refuse(rfile, "records[" + std::to_string(i) + "].index",
               "run " + std::to_string(recs[i].index) + " is in more than one shard");
      seen[recs[i].index] = 1;
      set.runs.back().insert(recs[i].index);
    }
    if (!m.only.empty()) any_only = true;
    only.insert(m.only.begin(), m.only.end());
    copy_mc_runs(shards[j], set.runs.back(), fs::path());  // walked, not copied
    for (McRecord& r : recs) set.records.push_back(std::move(r));
  }
  set.only.assign(only.begin(), only.end());
  check_complete(set, seen, any_only, first_file);
  std::sort(set.records.begin(), set.records.end(), [](const McRecord& a, const McRecord& b) { return a.index < b.index; });
  return set;
}

}  // namespace harness
