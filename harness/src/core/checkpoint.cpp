// checkpoint.cpp: the checkpoint file (docs/checkpoint.md, "Layout").
#include "harness/core/checkpoint.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

namespace harness {

uint64_t fnv1a64_bytes(uint64_t h, const void* p, size_t n)
{
  const auto* b = static_cast<const uint8_t*>(p);
  for (size_t i = 0; i < n; ++i) {
    h ^= b[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

namespace {

constexpr char kMagic[8] = {'K', 'S', 'T', 'R', 'L', 'C', 'K', 'P'};

// Saving: each part as its byte count (uint32) and its bytes.
class StateWriter final : public sim::StateIO {
 public:
  bool loading() const override { return false; }
  void bytes(const char*, void* p, std::size_t n) override
  {
    const auto n32 = static_cast<uint32_t>(n);
    const auto* b = static_cast<const uint8_t*>(p);
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(n32 >> (8 * i)));
    out.insert(out.end(), b, b + n);
  }
  std::vector<uint8_t> out;
};

// Restoring: every part must have the byte count the run has for it.
class StateReader final : public sim::StateIO {
 public:
  StateReader(const std::vector<uint8_t>& in, bool keep_streams) : in_(in), keep_streams_(keep_streams) {}
  bool loading() const override { return true; }
  void bytes(const char* what, void* p, std::size_t n) override
  {
    if (in_.size() - pos_ < 4) throw CheckpointError(std::string("checkpoint: the state ends before part ") + what);
    uint32_t m = 0;
    for (int i = 0; i < 4; ++i) m |= static_cast<uint32_t>(in_[pos_ + static_cast<size_t>(i)]) << (8 * i);
    pos_ += 4;
    if (m != n || in_.size() - pos_ < n) {
      std::ostringstream e;
      e << "checkpoint: part " << what << " holds " << m << " bytes, this run has " << n
        << " (a checkpoint of another build or configuration)";
      throw CheckpointError(e.str());
    }
    if (!keep_streams_ || std::strncmp(what, "rng.", 4) != 0) std::memcpy(p, in_.data() + pos_, n);
    pos_ += n;
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  const std::vector<uint8_t>& in_;
  const bool keep_streams_;  // the random streams (sim::Rng, parts "rng.*") keep the run's
  size_t pos_ = 0;
};

uint64_t fnv1a64(const uint8_t* p, size_t n) { return fnv1a64_bytes(kFnv1a64Start, p, n); }

void put_u32(std::vector<uint8_t>& o, uint32_t v)
{
  for (int i = 0; i < 4; ++i) o.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void put_u64(std::vector<uint8_t>& o, uint64_t v)
{
  for (int i = 0; i < 8; ++i) o.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void put_bytes(std::vector<uint8_t>& o, const uint8_t* p, size_t n)
{
  put_u64(o, n);
  o.insert(o.end(), p, p + n);
}
void put_text(std::vector<uint8_t>& o, const std::string& s)
{
  put_bytes(o, reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

// Reads the fields in order; a field past the end is a truncated file.
struct Cursor {
  const std::vector<uint8_t>& b;
  size_t end;  // the checksum's offset
  const std::string& path;
  size_t pos = 0;
  void need(size_t n) const
  {
    if (end - pos < n) throw CheckpointError(path + ": truncated checkpoint (a field runs past its end)");
  }
  uint64_t u(int bytes)
  {
    need(static_cast<size_t>(bytes));
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<uint64_t>(b[pos + static_cast<size_t>(i)]) << (8 * i);
    pos += static_cast<size_t>(bytes);
    return v;
  }
  std::vector<uint8_t> blob()
  {
    const uint64_t n = u(8);
    need(static_cast<size_t>(n));
    std::vector<uint8_t> out(b.begin() + static_cast<std::ptrdiff_t>(pos),
                             b.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += static_cast<size_t>(n);
    return out;
  }
  std::string text()
  {
    const std::vector<uint8_t> v = blob();
    return std::string(v.begin(), v.end());
  }
};

}  // namespace

std::vector<uint8_t> save_run_state(Run& run)
{
  StateWriter w;
  run.state_io(w);
  return std::move(w.out);
}

namespace {
void restore_state(Run& run, const std::vector<uint8_t>& state, bool keep_streams)
{
  StateReader r(state, keep_streams);
  try {
    run.state_io(r);
  } catch (const std::runtime_error& e) {
    throw CheckpointError(e.what());
  }
  if (!r.at_end()) throw CheckpointError("checkpoint: the state holds more than this run has (another configuration)");
}
}  // namespace

void restore_run_state(Run& run, const std::vector<uint8_t>& state) { restore_state(run, state, false); }

void restore_branch_state(Run& run, const std::vector<uint8_t>& state) { restore_state(run, state, true); }

uint64_t checkpoint_checksum(const std::vector<uint8_t>& file, const std::string& path)
{
  std::vector<uint8_t> state;
  decode_checkpoint(file, state, path);
  uint64_t sum = 0;
  for (int i = 0; i < 8; ++i) sum |= static_cast<uint64_t>(file[file.size() - 8 + static_cast<size_t>(i)]) << (8 * i);
  return sum;
}

std::vector<uint8_t> encode_checkpoint(const CheckpointInfo& info, const std::vector<uint8_t>& state)
{
  std::vector<uint8_t> o;
  o.reserve(state.size() + info.scenario_text.size() + 256);
  for (const char c : kMagic) o.push_back(static_cast<uint8_t>(c));
  put_u32(o, kCheckpointFormat);
  put_u32(o, info.accepts_events ? 1u : 0u);  // flags: bit 0 the run accepts events
  put_u64(o, info.tick);
  put_u64(o, info.total_ticks);
  put_u64(o, info.sink_rows);
  put_text(o, info.kestrel_version);
  put_text(o, info.scenario_name);
  put_text(o, info.scenario_text);
  put_text(o, info.outputs);
  put_bytes(o, state.data(), state.size());
  put_u64(o, fnv1a64(o.data(), o.size()));
  return o;
}

CheckpointInfo decode_checkpoint(const std::vector<uint8_t>& file, std::vector<uint8_t>& state, const std::string& path)
{
  if (file.size() < 24 || std::memcmp(file.data(), kMagic, 8) != 0)
    throw CheckpointError(path + ": not a Kestrel checkpoint (no KSTRLCKP magic)");
  Cursor c{file, file.size() - 8, path};
  c.pos = 8;
  const uint64_t format = c.u(4);
  if (format != kCheckpointFormat && format != 1)
    throw CheckpointError(path + ": checkpoint format " + std::to_string(format) + "; this kestrel reads format " +
                          std::to_string(kCheckpointFormat));
  uint64_t sum = 0;
  for (int i = 0; i < 8; ++i) sum |= static_cast<uint64_t>(file[file.size() - 8 + static_cast<size_t>(i)]) << (8 * i);
  if (sum != fnv1a64(file.data(), file.size() - 8))
    throw CheckpointError(path + ": checksum mismatch: the checkpoint is damaged (or was cut short); refused");
  const uint64_t flags = c.u(4);
  CheckpointInfo info;
  info.accepts_events = (flags & 1u) != 0;
  info.tick = c.u(8);
  info.total_ticks = c.u(8);
  info.sink_rows = c.u(8);
  info.kestrel_version = c.text();
  info.scenario_name = c.text();
  info.scenario_text = c.text();
  if (format >= 2) info.outputs = c.text();
  state = c.blob();
  if (c.pos != c.end) throw CheckpointError(path + ": checkpoint has bytes after its state");
  return info;
}

void write_checkpoint_file(const std::string& path, const std::vector<uint8_t>& bytes)
{
  const std::string tmp = path + ".tmp";
  auto fail = [&](const char* what) {
    const std::string e = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw CheckpointError(path + ": " + what + ": " + e + " (the previous checkpoint is kept)");
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create the temporary file");
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      fail("cannot write");
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("cannot flush to disk");
  }
  if (::close(fd) != 0) fail("cannot close");
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot rename into place");
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {  // the rename itself on disk
    ::fsync(dfd);
    ::close(dfd);
  }
}

std::vector<uint8_t> read_checkpoint_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(path + ": cannot open the checkpoint");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string first_difference(const std::string& a, const std::string& b)
{
  if (a == b) return "";
  std::istringstream x(a), y(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(x, la)), gb = static_cast<bool>(std::getline(y, lb));
    if (!ga) la = "(end)";
    if (!gb) lb = "(end)";
    if (la != lb || (!ga && !gb))
      return "line " + std::to_string(line) + ": checkpoint `" + la + "`, run `" + lb + "`";
  }
}

void save_checkpoint(Run& run, const std::string& path, const std::string& scenario_text, const std::string& outputs)
{
  CheckpointInfo info;
  info.tick = run.tick();
  info.total_ticks = run.total_ticks();
  info.sink_rows = run.recorder().sink_rows();
  info.kestrel_version = version();
  info.scenario_name = run.scenario().name;
  info.scenario_text = scenario_text;
  info.outputs = outputs;
  info.accepts_events = run.accepts_events();
  write_checkpoint_file(path, encode_checkpoint(info, save_run_state(run)));
}

CheckpointInfo restore_checkpoint(Run& run, const std::string& path, const std::string& scenario_text)
{
  std::vector<uint8_t> state;
  const CheckpointInfo info = decode_checkpoint(read_checkpoint_file(path), state, path);
  const std::string diff = first_difference(info.scenario_text, scenario_text);
  if (!diff.empty())
    throw CheckpointError(path + ": a checkpoint of scenario '" + info.scenario_name + "', not of this run's ('" +
                          run.scenario().name + "'): refused (" + diff + ")");
  restore_run_state(run, state);
  return info;
}

}  // namespace harness
