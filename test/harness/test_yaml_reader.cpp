// The generic YAML reader (harness/src/yaml_reader.h) alone, on small
// documents unrelated to the scenario schema: typed decoding, issues with
// file:line:col, unknown keys with a did-you-mean hint, alternative-unit
// spellings, unit vectors and inertia checks, --set attribution.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <malloc.h>
#include <random>

#include <yaml-cpp/yaml.h>

#include "scenario/yaml_reader.h"

namespace {

using harness::Ctx;
using harness::MapReader;
using harness::ScenarioIssue;

struct Doc {
  std::vector<ScenarioIssue> issues;
  Ctx ctx;
  YAML::Node root;
  explicit Doc(const std::string& text) : ctx{"d.yaml", &issues, {}}, root(YAML::Load(text)) {}
};

}  // namespace

TEST(YamlReader, DecodesTypesAndLeavesAbsentKeysUnset)
{
  Doc d("x: 2.5\nn: 7\nb: true\ns: hello\nc: blue\nv: [1, 2, 3]\nu: [0, 0, 1]\nI: [1, 2, 2.5]\nbig: 18446744073709551615\n");
  MapReader r(d.ctx, d.root, "");
  EXPECT_EQ(r.real("x"), 2.5);
  EXPECT_EQ(r.integer("n", 0, 10), 7);
  EXPECT_EQ(r.boolean("b"), true);
  EXPECT_EQ(r.string("s"), "hello");
  EXPECT_EQ(r.choice("c", {"red", "blue"}), 1u);
  EXPECT_EQ(*r.vec3("v"), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(*r.unit_vec3("u"), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(r.inertia("I")->diagonal(), Eigen::Vector3d(1, 2, 2.5));
  EXPECT_EQ(r.uinteger("big"), 18446744073709551615ull);
  EXPECT_FALSE(r.real("absent").has_value());
  r.finish();
  EXPECT_TRUE(d.issues.empty());
}

// decode_double reads a plain decimal literal without yaml-cpp's stream:
// the value must be the stream's, bit for bit.  The oracle is yaml-cpp's own
// conversion (YAML::convert<double>), an implementation independent of the
// fast path; the texts are the kinds a scenario or a manifest holds (the
// shortest round trip, 17 digits, fixed and exponent forms, integers) from
// random bit patterns, and the edges of the grammar.
TEST(YamlReader, PlainDecimalsReadAsYamlCppsConversionBitForBit)
{
  auto bits = [](double x) {
    uint64_t u = 0;
    std::memcpy(&u, &x, sizeof u);
    return u;
  };
  auto same_as_yaml_cpp = [&](const std::string& t) {
    double fast = 0.0, slow = 0.0;
    const bool f = harness::plain_decimal_value(t, fast);
    const bool sl = YAML::convert<double>::decode(YAML::Node(t), slow);
    double d = 0.0;
    const bool dd = harness::decode_double(YAML::Node(t), d);
    if (f) {  // taken: yaml-cpp reads the same double
      EXPECT_TRUE(sl) << t;
      EXPECT_EQ(bits(fast), bits(slow)) << t;
    }
    EXPECT_EQ(dd, sl && !t.empty()) << t;  // decode_double as before
    if (dd && sl && !std::isnan(slow)) {
      EXPECT_EQ(bits(d), bits(slow)) << t;
    }
    return f;
  };
  std::mt19937_64 g(20261207);
  int taken = 0, n = 0;
  for (int i = 0; i < 20000; ++i) {
    double x = 0.0;
    const uint64_t u = g();
    std::memcpy(&x, &u, sizeof x);
    if (!std::isfinite(x)) continue;
    const double y = std::ldexp(static_cast<double>(g() >> 11), -53) * 2e3 - 1e3;  // the range of most keys
    char b[64];
    for (double v : {x, y}) {
      for (const char* f : {"%.17g", "%.6g", "%.3e", "%.10f", "%.1E", "%+.12g"}) {
        std::snprintf(b, sizeof b, f, v);
        taken += same_as_yaml_cpp(b) ? 1 : 0;
        ++n;
      }
    }
  }
  EXPECT_GT(taken, n * 9 / 10);  // the fast path reads nearly all of them
  for (const char* t : {"0", "-0", "+0", "0.0", "-0.0", "1", "+1.5", "-2.25", ".5", "-.5", "5.", "007", "1e5", "1E-5",
                        "1e+5", "2.5e-3", "2.2250738585072014e-308", "1.7976931348623157e308",
                        "9007199254740993", "0.1", "3.141592653589793238462643383279"})
    EXPECT_TRUE(same_as_yaml_cpp(t)) << t;
  for (const char* t : {"", "+", "-", ".", "e5", "1e", "1e+", "1.2.3", " 1", "1 ", "0x1p3", "inf", ".inf", "-.inf",
                        ".nan", "nan", "1_000", "1,5", "true", "1e400", "-1e400", "--1", "+-1", "1e5.0"})
    EXPECT_FALSE(same_as_yaml_cpp(t)) << t;
  for (const char* t : {"4.9406564584124654e-324", "1e-310", "1e-400", "-1e-400"})  // subnormal, underflow: either path
    same_as_yaml_cpp(t);
}

// The reload's tree writes a number as dump() does, without a serializer.
TEST(YamlReader, JsonScalarTextIsDumpsText)
{
  std::mt19937_64 g(7);
  for (int i = 0; i < 20000; ++i) {
    double x = 0.0;
    const uint64_t u = g();
    std::memcpy(&x, &u, sizeof x);
    for (const nlohmann::json& j : {nlohmann::json(x), nlohmann::json(static_cast<double>(static_cast<int32_t>(u))),
                                    nlohmann::json(static_cast<int64_t>(u)), nlohmann::json(u),
                                    nlohmann::json(std::ldexp(static_cast<double>(u >> 11), -60))})
      ASSERT_EQ(harness::json_scalar_text(j), j.dump()) << j.dump();
  }
  for (const nlohmann::json& j : {nlohmann::json(0.0), nlohmann::json(-0.0), nlohmann::json(1e-5), nlohmann::json(100.0),
                                  nlohmann::json(1e21), nlohmann::json(5e-324), nlohmann::json(1.7976931348623157e308),
                                  nlohmann::json(std::nan("")), nlohmann::json(HUGE_VAL), nlohmann::json(true),
                                  nlohmann::json(false), nlohmann::json(0), nlohmann::json(-1), nlohmann::json(INT64_MIN),
                                  nlohmann::json(UINT64_MAX), nlohmann::json(nullptr), nlohmann::json("1.5")})
    EXPECT_EQ(harness::json_scalar_text(j), j.dump()) << j.dump();
}

namespace {
// The kind, a scalar's text, a map's keys in order, each element.
::testing::AssertionResult same_tree(const YAML::Node& a, const YAML::Node& b, const std::string& at = "")
{
  if (a.Type() != b.Type()) return ::testing::AssertionFailure() << at << ": kind";
  if (a.IsScalar() && a.Scalar() != b.Scalar())
    return ::testing::AssertionFailure() << at << ": '" << a.Scalar() << "' against '" << b.Scalar() << "'";
  if (a.IsSequence() || a.IsMap()) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << at << ": size";
    if (a.IsSequence()) {
      for (size_t i = 0; i < a.size(); ++i)
        if (auto r = same_tree(a[i], b[i], at + "[" + std::to_string(i) + "]"); !r) return r;
    } else {
      auto ib = b.begin();
      for (auto ia = a.begin(); ia != a.end(); ++ia, ++ib) {
        if (ia->first.Scalar() != ib->first.Scalar()) return ::testing::AssertionFailure() << at << ": keys";
        if (auto r = same_tree(ia->second, ib->second, at + "." + ia->first.Scalar()); !r) return r;
      }
    }
  }
  return ::testing::AssertionSuccess();
}
}  // namespace

// The kept tree of a sequence of documents is, after each, the tree built
// anew from that document; documents of the kept shape reuse it, others
// rebuild it; lookups of absent keys between documents change nothing.
TEST(YamlReader, TheKeptTreeIsTheTreeOfEachDocument)
{
  harness::KeptYamlTree kept;
  nlohmann::json j = nlohmann::json::parse(
      R"({"a": 1.5, "b": {"c": [1, 2, 3], "d": "text", "e": null, "f": true, "g": -0.0}, "h": [{"i": 7}, {"i": 8}]})");
  auto check = [&](const nlohmann::json& doc, uint64_t built, uint64_t reused, const std::string& what) {
    const YAML::Node& t = kept.tree_of(doc);
    EXPECT_TRUE(same_tree(t, harness::yaml_of_json(doc))) << what;
    EXPECT_EQ(kept.built(), built) << what;
    EXPECT_EQ(kept.reused(), reused) << what;
    YAML::Node m = t;  // a reader's non-const lookups of absent keys
    (void)m["absent"];
    (void)m["b"]["absent too"];
  };
  check(j, 1, 0, "first");
  check(j, 1, 1, "the same");
  j["a"] = 2.25;
  j["b"]["c"][1] = -4;
  j["b"]["d"] = "other";
  check(j, 1, 2, "numbers and a string");
  j["b"]["g"] = 0.0;  // written 0.0, not -0.0
  j["b"]["f"] = false;
  j["h"][1]["i"] = 8.5;  // integer to double
  j["b"]["d"] = 3;       // string to number
  check(j, 1, 3, "bits, booleans and kinds of scalar");
  j["b"]["c"].push_back(4);
  check(j, 2, 3, "a list grown");
  j["b"]["e"] = 1.0;
  check(j, 3, 3, "null to a number");
  j["b"]["e"] = nullptr;
  check(j, 4, 3, "a number to null");
  j["b"].erase("f");
  j["b"]["z"] = true;
  check(j, 5, 3, "a key dropped, another added");
  nlohmann::json k = j;
  k["b"] = nlohmann::json::array({1, 2});
  check(k, 6, 3, "a map to a list");
  check(j, 7, 3, "back");
  j["a"] = 1e300;
  check(j, 7, 4, "again in place");
}

// Memory held by the kept tree does not grow with the documents, whether
// they set it in place or build it anew (a shape that changes every time):
// the heap in use after 2,000 documents is that after 200.
TEST(YamlReader, TheKeptTreeHoldsOneDocumentsMemory)
{
  nlohmann::json a = nlohmann::json::parse(R"({"x": [1.5, 2.5, 3.5], "y": {"z": "s", "w": 4}, "v": null})");
  nlohmann::json b = a;
  b["x"].push_back(4.5);  // another shape
  for (const bool alternate : {false, true}) {
    harness::KeptYamlTree kept;
    size_t after200 = 0;
    for (int i = 0; i < 2000; ++i) {
      nlohmann::json d = alternate && i % 2 == 1 ? b : a;
      d["x"][0] = 0.5 * i;
      d["y"]["z"] = "s" + std::to_string(i);
      const YAML::Node& t = kept.tree_of(d);
      ASSERT_EQ(t["x"][0].Scalar(), harness::json_scalar_text(d["x"][0]));
      if (i == 199) after200 = mallinfo2().uordblks;
    }
    EXPECT_EQ(kept.built(), alternate ? 2000u : 1u);
    const size_t after2000 = mallinfo2().uordblks;
    if (after200 == 0 && after2000 == 0) GTEST_SKIP() << "mallinfo2 counts nothing here (a sanitizer's allocator)";
    EXPECT_LT(after2000, after200 + 16384) << (alternate ? "rebuilt each time" : "set in place");
  }
}

TEST(YamlReader, IssuesCarryLineColumnAndKey)
{
  Doc d("a:\n  x: -1\n  y: word\n  n: 11\n  z: .nan\n");
  MapReader top(d.ctx, d.root, "");
  MapReader a = top.sub("a");
  EXPECT_FALSE(a.real("x", [](double v) { return v > 0 ? std::string() : std::string("must be > 0 [m]"); }));
  EXPECT_FALSE(a.real("y"));
  EXPECT_FALSE(a.integer("n", 0, 10));
  EXPECT_FALSE(a.real("z"));
  a.finish();
  top.finish();
  ASSERT_EQ(d.issues.size(), 4u);
  EXPECT_EQ(d.issues[0].str(), "d.yaml:2:6: a.x: must be > 0 [m], got -1");
  EXPECT_EQ(d.issues[1].str(), "d.yaml:3:6: a.y: expected a number, got scalar 'word'");
  EXPECT_EQ(d.issues[2].str(), "d.yaml:4:6: a.n: must be in [0, 10], got 11");
  EXPECT_EQ(d.issues[3].str(), "d.yaml:5:6: a.z: must be finite, got .nan");
}

TEST(YamlReader, UnknownAndDuplicateKeys)
{
  Doc d("speed: 1\nspeeed: 2\ncolour: red\nspeed: 3\n");
  MapReader r(d.ctx, d.root, "");
  r.real("speed");
  r.finish();
  ASSERT_EQ(d.issues.size(), 3u);
  EXPECT_EQ(d.issues[0].str(), "d.yaml:4:1: speed: duplicate key");
  EXPECT_EQ(d.issues[1].str(), "d.yaml:2:1: speeed: unknown key (did you mean 'speed'?)");
  EXPECT_EQ(d.issues[2].str(), "d.yaml:3:1: colour: unknown key");
  EXPECT_EQ(harness::did_you_mean("Kp", {"K", "P", "K_i"}), "K");
  EXPECT_EQ(harness::did_you_mean("zzzzzz", {"K", "P"}), "");
}

TEST(YamlReader, AlternativeUnitSpelling)
{
  Doc d("a: {w_rpm: 60}\nb: {w: 1, w_rpm: 2}\n");
  MapReader top(d.ctx, d.root, "");
  MapReader a = top.sub("a");
  const double rpm = 2.0 * M_PI / 60.0;
  EXPECT_NEAR(*a.quantity("w", "_rpm", rpm), 2.0 * M_PI, 1e-15);
  a.finish();
  MapReader b = top.sub("b");
  EXPECT_FALSE(b.quantity("w", "_rpm", rpm).has_value());
  b.finish();  // both spellings are known keys: no 'unknown key' on top
  top.finish();
  ASSERT_EQ(d.issues.size(), 1u);
  EXPECT_EQ(d.issues[0].key, "b.w_rpm");
  EXPECT_NE(d.issues[0].message.find("not both"), std::string::npos);
}

TEST(YamlReader, UnitVectorsAndInertia)
{
  Doc d("u: [0, 0, 1.0005]\nbad: [1, 1, 0]\nI: [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]\nJ: [1, 1, 3]\n");
  MapReader r(d.ctx, d.root, "");
  const auto u = r.unit_vec3("u");
  ASSERT_TRUE(u.has_value());
  EXPECT_DOUBLE_EQ(u->norm(), 1.0);  // renormalised
  EXPECT_FALSE(r.unit_vec3("bad"));
  EXPECT_FALSE(r.inertia("I"));
  EXPECT_FALSE(r.inertia("J"));
  r.finish();
  ASSERT_EQ(d.issues.size(), 3u);
  EXPECT_NE(d.issues[0].message.find("unit vector"), std::string::npos);
  EXPECT_NE(d.issues[1].message.find("symmetric"), std::string::npos);
  EXPECT_NE(d.issues[2].message.find("triangle inequality"), std::string::npos);
  Eigen::Vector3d exact(0, 1, 0);
  EXPECT_EQ(harness::check_unit_vector(exact), "");
  EXPECT_EQ(exact, Eigen::Vector3d(0, 1, 0));
}

TEST(YamlReader, CommandLineValuesNameTheSet)
{
  Doc d("a: {x: 1}\n");
  d.ctx.overridden.insert("a.x");
  MapReader top(d.ctx, d.root, "");
  MapReader a = top.sub("a");
  EXPECT_FALSE(a.boolean("x"));
  a.finish();
  top.finish();
  ASSERT_EQ(d.issues.size(), 1u);
  EXPECT_EQ(d.issues[0].where, "--set a.x");
  EXPECT_EQ(d.issues[0].line, 0);
  EXPECT_EQ(d.issues[0].str(), "d.yaml: --set a.x: a.x: expected true or false, got scalar '1'");
}

TEST(YamlReader, KeyLines)
{
  std::map<std::string, std::pair<int, int>> lines;
  harness::collect_key_lines(YAML::Load("a:\n  b: 1\nl:\n  - {c: 2}\n"), "", lines);
  EXPECT_EQ(lines.at("a.b"), std::make_pair(2, 3));
  EXPECT_EQ(lines.at("l[0].c"), std::make_pair(4, 6));
}

// ---- bounds on the text (check_yaml_text), before any node tree is built ----------

namespace {
std::string first_problem(const std::string& text)
{
  const std::vector<ScenarioIssue> v = harness::check_yaml_text(text, "d.yaml");
  return v.empty() ? "" : v.front().str();
}
// n levels of ten aliases each: 10^n nodes once expanded, a few hundred bytes written.
std::string alias_bomb(int levels)
{
  std::string t = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k <= levels; ++k) {
    t += "a" + std::to_string(k) + ": &a" + std::to_string(k) + " [";
    for (int j = 0; j < 10; ++j) t += (j ? ", *a" : "*a") + std::to_string(k - 1);
    t += "]\n";
  }
  return t;
}
}  // namespace

