// kestrel::report: the page is self-contained and the run data is embedded
// safely (no way to close the data <script> element from inside the data).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "report/report.hpp"

namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// the text of <script id="kestrel-data" ...>...</script>
std::string embedded_data(const std::string& page) {
  const std::string open = "<script id=\"kestrel-data\" type=\"application/json\">";
  const std::size_t a = page.find(open);
  EXPECT_NE(a, std::string::npos);
  const std::size_t b = page.find("</script>", a + open.size());
  EXPECT_NE(b, std::string::npos);
  return page.substr(a + open.size(), b - a - open.size());
}

std::string unescape_lt(std::string s) {
  for (std::size_t p = s.find("\\u003c"); p != std::string::npos; p = s.find("\\u003c", p + 1)) s.replace(p, 6, "<");
  return s;
}

const char* kHostile =
    R"({"meta":{"scenario":"x</script><script>alert(1)</script><!-- </SCRIPT >","seed":1},)"
    R"("series":{"t":[0,1]},"dataflow_dot":"digraph { a -> b [label=\"<!--\"]; }"})";

}  // namespace

TEST(ReportEmbed, PageIsAnHtmlDocumentWithTheBundle) {
  const std::string page = report::render_html("{}");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("</html>"), std::string::npos);
  EXPECT_EQ(page.size(), report::page_size() + 2);
  if (!report::has_bundle()) GTEST_SKIP() << "built without Node.js/npm: data-only page";
  EXPECT_GT(report::page_size(), 200000u) << "the page should carry uPlot and three.js";
  EXPECT_NE(page.find("id=\"plots\""), std::string::npos);
  EXPECT_NE(page.find("id=\"replay\""), std::string::npos);
  EXPECT_NE(page.find("id=\"dataflow\""), std::string::npos);
  EXPECT_NE(page.find("three.js"), std::string::npos) << "licence notices embedded";
  EXPECT_NE(page.find("uplot"), std::string::npos);
}

TEST(ReportEmbed, NothingIsFetchedFromOutside) {
  const std::string page = lower(report::render_html("{}"));
  // no external scripts, style sheets, images, frames or imports
  const std::regex ext(R"re((src|href|action|poster|data)\s*=\s*["']?\s*(https?:|//|ftp:|file:))re");
  EXPECT_FALSE(std::regex_search(page, ext));
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(page.find("<iframe"), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
  EXPECT_FALSE(std::regex_search(page, std::regex(R"(url\(\s*["']?(https?:|//))")));
  // every <script> is inline
  EXPECT_FALSE(std::regex_search(page, std::regex(R"(<script[^>]*\ssrc\s*=)")));
}

TEST(ReportEmbed, DataCannotCloseTheScriptElement) {
  const std::string base = lower(report::render_html("{}"));
  const std::string page = report::render_html(kHostile);
  const std::string lp = lower(page);
  EXPECT_EQ(count(lp, "</script"), count(base, "</script"));
  EXPECT_EQ(count(lp, "<script"), count(base, "<script"));
  EXPECT_EQ(count(lp, "<!--"), count(base, "<!--"));
  const std::string data = embedded_data(page);
  EXPECT_EQ(data.find('<'), std::string::npos);
  EXPECT_EQ(unescape_lt(data), kHostile) << "the JSON text is unchanged but for '<' -> \\u003c";
}

TEST(ReportEmbed, EscapeOnlyTouchesLessThan) {
  EXPECT_EQ(report::escape_json_for_script(R"({"a":"<b>&\u2028"})"), R"({"a":"\u003cb>&\u2028"})");
  EXPECT_EQ(report::escape_json_for_script(""), "");
  const std::string utf8 = "{\"s\":\"\xc3\xa9\xe2\x80\xa8\"}";
  EXPECT_EQ(report::escape_json_for_script(utf8), utf8);
}

TEST(ReportEmbed, LargeDataRoundTrips) {
  std::string json = "{\"series\":{\"t\":[";
  for (int i = 0; i < 400000; ++i) json += (i ? "," : "") + std::to_string(i);
  json += "]}}";
  const std::string page = report::render_html(json);
  EXPECT_EQ(page.size(), report::page_size() + json.size());
  EXPECT_EQ(embedded_data(page), json);
}

TEST(ReportEmbed, WritesFilesAndStreamsAlike) {
  const std::string path = ::testing::TempDir() + "kestrel_report_embed_test.html";
  report::write_html(kHostile, path);
  std::ifstream f(path, std::ios::binary);
  std::stringstream buf;
  buf << f.rdbuf();
  EXPECT_EQ(buf.str(), report::render_html(kHostile));
  std::ostringstream os;
  report::write_html(kHostile, os);
  EXPECT_EQ(os.str(), buf.str());
  std::remove(path.c_str());
}

TEST(ReportEmbed, UnwritablePathThrowsNamingIt) {
  const std::string bad = "/nonexistent-dir-kestrel/report.html";
  try {
    report::write_html("{}", bad);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}
