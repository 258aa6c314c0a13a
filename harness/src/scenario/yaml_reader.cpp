// yaml_reader.cpp: see yaml_reader.h.
#include "scenario/yaml_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <yaml-cpp/eventhandler.h>

namespace harness {

void Ctx::error(const YAML::Node& at, const std::string& key, const std::string& msg) const
{
  ScenarioIssue is;
  is.file = file;
  is.key = key;
  is.message = msg;
  for (const std::string& o : overridden) {
    if (key == o || key.rfind(o + ".", 0) == 0 || key.rfind(o + "[", 0) == 0) {
      is.where = "--set " + o;
      break;
    }
  }
  if (is.where.empty() && at.IsDefined()) {
    const YAML::Mark m = at.Mark();
    if (m.line >= 0) {
      is.line = m.line + 1;
      is.column = m.column + 1;
    }
  }
  if (is.where.empty() && is.line == 0) {
    // a node the command line created (e.g. the 'a' of --set a.b=1)
    for (const std::string& o : overridden)
      if (o.rfind(key + ".", 0) == 0 || o.rfind(key + "[", 0) == 0) {
        is.where = "--set " + o;
        break;
      }
  }
  issues->push_back(is);
}

std::string kind_name(const YAML::Node& n)
{
  switch (n.Type()) {
    case YAML::NodeType::Null: return "an empty value (null)";
    case YAML::NodeType::Scalar: return "scalar '" + n.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "undefined";
  }
}

std::string fmt(double v)
{
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string join(const std::string& path, const std::string& key)
{
  return path.empty() ? key : path + "." + key;
}

bool plain_decimal_value(const std::string& s, double& out)
{
  const char* p = s.data();
  const char* const end = p + s.size();
  if (p != end && (*p == '+' || *p == '-')) ++p;
  const char* const num = p;
  size_t digits = 0;
  for (; p != end && *p >= '0' && *p <= '9'; ++p) ++digits;
  if (p != end && *p == '.')
    for (++p; p != end && *p >= '0' && *p <= '9'; ++p) ++digits;
  if (digits == 0) return false;
  if (p != end && (*p == 'e' || *p == 'E')) {
    ++p;
    if (p != end && (*p == '+' || *p == '-')) ++p;
    const char* const exp = p;
    while (p != end && *p >= '0' && *p <= '9') ++p;
    if (p == exp) return false;
  }
  if (p != end) return false;
  // from_chars takes no '+' sign: the value of "+x" is that of "x".
  const char* const first = s[0] == '+' ? num : s.data();
  double v = 0.0;
  const std::from_chars_result r = std::from_chars(first, end, v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != end || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool decode_double(const YAML::Node& n, double& out)
{
  if (!n.IsScalar()) return false;
  const std::string& s = n.Scalar();
  if (plain_decimal_value(s, out)) return true;  // what the conversion below gives such text, without a stream
  // yaml-cpp accepts ".nan"/".inf"; callers reject non-finite values.
  // Refuse booleans or other words that happen to convert.
  return YAML::convert<double>::decode(n, out) && !s.empty();
}

bool decode_int(const YAML::Node& n, long long& out)
{
  if (!n.IsScalar()) return false;
  return YAML::convert<long long>::decode(n, out);
}

std::string did_you_mean(const std::string& k, const std::vector<std::string>& known)
{
  // smallest edit distance among the known words, if close
  std::string best;
  size_t best_d = 3;
  for (const std::string& u : known) {
    const size_t n = k.size(), m = u.size();
    std::vector<size_t> prev(m + 1), cur(m + 1);
    for (size_t j = 0; j <= m; ++j) prev[j] = j;
    for (size_t i = 1; i <= n; ++i) {
      cur[0] = i;
      for (size_t j = 1; j <= m; ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (k[i - 1] == u[j - 1] ? 0 : 1)});
      std::swap(prev, cur);
    }
    if (prev[m] < best_d) {
      best_d = prev[m];
      best = u;
    }
  }
  return best;
}

std::string check_unit_vector(Eigen::Vector3d& v)
{
  const double n = v.norm();
  if (!(std::fabs(n - 1.0) <= kUnitTol))
    return "must be a unit vector (|v| = 1 within " + fmt(kUnitTol) + "), |v| = " + fmt(n);
  // Renormalise, but leave an already-normalised vector bit-for-bit alone
  // so a manifest reloads to exactly the same values.
  if (!(std::fabs(n - 1.0) <= 4.0 * std::numeric_limits<double>::epsilon())) v /= n;
  return "";
}

std::string check_inertia(const Eigen::Matrix3d& m)
{
  if (!m.allFinite()) return "inertia must be finite";
  const double scale = m.cwiseAbs().maxCoeff();
  if (!((m - m.transpose()).cwiseAbs().maxCoeff() <= kSymTol * scale)) return "inertia must be symmetric";
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m);
  if (!(es.eigenvalues().minCoeff() > 0.0))
    return "inertia must be positive definite (smallest eigenvalue " + fmt(es.eigenvalues().minCoeff()) +
           " kg*m^2)";
  const Eigen::Vector3d ev = es.eigenvalues();
  if (ev(0) + ev(1) < ev(2) * (1.0 - 1e-12))
    return "inertia violates the triangle inequality (principal moments " + fmt(ev(0)) + ", " + fmt(ev(1)) +
           ", " + fmt(ev(2)) + ")";
  return "";
}

// ---- bounds on the text -------------------------------------------------------

ScenarioIssue file_issue(const std::string& file, int line, int col, const std::string& msg)
{
  ScenarioIssue is;
  is.file = file;
  is.line = line;
  is.column = col;
  is.key = "(file)";
  is.message = msg;
  return is;
}

namespace {

// Counts nodes as the parser reports them: each anchor's expanded size is
// known when its node ends, an alias adds that size without expanding it.
class BoundsHandler : public YAML::EventHandler {
 public:
  BoundsHandler(const std::string& text, const std::string& file, std::vector<ScenarioIssue>& issues)
      : text_(text), file_(file), issues_(issues)
  {
  }
  bool failed() const { return !issues_.empty(); }
  int documents = 0;

  void OnDocumentStart(const YAML::Mark& m) override
  {
    if (++documents == 2)
      fail(m, "a second YAML document (after '---'): a scenario file holds exactly one");
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t a) override { leaf(m, a); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t a, const std::string&) override
  {
    check_quote(m);
    leaf(m, a);
  }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t a) override
  {
    for (const Open& o : open_)
      if (o.anchor == a && a != 0) {
        fail(m, "an alias inside the node its anchor names (a cycle)");
        return;
      }
    const auto it = sizes_.find(a);
    add(m, it == sizes_.end() ? 1 : it->second);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t a, YAML::EmitterStyle::value) override
  {
    start(m, a, false);
  }
  void OnSequenceEnd() override { end(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t a, YAML::EmitterStyle::value) override
  {
    start(m, a, true);
  }
  void OnMapEnd() override { end(); }

 private:
  struct Open {
    YAML::anchor_t anchor;
    size_t size;     // expanded nodes inside so far (itself included)
    size_t entries;  // direct children (a map's keys and values both count)
    bool is_map;
  };
  // A quoted scalar must close on the line it opens on: YAML lets a quoted
  // string run over lines (up to the end of the file when the quote is never
  // closed), which turns an unclosed quote into a dozen unrelated problems.
  void check_quote(const YAML::Mark& m)
  {
    if (m.pos < 0 || static_cast<size_t>(m.pos) >= text_.size()) return;
    const char q = text_[static_cast<size_t>(m.pos)];
    if (q != '"' && q != '\'') return;
    for (size_t i = static_cast<size_t>(m.pos) + 1; i < text_.size(); ++i) {
      const char c = text_[i];
      if (c == '\n' || c == '\r') break;
      if (q == '"' && c == '\\') {
        ++i;  // an escape: the next character is not the closing quote
      } else if (c == q) {
        if (q == '\'' && i + 1 < text_.size() && text_[i + 1] == '\'') ++i;  // '' is an escaped quote
        else return;
      }
    }
    fail(m, std::string("unclosed quote: the ") + (q == '"' ? "double" : "single") +
                " quote opened here does not close on this line");
  }
  void fail(const YAML::Mark& m, const std::string& msg)
  {
    if (issues_.empty()) issues_.push_back(file_issue(file_, m.line + 1, m.column + 1, msg));
  }
  void add(const YAML::Mark& m, size_t n)
  {
    total_ += n;
    if (total_ > kMaxYamlNodes) {
      fail(m, "more than " + std::to_string(kMaxYamlNodes) +
                  " nodes once aliases are expanded (an alias bomb?); a scenario has a few hundred");
      return;
    }
    if (open_.empty()) return;
    Open& o = open_.back();
    o.size += n;
    if (++o.entries > (o.is_map ? 2 : 1) * kMaxYamlList)
      fail(m, std::string(o.is_map ? "a map" : "a list") + " with more than " + std::to_string(kMaxYamlList) +
                  " entries");
  }
  void leaf(const YAML::Mark& m, YAML::anchor_t a)
  {
    if (a != 0) sizes_[a] = 1;
    add(m, 1);
  }
  void start(const YAML::Mark& m, YAML::anchor_t a, bool is_map)
  {
    add(m, 1);
    open_.push_back({a, 1, 0, is_map});
    if (open_.size() > kMaxYamlDepth)
      fail(m, "nested more than " + std::to_string(kMaxYamlDepth) + " levels deep");
  }
  void end()
  {
    if (open_.empty()) return;
    const Open o = open_.back();
    open_.pop_back();
    if (o.anchor != 0) sizes_[o.anchor] = o.size;
    // the children were already counted in total_; the parent grows by them
    if (!open_.empty()) open_.back().size += o.size - 1;
  }

  const std::string& text_;
  const std::string& file_;
  std::vector<ScenarioIssue>& issues_;
  std::vector<Open> open_;
  std::map<YAML::anchor_t, size_t> sizes_;
  size_t total_ = 0;
};

// A NUL or control byte (tab, line feed and carriage return are text).
bool is_control(unsigned char c) { return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f; }

}  // namespace

std::vector<ScenarioIssue> check_yaml_text(const std::string& text, const std::string& file)
{
  std::vector<ScenarioIssue> issues;
  if (text.size() > kMaxYamlBytes) {
    issues.push_back(file_issue(file, 0, 0, "file too large (" + std::to_string(text.size()) + " bytes; at most " +
                                                std::to_string(kMaxYamlBytes) + "): a scenario is a few kilobytes"));
    return issues;
  }
  int line = 1, col = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (is_control(c)) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "0x%02X", c);
      issues.push_back(file_issue(file, line, col,
                                  std::string(c == 0 ? "NUL byte" : "control byte ") + (c == 0 ? "" : buf) +
                                      " in the text: a scenario is YAML text, not binary data"));
      return issues;
    }
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  std::istringstream in(text);
  BoundsHandler h(text, file, issues);
  try {
    YAML::Parser parser(in);
    while (!h.failed() && parser.HandleNextDocument(h)) {
    }
  } catch (const YAML::Exception& e) {
    if (issues.empty())
      issues.push_back(file_issue(file, e.mark.line + 1, e.mark.column + 1, "YAML syntax error: " + e.msg));
  }
  return issues;
}

