#include "harness/link/pil.h"

#include "harness/link/cfs_link.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#ifndef KESTREL_PIL_BIN_AARCH64_LINUX
#define KESTREL_PIL_BIN_AARCH64_LINUX ""
#endif
#ifndef KESTREL_PIL_BIN_ARMHF_LINUX
#define KESTREL_PIL_BIN_ARMHF_LINUX ""
#endif
#ifndef KESTREL_PIL_BIN_CORTEX_M4F
#define KESTREL_PIL_BIN_CORTEX_M4F ""
#endif
#ifndef KESTREL_PIL_BIN_CORTEX_M4F_FLOAT
#define KESTREL_PIL_BIN_CORTEX_M4F_FLOAT ""
#endif

namespace harness {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Where kestrel-fsw-m4f reads its configuration image (its
// KESTREL_M4F_CONFIG_ADDR, flight/m4f/CMakeLists.txt).
constexpr const char* kM4fConfigAddr = "0x00380000";
constexpr double kStopGrace = 2.0;  // [s] SIGTERM -> SIGKILL

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::vector<std::string> split_words(const std::string& s)
{
  std::istringstream is(s);
  std::vector<std::string> w;
  for (std::string x; is >> x;) w.push_back(x);
  return w;
}

std::string join(const std::vector<std::string>& v)
{
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// A private folder for the image, the socket and the emulator's output.
class TempFolder {
 public:
  TempFolder()
  {
    std::string tmpl = "/tmp/kestrel-pil-XXXXXX";  // short: a unix socket path is limited to 107 bytes
    if (::mkdtemp(tmpl.data()) == nullptr)
      throw FswEndpointError(std::string("PIL (harness side): cannot create a temporary folder: ") +
                             std::strerror(errno));
    p_ = tmpl;
  }
  ~TempFolder()
  {
    std::error_code ec;
    fs::remove_all(p_, ec);
  }
  const fs::path& path() const { return p_; }

 private:
  fs::path p_;
};

// The emulator, in a process group of its own (a terminal's Ctrl-C goes to
// the harness, which then stops it in order), stdout on a pipe, stderr in a
// file, killed with the harness (PR_SET_PDEATHSIG).
class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& argv, const fs::path& err_file) : err_file_(err_file)
  {
    int out[2];
    if (::pipe2(out, O_CLOEXEC) != 0)
      throw FswEndpointError(std::string("PIL (harness side): pipe: ") + std::strerror(errno));
    const pid_t parent = ::getpid();
    std::vector<char*> av;
    for (const auto& a : argv) av.push_back(const_cast<char*>(a.c_str()));
    av.push_back(nullptr);
    const std::string errp = err_file.string();
    pid_ = ::fork();
    if (pid_ < 0) {
      ::close(out[0]);
      ::close(out[1]);
      throw FswEndpointError(std::string("PIL (harness side): fork: ") + std::strerror(errno));
    }
    if (pid_ == 0) {  // child: async-signal-safe calls only
      ::setpgid(0, 0);
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(126);
      const int in = ::open("/dev/null", O_RDONLY);
      const int err = ::open(errp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      if (in >= 0) ::dup2(in, 0);
      ::dup2(out[1], 1);
      if (err >= 0) ::dup2(err, 2);
      ::execvp(av[0], av.data());
      const char* m = "kestrel: cannot execute the emulator: ";
      (void)!::write(2, m, std::strlen(m));
      (void)!::write(2, av[0], std::strlen(av[0]));
      (void)!::write(2, ": ", 2);
      (void)!::write(2, std::strerror(errno), std::strlen(std::strerror(errno)));
      (void)!::write(2, "\n", 1);
      ::_exit(127);
    }
    ::setpgid(pid_, pid_);  // also here: no race with a stop right after the fork
    ::close(out[1]);
    out_ = out[0];
  }
  ~ChildProcess()
  {
    stop();
    if (out_ >= 0) ::close(out_);
  }
  pid_t pid() const { return pid_; }

  // true once it has ended (reaped; status_ set)
  bool ended()
  {
    if (reaped_) return true;
    int st = 0;
    if (::waitpid(pid_, &st, WNOHANG) == pid_) {
      reaped_ = true;
      status_ = st;
    }
    return reaped_;
  }

  std::string end_text() const
  {
    std::ostringstream os;
    if (WIFEXITED(status_))
      os << "exited with status " << WEXITSTATUS(status_);
    else if (WIFSIGNALED(status_))
      os << "was killed by signal " << WTERMSIG(status_);
    else
      os << "ended";
    return os.str();
  }

  // The last lines of its stderr.
  std::string output_tail() const
  {
    std::ifstream f(err_file_);
    std::vector<std::string> lines;
    for (std::string l; std::getline(f, l);)
      if (!l.empty()) lines.push_back(l);
    const size_t from = lines.size() > 4 ? lines.size() - 4 : 0;
    std::string s;
    for (size_t i = from; i < lines.size(); ++i) s += (s.empty() ? "" : " | ") + lines[i];
    return s.empty() ? "(no output)" : s;
  }

  // One line of its stdout within timeout_s; false on timeout or end.
  bool read_line(std::string& line, double timeout_s)
  {
    const auto t0 = Clock::now();
    for (;;) {
      const auto nl = out_buf_.find('\n');
      if (nl != std::string::npos) {
        line = out_buf_.substr(0, nl);
        out_buf_.erase(0, nl + 1);
        return true;
      }
      const double left = timeout_s - seconds_since(t0);
      if (left <= 0) return false;
      pollfd p{out_, POLLIN, 0};
      const int rc = ::poll(&p, 1, static_cast<int>(std::min(left, 0.1) * 1000.0) + 1);
      if (rc < 0 && errno != EINTR) return false;
      if (rc > 0) {
        char b[256];
        const ssize_t n = ::read(out_, b, sizeof b);
        if (n <= 0) {  // stdout closed: it is ending; give it a moment to be reaped
          const auto t1 = Clock::now();
          while (!ended() && seconds_since(t1) < kStopGrace) std::this_thread::sleep_for(std::chrono::milliseconds(5));
          return false;
        }
        out_buf_.append(b, static_cast<size_t>(n));
      }
    }
  }

  // SIGTERM to the group, SIGKILL after a grace period, reaped.
  void stop()
  {
    if (ended()) return;
    ::kill(-pid_, SIGTERM);
    const auto t0 = Clock::now();
    while (!ended() && seconds_since(t0) < kStopGrace) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(-pid_, SIGKILL);
    if (!reaped_) {
      int st = 0;
      while (::waitpid(pid_, &st, 0) < 0 && errno == EINTR) {
      }
      reaped_ = true;
      status_ = st;
    }
  }

 private:
  pid_t pid_ = -1;
  int out_ = -1;
  bool reaped_ = false;
  int status_ = 0;
  fs::path err_file_;
  std::string out_buf_;
};

// The link to the emulated FSW, owning the emulator: receive waits in short
// slices and notices the emulator's end at once.
class PilTransport : public LinkTransport {
 public:
  PilTransport(std::string what, std::unique_ptr<TempFolder> dir, std::unique_ptr<ChildProcess> child)
      : what_(std::move(what)), dir_(std::move(dir)), child_(std::move(child))
  {
  }
  ~PilTransport() override
  {
    link_.reset();  // close our end first (the emulator sees EOF / nothing)
    child_.reset();
  }
  void set_link(std::unique_ptr<LinkTransport> l) { link_ = std::move(l); }
  bool datagram() const override { return link_ && link_->datagram(); }  // Linux targets: UDP, retransmitted
  std::string describe() const override
  {
    return what_ + " (pid " + std::to_string(child_->pid()) + "), " + (link_ ? link_->describe() : "not connected");
  }
  void send(const uint8_t* p, size_t n) override
  {
    check_alive("");
    try {
      link_->send(p, n);
    } catch (const FswEndpointError& e) {
      link_broke(e);
    }
  }
  // The link broke (the emulator's socket closed): say why if the emulator
  // is ending.
  [[noreturn]] void link_broke(const FswEndpointError& e)
  {
    const auto t0 = Clock::now();
    while (!child_->ended() && seconds_since(t0) < kStopGrace) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    check_alive("during the run");
    throw FswEndpointError(std::string(e.what()) + " (the emulated FSW, " + what_ + ", is still running; its output: " +
                           child_->output_tail() + ")");
  }
  bool recv(std::vector<uint8_t>& pkt, double timeout_s) override
  {
    const auto t0 = Clock::now();
    for (;;) {
      const double left = timeout_s - seconds_since(t0);
      bool got = false;
      try {
        got = link_->recv(pkt, std::max(0.0, std::min(left, 0.2)));
      } catch (const FswEndpointError& e) {
        link_broke(e);
      }
      if (got) return true;
      check_alive("during the run");
      if (left <= 0.2) return false;
    }
  }
  std::string diagnose() const override
  {
    return "FSW side: the emulated FSW is still running but did not answer; the harness sent its packet. Its output: " +
           child_->output_tail();
  }
  void check_alive(const std::string& when)
  {
    if (child_->ended())
      throw FswEndpointError("PIL (FSW side): the emulated FSW (" + what_ + ") " + child_->end_text() +
                             (when.empty() ? "" : " " + when) + "; its output: " + child_->output_tail());
  }
  ChildProcess& child() { return *child_; }
  const fs::path& dir() const { return dir_->path(); }

 private:
  std::string what_;
  std::unique_ptr<TempFolder> dir_;
  std::unique_ptr<ChildProcess> child_;
  std::unique_ptr<LinkTransport> link_;
};

void write_image(const FswAcsConfig& cfg, const fs::path& file)
{
  std::vector<uint8_t> img(fsw_link_config_size());
  size_t len = 0;
  if (fsw_link_config_encode(&cfg, img.data(), img.size(), &len, nullptr) != FSW_OK)
    throw FswEndpointError("PIL (harness side): cannot encode the FSW configuration image");
  std::ofstream f(file, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(img.data()), static_cast<std::streamsize>(len));
  f.close();
  if (!f) throw FswEndpointError("PIL (harness side): cannot write " + file.string());
}

// Connects to the emulator's UART socket; retries until it listens.
std::unique_ptr<LinkTransport> connect_uart(const fs::path& sock, PilTransport& t, double timeout_s,
                                            const std::string& what)
{
  const auto t0 = Clock::now();
  for (;;) {
    t.check_alive("before its UART socket opened");
    auto link = connect_unix_transport(sock.string(), "UART0 on unix socket " + sock.string());
    if (link) return link;
    if (seconds_since(t0) > timeout_s)
      throw FswEndpointError("PIL (FSW side): the emulator (" + what + ") did not open its UART socket within " +
                             std::to_string(timeout_s) + " s; it was stopped. Its output: " +
                             t.child().output_tail());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

const std::vector<PilTarget>& pil_targets()
{
  static const std::vector<PilTarget> k = {
      {"aarch64-linux", KESTREL_PIL_BIN_AARCH64_LINUX, {"qemu-aarch64", "-L", "/usr/aarch64-linux-gnu"}, false},
      {"armhf-linux", KESTREL_PIL_BIN_ARMHF_LINUX, {"qemu-arm", "-L", "/usr/arm-linux-gnueabihf"}, false},
      {"cortex-m4f", KESTREL_PIL_BIN_CORTEX_M4F, {"qemu-system-arm", "-M", "mps2-an386", "-cpu", "cortex-m4"}, true},
      {"cortex-m4f-float",
       KESTREL_PIL_BIN_CORTEX_M4F_FLOAT,
       {"qemu-system-arm", "-M", "mps2-an386", "-cpu", "cortex-m4"},
       true},
  };
  return k;
}

std::unique_ptr<LinkTransport> open_pil_transport(const std::string& spec, const FswAcsConfig& cfg,
                                                  const LinkOptions& opt)
{
  const std::string name = spec.rfind("pil:", 0) == 0 ? spec.substr(4) : spec;
  const PilTarget* tgt = nullptr;
  std::string known;
  for (const PilTarget& t : pil_targets()) {
    if (t.name == name) tgt = &t;
    known += (known.empty() ? "" : ", ") + t.name;
  }
  if (tgt == nullptr) throw FswEndpointError("PIL: unknown target '" + name + "' (known: " + known + ")");
  const std::string bin = opt.pil_bin.empty() ? tgt->default_bin : opt.pil_bin;
  if (bin.empty())
    throw FswEndpointError("PIL (harness side): this build has no " + name +
                           " FSW program (its cross compiler or emulator was missing at configure time, or "
                           "KESTREL_BUILD_PIL is OFF); give one with --pil-bin FILE");
  if (!fs::is_regular_file(bin)) throw FswEndpointError("PIL (harness side): no FSW program at " + bin);
  std::vector<std::string> argv = opt.pil_emulator.empty() ? tgt->emulator : split_words(opt.pil_emulator);
  if (argv.empty()) throw FswEndpointError("PIL: empty --pil-emulator");
  const std::string what = fs::path(bin).filename().string() + " on " + argv[0] + " (" + name + ")";

  if (tgt->bare_metal && !opt.key_file.empty())
    throw FswEndpointError("PIL: --link-key: the " + name +
                           " target's UART link has no packet authentication (the Linux targets, over UDP, have)");
  auto dir = std::make_unique<TempFolder>();
  const fs::path img = dir->path() / "fsw.img", sock = dir->path() / "uart0.sock", err = dir->path() / "fsw.log";
  write_image(cfg, img);
  if (tgt->bare_metal) {
    // UART0 on a unix socket; wait=on: the guest starts once we connect, so
    // nothing it sends is lost.  -serial none is not used: the first
    // -serial is UART0.
    for (const std::string& a :
         {std::string("-nographic"), std::string("-monitor"), std::string("none"), std::string("-semihosting-config"),
          std::string("enable=on,target=native"), std::string("-chardev"),
          "socket,id=u0,path=" + sock.string() + ",server=on,wait=on", std::string("-serial"),
          std::string("chardev:u0"), std::string("-device"),
          "loader,file=" + img.string() + ",addr=" + kM4fConfigAddr, std::string("-kernel"), bin})
      argv.push_back(a);
  } else {
    for (const std::string& a : {bin, std::string("--udp"), std::string("127.0.0.1:0"), std::string("--config"),
                                 img.string()})
      argv.push_back(a);
    if (!opt.key_file.empty()) {  // the emulated kestrel-fsw reads the same key file
      argv.push_back("--key");
      argv.push_back(opt.key_file);
    }
  }
  auto child = std::make_unique<ChildProcess>(argv, err);
  auto t = std::make_unique<PilTransport>(what, std::move(dir), std::move(child));
  if (tgt->bare_metal) {
    t->set_link(connect_uart(sock, *t, opt.timeout_s, what));
    return t;
  }
  // kestrel-fsw prints "kestrel-fsw: ready udp 127.0.0.1:PORT" when it listens
  const std::string pre = "kestrel-fsw: ready udp ";
  std::string line;
  const auto t0 = Clock::now();
  for (;;) {
    const double left = opt.timeout_s - seconds_since(t0);
    if (left > 0 && t->child().read_line(line, left)) {
      if (line.rfind(pre, 0) == 0) break;
      continue;  // anything else it prints first
    }
    t->check_alive("before it was ready");
    throw FswEndpointError("PIL (FSW side): the emulated FSW (" + what + ", pid " +
                           std::to_string(t->child().pid()) + ") did not report ready within " +
                           std::to_string(opt.timeout_s) + " s; it was stopped. Command: " + join(argv) +
                           ". Its output: " + t->child().output_tail());
  }
  t->set_link(open_link_transport("udp:" + line.substr(pre.size()), opt.key_file));
  return t;
}

std::unique_ptr<LinkTransport> open_fsw_transport(const std::string& spec, const FswAcsConfig& cfg,
                                                  const LinkOptions& opt)
{
  if (spec.rfind("pil:", 0) == 0) return open_pil_transport(spec, cfg, opt);
  if (spec.rfind("cfs:", 0) == 0) {
    if (!opt.key_file.empty())
      throw FswEndpointError("FSW link: --link-key: packet authentication needs a UDP link (udp:HOST:PORT)");
    return open_cfs_transport(spec.substr(4), opt.timeout_s);
  }
  return open_link_transport(spec, opt.key_file);
}

}  // namespace harness