TEST(YamlBounds, OrdinaryTextPasses)
{
  EXPECT_EQ(first_problem("a: 1\nb: [1, 2, 3]\nc: {d: \"x y\", e: 'it''s'}\nf: &k [1]\ng: *k\n"), "");
  EXPECT_EQ(first_problem(alias_bomb(3)), "");  // 1000 nodes: fine
  EXPECT_EQ(first_problem("---\na: 1\n...\n"), "");  // one explicit document
}

TEST(YamlBounds, AliasBombIsRefusedAtTheAliasInLinearTime)
{
  const auto t0 = std::chrono::steady_clock::now();
  const std::string p = first_problem(alias_bomb(30));  // 10^31 nodes if expanded
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(p.find("d.yaml:5:10:"), std::string::npos) << p;  // a4 (10^5 nodes) crosses 20000
  EXPECT_NE(p.find("alias bomb"), std::string::npos) << p;
  EXPECT_LT(s, 0.5);
}

TEST(YamlBounds, CyclesDepthDocumentsListsAndBytes)
{
  EXPECT_NE(first_problem("a: &x [1, *x]\n").find("d.yaml:1:11: (file): an alias inside the node its anchor names"),
            std::string::npos)
      << first_problem("a: &x [1, *x]\n");
  EXPECT_NE(first_problem("a: " + std::string(33, '[') + std::string(33, ']') + "\n").find("nested more than 32"),
            std::string::npos);
  EXPECT_EQ(first_problem("a: " + std::string(31, '[') + std::string(31, ']') + "\n"), "");
  EXPECT_NE(first_problem("a: " + std::string(100000, '[')).find("nested more than 32"), std::string::npos);
  EXPECT_NE(first_problem("a: 1\n---\nb: 2\n").find("d.yaml:2:1: (file): a second YAML document"), std::string::npos);
  std::string big = "a: [0";
  for (int i = 0; i < 1000; ++i) big += ", 0";
  EXPECT_NE(first_problem(big + "]\n").find("a list with more than 1000 entries"), std::string::npos);
  EXPECT_NE(first_problem(std::string("a: 1\nb: x\0y\n", 12)).find("d.yaml:2:5: (file): NUL byte"), std::string::npos);
  EXPECT_NE(first_problem("a: \x01\n").find("control byte 0x01"), std::string::npos);
  EXPECT_NE(first_problem(std::string(harness::kMaxYamlBytes + 1, ' ')).find("file too large"), std::string::npos);
}