void collect_key_lines(const YAML::Node& n, const std::string& path, std::map<std::string, std::pair<int, int>>& out)
{
  if (n.IsMap()) {
    for (auto it = n.begin(); it != n.end(); ++it) {
      if (!it->first.IsScalar()) continue;
      const std::string k = join(path, it->first.Scalar());
      const YAML::Mark m = it->first.Mark();
      if (m.line >= 0) out[k] = {m.line + 1, m.column + 1};
      collect_key_lines(it->second, k, out);
    }
  } else if (n.IsSequence()) {
    for (size_t i = 0; i < n.size(); ++i) {
      const std::string k = path + "[" + std::to_string(i) + "]";
      const YAML::Mark m = n[i].Mark();
      if (m.line >= 0) out[k] = {m.line + 1, m.column + 1};
      collect_key_lines(n[i], k, out);
    }
  }
}

// ---- MapReader ----------------------------------------------------------------

MapReader::MapReader(const Ctx& ctx, const YAML::Node& node, std::string path, bool present)
    : ctx_(&ctx), node_(pick(ctx, node, path, present)), path_(std::move(path))
{
  synthetic_ = !(present && node.IsDefined() && node.IsMap());
  if (synthetic_) return;
  // duplicate keys
  std::set<std::string> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) {
      ctx.error(it->first, path_.empty() ? "(top level)" : path_, "keys must be plain names, got " + kind_name(it->first));
      continue;
    }
    const std::string k = it->first.Scalar();
    if (!seen.insert(k).second) ctx.error(it->first, join(path_, k), "duplicate key");
  }
}

