// Helpers of the HWIL test and benchmark: a child process whose first
// stdout line is read with a timeout and which is always stopped, a scratch
// folder, and a socat pty pair.
#ifndef KESTREL_HWIL_SUPPORT_HPP
#define KESTREL_HWIL_SUPPORT_HPP

#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace hwil {

// A child process with its stdout on a pipe; stopped (SIGTERM, then SIGKILL
// after 10 s) and reaped by the destructor.
class Child {
 public:
  // merge_stderr: stderr goes to the same pipe (read with rest())
  explicit Child(const std::vector<std::string>& argv, bool merge_stderr = false)
  {
    int out[2];
    if (::pipe(out) != 0) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, out[1], 1);
    if (merge_stderr) posix_spawn_file_actions_adddup2(&fa, out[1], 2);
    posix_spawn_file_actions_addclose(&fa, out[0]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int rc = posix_spawn(&pid_, args[0], &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    ::close(out[1]);
    fd_ = out[0];
    if (rc != 0) {
      pid_ = -1;
      throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
    }
  }
  ~Child()
  {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      int st = 0;
      while (::waitpid(pid_, &st, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > end) {
          ::kill(pid_, SIGKILL);
          ::waitpid(pid_, &st, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    if (fd_ >= 0) ::close(fd_);
  }
  // Stops the child (SIGTERM) and returns all it wrote from now on until it
  // exits (bounded by timeout_s; SIGKILL after it).
  std::string rest(double timeout_s)
  {
    std::string s;
    if (pid_ <= 0) return s;
    ::kill(pid_, SIGTERM);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char buf[512];
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n <= 0) break;
      s.append(buf, static_cast<size_t>(n));
    }
    int st = 0;
    if (::waitpid(pid_, &st, WNOHANG) == 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &st, 0);
    }
    pid_ = -1;
    return s;
  }
  // The first stdout line (without the newline); "" on timeout or exit.
  std::string line(double timeout_s)
  {
    std::string s;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char c;
      if (::read(fd_, &c, 1) != 1) return "";
      if (c == '\n') return s;
      s += c;
    }
    return "";
  }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
};

// A scratch folder, removed at the end.
struct TempDir {
  std::filesystem::path p;
  TempDir()
  {
    char tmpl[] = "/tmp/kestrel_hwil_XXXXXX";
    p = ::mkdtemp(tmpl);
  }
  ~TempDir()
  {
    std::error_code ec;
    std::filesystem::remove_all(p, ec);
  }
};

// A socat pseudo-terminal pair: end_a() and end_b() are the two device
// links (in dir); waits (bounded, polling the links) until both exist.
class PtyPair {
 public:
  PtyPair(const std::string& socat, const std::filesystem::path& dir, double timeout_s)
      : a_((dir / "pty_a").string()), b_((dir / "pty_b").string())
  {
    child_ = std::make_unique<Child>(
        std::vector<std::string>{socat, "pty,raw,echo=0,link=" + a_, "pty,raw,echo=0,link=" + b_});
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!(std::filesystem::exists(a_) && std::filesystem::exists(b_))) {
      if (std::chrono::steady_clock::now() > end) throw std::runtime_error("socat made no pty pair");
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  const std::string& end_a() const { return a_; }
  const std::string& end_b() const { return b_; }

 private:
  std::string a_, b_;
  std::unique_ptr<Child> child_;
};

}  // namespace hwil

#endif
