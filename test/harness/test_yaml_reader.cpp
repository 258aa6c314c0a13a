// The generic YAML reader (harness/src/yaml_reader.h) alone, on small
// documents unrelated to the scenario schema: typed decoding, issues with
// file:line:col, unknown keys with a did-you-mean hint, alternative-unit
// spellings, unit vectors and inertia checks, --set attribution.
#include <gtest/gtest.h>

#include <chrono>

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