// The map to read, or a fresh empty map (absent, null or not a map; the
// last is reported here).  Never assigns to an invalid (zombie) node.
YAML::Node MapReader::pick(const Ctx& ctx, const YAML::Node& node, const std::string& path, bool present)
{
  if (present && node.IsDefined() && node.IsMap()) return node;
  if (present && node.IsDefined() && !node.IsNull())
    ctx.error(node, path.empty() ? "(top level)" : path, "expected a map of keys, got " + kind_name(node));
  return YAML::Node(YAML::NodeType::Map);
}

std::string MapReader::key_path(const std::string& key) const
{
  auto it = alias_.find(key);
  return it != alias_.end() ? join(it->second, key) : join(path_, key);
}

YAML::Node MapReader::at(const std::string& key, const YAML::Node& v) const
{
  // An empty value (`mass:`) has no place of its own (the parser puts it at
  // the next token, often the next key's line): name the key's place.
  if (v.IsDefined() && !v.IsNull()) return v;
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) return it->first;
  return v;
}

std::nullopt_t MapReader::empty_value(const std::string& key, const std::string& expected)
{
  error_at_key(key, "expected " + expected + ", got an empty value");
  return std::nullopt;
}

YAML::Node MapReader::get(const std::string& key)
{
  used_.insert(key);
  const YAML::Node& cn = node_;  // const lookup: a missing key is undefined, never created
  return cn[key];
}

