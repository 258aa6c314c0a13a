// kestrel::report: the page is self-contained and the run data is embedded
// safely (no way to close the data <script> element from inside the data).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "page_checks.hpp"
#include "report/report.hpp"

namespace {

using page_checks::embedded_data;

const char* kHostile =
    R"({"meta":{"scenario":"x</script><script>alert(1)</script><!-- </SCRIPT >","seed":1},)"
    R"("series":{"t":[0,1]},"dataflow_dot":"digraph { a -> b [label=\"<!--\"]; }"})";

// campaign data with the same hostile strings (docs/report.md, "Monte Carlo report")
const char* kHostileMc =
    R"({"kind":"kestrel_mc_report","schema":1,"scenario":"x</script><script>alert(1)</script><!-- </SCRIPT >",)"
    R"("master_seed":42,"runs":1,"failed":1,"invalid":0,"criteria":[{"name":"<!--","metric":"m","op":"below","threshold":1}],)"
    R"("drawn":[{"name":"</script>","unit":"deg"}],"metrics":[{"name":"m","unit":"deg"}],)"
    R"("table":[{"index":0,"seed":"18446744073709551615","pass":false,"invalid":false,"reason":"</script>",)"
    R"("drawn":[1.5],"metrics":[2.5],"report":"runs/000000/report.html"}]})";

// the file written, the stream written and the string rendered are the same page
template <class Render, class WriteFile, class WriteStream>
void expect_file_and_stream_alike(const std::string& data, const std::string& name, Render render, WriteFile write_file,
                                  WriteStream write_stream) {
  const std::string path = ::testing::TempDir() + name;
  write_file(data, path);
  std::ifstream f(path, std::ios::binary);
  std::stringstream buf;
  buf << f.rdbuf();
  EXPECT_EQ(buf.str(), render(data));
  std::ostringstream os;
  write_stream(data, os);
  EXPECT_EQ(os.str(), buf.str());
  std::remove(path.c_str());
}

template <class WriteFile>
void expect_throws_naming(const std::string& bad, WriteFile write_file) {
  try {
    write_file(bad);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

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

TEST(ReportEmbed, NothingIsFetchedFromOutside) { page_checks::expect_self_contained(report::render_html("{}")); }

TEST(ReportEmbed, DataCannotCloseTheScriptElement) {
  page_checks::expect_data_contained(report::render_html("{}"), report::render_html(kHostile), kHostile);
}

TEST(ReportEmbed, EscapeOnlyTouchesLessThan) {
  EXPECT_EQ(report::escape_json_for_script(R"({"a":"<b>&\u2028"})"), R"({"a":"\u003cb>&\u2028"})");
  EXPECT_EQ(report::escape_json_for_script(""), "");
  // at the ends and back to back
  EXPECT_EQ(report::escape_json_for_script("<<a<"), R"(\u003c\u003ca\u003c)");
  EXPECT_EQ(report::escape_json_for_script("<"), R"(\u003c)");
  EXPECT_EQ(report::escape_json_for_script("a</script>b"), R"(a\u003c/script>b)");
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
  expect_file_and_stream_alike(
      kHostile, "kestrel_report_embed_test.html", [](const std::string& d) { return report::render_html(d); },
      [](const std::string& d, const std::string& p) { report::write_html(d, p); },
      [](const std::string& d, std::ostream& o) { report::write_html(d, o); });
}

TEST(ReportEmbed, UnwritablePathThrowsNamingIt) {
  expect_throws_naming("/nonexistent-dir-kestrel/report.html",
                       [](const std::string& p) { report::write_html("{}", p); });
}

// The Monte Carlo report page (report::write_mc_html): a second page of the
// same library, with the campaign data embedded the same way.
TEST(ReportMcEmbed, PageIsAnHtmlDocumentWithTheBundle) {
  const std::string page = report::render_mc_html("{}");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("</html>"), std::string::npos);
  EXPECT_EQ(page.size(), report::mc_page_size() + 2);
  EXPECT_NE(page, report::render_html("{}"));
  EXPECT_NE(page.find("Monte Carlo report"), std::string::npos);
  if (!report::has_bundle()) GTEST_SKIP() << "built without Node.js/npm: data-only page";
  // uPlot (about 50 kB minified) and the page code, but not three.js
  EXPECT_GT(report::mc_page_size(), 50000u) << "the page should carry uPlot";
  for (const char* id : {"id=\"mc-series\"", "id=\"mc-hist\"", "id=\"mc-scatter\"", "id=\"mc-table\"", "id=\"criteria\""}) {
    EXPECT_NE(page.find(id), std::string::npos) << id;
  }
  EXPECT_NE(page.find("uplot"), std::string::npos) << "licence notice embedded";
  EXPECT_EQ(page.find("three.js"), std::string::npos) << "three.js is not needed by this page";
}

TEST(ReportMcEmbed, NothingIsFetchedFromOutside) { page_checks::expect_self_contained(report::render_mc_html("{}")); }

TEST(ReportMcEmbed, DataCannotCloseTheScriptElement) {
  page_checks::expect_data_contained(report::render_mc_html("{}"), report::render_mc_html(kHostileMc), kHostileMc);
}

TEST(ReportMcEmbed, WritesFilesAndStreamsAlike) {
  expect_file_and_stream_alike(
      kHostileMc, "kestrel_mc_report_embed_test.html", [](const std::string& d) { return report::render_mc_html(d); },
      [](const std::string& d, const std::string& p) { report::write_mc_html(d, p); },
      [](const std::string& d, std::ostream& o) { report::write_mc_html(d, o); });
}

TEST(ReportMcEmbed, UnwritablePathThrowsNamingIt) {
  expect_throws_naming("/nonexistent-dir-kestrel/mc_report.html",
                       [](const std::string& p) { report::write_mc_html("{}", p); });
}

// write_mc_html_file reads the data a piece (256 kB) at a time: the page is
// the one of the whole text, a '<' on either side of a piece boundary
// included, and a missing data file or an unwritable page is named.
TEST(ReportMcEmbed, PageFromTheDataFileIsThePageOfItsText) {
  std::string json = "{\"table\":[";
  for (int i = 0; i < 120000; ++i) json += (i ? ",\"<" : "\"<") + std::to_string(i) + "\"";
  json += "]}";
  const std::size_t piece = std::size_t(1) << 18;
  ASSERT_GT(json.size(), 3 * piece);
  for (std::size_t at : {piece - 1, piece, 2 * piece - 1, 2 * piece}) json[at] = '<';
  const std::string data = "kestrel_mc_report_file_test.json", html = "kestrel_mc_report_file_test.html";
  std::ofstream(data, std::ios::binary) << json;
  report::write_mc_html_file(data, html);
  std::ifstream in(html, std::ios::binary);
  std::ostringstream got;
  got << in.rdbuf();
  EXPECT_TRUE(got.str() == report::render_mc_html(json)) << "the pages differ";
  EXPECT_TRUE(page_checks::unescape_lt(embedded_data(got.str())) == json) << "the data read back differs";
  EXPECT_EQ(embedded_data(got.str()).find("<"), std::string::npos);
  expect_throws_naming("/nonexistent-dir-kestrel/mc_report.html",
                       [&](const std::string& p) { report::write_mc_html_file(data, p); });
  expect_throws_naming("/nonexistent-dir-kestrel/data.json",
                       [&](const std::string& p) { report::write_mc_html_file(p, html); });
  std::remove(data.c_str());
  std::remove(html.c_str());
}