TEST(YamlBounds, UnclosedQuotesAreNamedAtTheQuote)
{
  EXPECT_NE(first_problem("a: \"abc\nb: 1\nc: 2\n").find("d.yaml:1:4: (file): unclosed quote: the double quote"),
            std::string::npos);
  EXPECT_NE(first_problem("a:\n  b: 'abc\n  c: 1\n").find("d.yaml:2:6: (file): unclosed quote: the single quote"),
            std::string::npos)
      << first_problem("a:\n  b: 'abc\n  c: 1\n");
  EXPECT_EQ(first_problem("a: \"x \\\" y\"\nb: 'it''s'\n"), "");  // escaped quotes close on the line
}

TEST(YamlBounds, MessagesEscapeControlBytesAndInvalidUtf8)
{
  EXPECT_EQ(harness::escape_bytes(std::string("a\0b\x1b[1m\n\xff\xc3\xa9", 11)), "a\\x00b\\x1B[1m\\x0A\\xFFé");
}

// Valid UTF-8 that would hide or reorder what a message quotes is shown as
// \uXXXX (code points written out by hand from their UTF-8 bytes): the
// right-to-left override U+202E (E2 80 AE), which would print "exe.txt"
// reversed, the zero-width space U+200B (E2 80 8B), which would make 'rw2'
// and 'rw<ZWSP>2' look alike, the isolates U+2066..U+2069, the byte-order
// mark U+FEFF, the C1 control NEL U+0085 (C2 85), the line separator
// U+2028; ordinary letters of any script, and a 4-byte emoji, stay as they are.
TEST(YamlBounds, MessagesEscapeBidirectionalAndInvisibleCharacters)
{
  EXPECT_EQ(harness::escape_bytes("rw\xe2\x80\x8b" "2"), "rw\\u200B2");
  EXPECT_EQ(harness::escape_bytes("a\xe2\x80\xaetxt.exe"), "a\\u202Etxt.exe");
  EXPECT_EQ(harness::escape_bytes("\xe2\x81\xa6x\xe2\x81\xa9"), "\\u2066x\\u2069");
  EXPECT_EQ(harness::escape_bytes("\xef\xbb\xbfkey"), "\\uFEFFkey");
  EXPECT_EQ(harness::escape_bytes("a\xc2\x85" "b"), "a\\u0085b");
  EXPECT_EQ(harness::escape_bytes("a\xe2\x80\xa8" "b"), "a\\u2028b");
  EXPECT_EQ(harness::escape_bytes("\xe2\x80\x8e\xe2\x80\x8f"), "\\u200E\\u200F");
  const std::string plain = "r\xc3\xa9" "f \xe4\xb8\xad \xd7\xa9 \xf0\x9f\x9a\x80";  // é, 中, ש (Hebrew), 🚀
  EXPECT_EQ(harness::escape_bytes(plain), plain);
  // and through a scenario problem, as printed
  const harness::ScenarioIssue is{"s.yaml", 3, 5, "wheels[0].name", "no device named 'rw\xe2\x80\xae" "9'", ""};
  EXPECT_EQ(is.str(), "s.yaml:3:5: wheels[0].name: no device named 'rw\\u202E9'");
}

TEST(YamlReader, AnEmptyValueIsReportedAtItsKey)
{
  Doc d("a:\n  x:\n  y: 2\n  v:\n  w: [1, 2, 3]\n");
  MapReader a(d.ctx, d.root, "");
  MapReader r = a.sub("a");
  EXPECT_FALSE(r.real("x").has_value());
  EXPECT_FALSE(r.vec3("v").has_value());
  ASSERT_EQ(d.issues.size(), 2u);
  EXPECT_EQ(d.issues[0].str(), "d.yaml:2:3: a.x: expected a number, got an empty value (null)");
  EXPECT_EQ(d.issues[1].str(), "d.yaml:4:3: a.v: expected a list of 3 numbers, got an empty value");
}