void MapReader::error_at(const std::string& key, const std::string& msg)
{
  const YAML::Node& cn = node_;
  const YAML::Node v = cn[key];
  ctx_->error(v.IsDefined() ? at(key, v) : node_, key_path(key), msg);
}

void MapReader::error_at_key(const std::string& key, const std::string& msg)
{
  ctx_->error(at(key, YAML::Node(YAML::NodeType::Null)), key_path(key), msg);
}

void MapReader::error_self(const std::string& msg) { ctx_->error(node_, path_, msg); }

void MapReader::missing(const std::string& key, const std::string& what)
{
  ctx_->error(node_, key_path(key), "required key missing (" + what + ")");
}

std::optional<double> MapReader::real(const std::string& key, const NumberCheck& check, double factor)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  double x = 0.0;
  if (!decode_double(v, x)) {
    ctx_->error(at(key, v), key_path(key), "expected a number, got " + kind_name(v));
    return std::nullopt;
  }
  if (!std::isfinite(x)) {
    ctx_->error(at(key, v), key_path(key), "must be finite, got " + v.Scalar());
    return std::nullopt;
  }
  if (check) {
    const std::string why = check(x);
    if (!why.empty()) {
      ctx_->error(at(key, v), key_path(key), why + ", got " + v.Scalar());
      return std::nullopt;
    }
  }
  return x * factor;
}

std::optional<bool> MapReader::spelling(const std::string& key, const std::string& suffix)
{
  const bool a = has(key), b = has(key + suffix);
  used_.insert(key);
  used_.insert(key + suffix);
  if (a && b) {
    error_at(key + suffix, "give either '" + key + "' or '" + key + suffix + "', not both");
    return std::nullopt;
  }
  return b;
}

std::optional<double> MapReader::quantity(const std::string& key, const std::string& suffix, double factor,
                                          const NumberCheck& check)
{
  const std::optional<bool> suffixed = spelling(key, suffix);
  if (!suffixed) return std::nullopt;
  return *suffixed ? real(key + suffix, check, factor) : real(key, check);
}

std::optional<long long> MapReader::integer(const std::string& key, long long lo, long long hi)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  long long x = 0;
  if (!decode_int(v, x)) {
    ctx_->error(at(key, v), key_path(key), "expected an integer, got " + kind_name(v));
    return std::nullopt;
  }
  if (x < lo || x > hi) {
    ctx_->error(at(key, v), key_path(key),
                "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + v.Scalar());
    return std::nullopt;
  }
  return x;
}

std::optional<uint64_t> MapReader::uinteger(const std::string& key)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  unsigned long long x = 0;
  if (!v.IsScalar() || v.Scalar().empty() || v.Scalar()[0] == '-' ||
      !YAML::convert<unsigned long long>::decode(v, x)) {
    ctx_->error(at(key, v), key_path(key), "expected a non-negative integer, got " + kind_name(v));
    return std::nullopt;
  }
  return static_cast<uint64_t>(x);
}

std::optional<bool> MapReader::boolean(const std::string& key)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  bool x = false;
  if (!v.IsScalar() || !YAML::convert<bool>::decode(v, x)) {
    ctx_->error(at(key, v), key_path(key), "expected true or false, got " + kind_name(v));
    return std::nullopt;
  }
  return x;
}

std::optional<std::string> MapReader::string(const std::string& key)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  if (!v.IsScalar()) {
    ctx_->error(at(key, v), key_path(key), "expected a string, got " + kind_name(v));
    return std::nullopt;
  }
  return v.Scalar();
}

