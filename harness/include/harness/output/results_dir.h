// results_dir: a run's results folder, all or nothing and never mixed.
//
// A run never writes into its target folder T directly.  It
//   1. takes an exclusive lock on T (flock on the file ".<T>.kestrel-lock"
//      beside T, holding the owner's pid; released by the kernel when the
//      process ends, however it ends): a second run on the same T is refused;
//   2. refuses an existing, non-empty T unless `force` is given, and even
//      then replaces only a folder that holds nothing but Kestrel result
//      files (so `--force -o ~` cannot delete a home folder);
//   3. creates a fresh working folder ".<T>.kestrel-work-<pid>" beside T
//      (this is the writability check, done before anything is simulated)
//      and checks the free space of its file system against an estimate;
//   4. on commit() moves the working folder into place with rename(2): T is
//      either the previous results, untouched, or the new ones, whole.  A
//      replaced T is first renamed aside and deleted only after the swap.
// Without commit() (an output error, an exception) the working folder is
// removed and T is left exactly as it was.  A crash (SIGKILL, power loss)
// can leave a working folder behind; its name says what it is.
#ifndef HARNESS_RESULTS_DIR_H
#define HARNESS_RESULTS_DIR_H

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace harness {

// The target cannot be used: it exists (without force), it holds foreign
// files, or another run holds its lock.  Nothing was run or written.
class ResultsDirRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ResultsDir {
 public:
  // Locks `target`, checks it and creates the working folder.  Throws
  // ResultsDirRefused, or OutputError (a folder cannot be created/written).
  ResultsDir(const std::string& target, bool force);
  // Continuing a run killed before it ended (`kestrel run --resume`): locks
  // `target` and takes over the working folder a killed run of it left
  // with `marker` in it (renamed to this process's working folder).
  // ResultsDirRefused when there is none (naming why: the results are
  // finished, or no run of them wrote a checkpoint) or several.
  ResultsDir(const std::string& target, const std::string& marker);
  ~ResultsDir();
  ResultsDir(const ResultsDir&) = delete;
  ResultsDir& operator=(const ResultsDir&) = delete;

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& work() const { return work_; }
  // Throws OutputError when the working folder's file system has fewer than
  // `bytes` available (a run's estimated output).
  void require_free_space(uint64_t bytes) const;
  // Moves the working folder into place (see above).  Throws OutputError.
  void commit();
  // What a killed run of the same results left beside them (a working
  // folder, or the previous results it had set aside): one line each,
  // naming the folder and the command that removes it.  Never removed
  // here: it may hold the only copy of something.
  const std::vector<std::string>& notes() const { return notes_; }
  // Leaves the working folder in place when this ends without commit() (a
  // campaign's finished runs, which `kestrel mc --resume` continues from).
  void keep_work();

  // The file names a results folder may hold (what --force may replace).
  static bool is_result_file_name(const std::string& name);
  // ... among them the checkpoints the live view saves: checkpoint-<tick>.kckp
  static bool is_live_checkpoint_name(const std::string& name);
  // ... and those of a Monte Carlo campaign's folder (with mc_manifest.json,
  // whose runs/ and shards/ folders --force also replaces).
  static bool is_campaign_file_name(const std::string& name);

 private:
  // The lock file's descriptor, closed (releasing the flock) when the
  // ResultsDir ends, or when its constructor throws at any point.
  struct Fd {
    int fd = -1;
    Fd() = default;
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() { reset(); }
    void reset();
  };
  void lock_target(const std::string& target);
  void find_leftovers(const std::filesystem::path& t);
  void adopt_work(const std::string& target, const std::string& marker);
  std::filesystem::path target_, work_, lock_path_;
  std::vector<std::string> notes_;
  Fd lock_;
  bool committed_ = false;
};

// Bytes available to an unprivileged writer on the file system holding `p`.
uint64_t free_bytes(const std::filesystem::path& p);

}  // namespace harness

#endif  // HARNESS_RESULTS_DIR_H