std::optional<size_t> MapReader::choice(const std::string& key, const std::vector<std::string>& options)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  std::string all;
  for (size_t i = 0; i < options.size(); ++i) all += (i ? ", " : "") + options[i];
  if (v.IsScalar()) {
    for (size_t i = 0; i < options.size(); ++i)
      if (v.Scalar() == options[i]) return i;
  }
  ctx_->error(at(key, v), key_path(key), "expected one of {" + all + "}, got " + kind_name(v));
  return std::nullopt;
}

std::optional<Eigen::Vector3d> MapReader::vec3(const std::string& key, double factor)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  if (v.IsNull()) return empty_value(key, "a list of 3 numbers");
  return vec3_of(v, key_path(key), factor);
}

std::optional<Eigen::Vector3d> MapReader::vec3_of(const YAML::Node& v, const std::string& kp, double factor)
{
  if (!v.IsSequence() || v.size() != 3) {
    ctx_->error(v, kp, "expected a list of 3 numbers, got " +
                           (v.IsSequence() ? "a list of " + std::to_string(v.size()) : kind_name(v)));
    return std::nullopt;
  }
  Eigen::Vector3d out;
  for (size_t i = 0; i < 3; ++i) {
    double x = 0.0;
    if (!decode_double(v[i], x)) {
      ctx_->error(v[i], kp + "[" + std::to_string(i) + "]", "expected a number, got " + kind_name(v[i]));
      return std::nullopt;
    }
    if (!std::isfinite(x)) {
      ctx_->error(v[i], kp + "[" + std::to_string(i) + "]", "must be finite, got " + v[i].Scalar());
      return std::nullopt;
    }
    out(static_cast<int>(i)) = x * factor;
  }
  return out;
}

std::optional<Eigen::Vector3d> MapReader::unit_vec3(const std::string& key)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  if (v.IsNull()) return empty_value(key, "a unit vector of 3 numbers");
  return unit_of(v, key_path(key));
}

std::optional<Eigen::Vector3d> MapReader::unit_of(const YAML::Node& v, const std::string& kp)
{
  auto u = vec3_of(v, kp);
  if (!u) return std::nullopt;
  const std::string why = check_unit_vector(*u);
  if (!why.empty()) {
    ctx_->error(v, kp, why);
    return std::nullopt;
  }
  return u;
}

std::optional<Eigen::Matrix3d> MapReader::inertia(const std::string& key)
{
  YAML::Node v = get(key);
  if (!v.IsDefined()) return std::nullopt;
  if (v.IsNull()) return empty_value(key, "3 diagonal values or a 3x3 list of lists");
  const std::string kp = key_path(key);
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  if (v.IsSequence() && v.size() == 3 && v[0].IsScalar()) {
    auto d = vec3_of(v, kp);
    if (!d) return std::nullopt;
    m = d->asDiagonal();
  } else if (v.IsSequence() && v.size() == 3) {
    for (size_t r = 0; r < 3; ++r) {
      auto row = vec3_of(v[r], kp + "[" + std::to_string(r) + "]");
      if (!row) return std::nullopt;
      m.row(static_cast<int>(r)) = row->transpose();
    }
  } else {
    ctx_->error(v, kp, "expected 3 diagonal values or a 3x3 list of lists, got " + kind_name(v));
    return std::nullopt;
  }
  const std::string why = check_inertia(m);
  if (!why.empty()) {
    ctx_->error(v, kp, why);
    return std::nullopt;
  }
  return m;
}

void MapReader::finish(const std::set<std::string>& ignore)
{
  if (synthetic_) return;
  const std::vector<std::string> known(used_.begin(), used_.end());
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) continue;
    const std::string k = it->first.Scalar();
    if (used_.count(k) || ignore.count(k)) continue;
    if (k.empty()) {  // `: 1`, a bare tag `!` or `""` as a key: name where it is, not ""
      ctx_->error(it->first, path_.empty() ? std::string("(top level)") : path_,
                  "a key with no name (empty, \"\" or a bare tag)");
      continue;
    }
    std::string msg = "unknown key";
    const std::string near = did_you_mean(k, known);
    if (!near.empty()) msg += " (did you mean '" + near + "'?)";
    ctx_->error(it->first, key_path(k), msg);
  }
}

MapReader MapReader::sub(const std::string& key)
{
  YAML::Node v = get(key);
  return MapReader(*ctx_, v, key_path(key), v.IsDefined());
}

}  // namespace harness
