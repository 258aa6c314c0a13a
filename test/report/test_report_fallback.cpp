// kestrel::report built without Node.js/npm (report/lib/fallback_page.cpp,
// compiled into this test whatever the build has): both pages are data-only
// documents that say why, show the embedded data as text with their one
// inline script, fetch nothing, and embed hostile data as safely as the
// bundled pages.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "page_checks.hpp"
#include "report/report.hpp"

namespace {

const char* kHostileMc =
    R"({"kind":"kestrel_mc_report","schema":1,"scenario":"x</script><script>alert(1)</script><!--",)"
    R"("table":[{"index":0,"seed":"1","pass":false,"reason":"</SCRIPT >"}]})";

// the inline scripts that are not the data element
std::size_t code_scripts(const std::string& page) {
  return page_checks::count(page_checks::lower(page), "<script>");
}

}  // namespace

TEST(ReportFallback, BuiltWithoutTheBundle) { EXPECT_FALSE(report::has_bundle()); }

TEST(ReportFallback, RunPageIsDataOnly) {
  const std::string page = report::render_html("{\"meta\":{}}");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("</html>"), std::string::npos);
  EXPECT_NE(page.find("Kestrel run report (data only)"), std::string::npos);
  EXPECT_NE(page.find("no Node.js/npm"), std::string::npos) << "the page says why it has no plots";
  EXPECT_EQ(page.size(), report::page_size() + 11);
  EXPECT_EQ(page_checks::embedded_data(page), "{\"meta\":{}}");
  EXPECT_EQ(code_scripts(page), 1u) << "one script: the data shown as text";
  page_checks::expect_self_contained(page);
}

TEST(ReportFallback, McPageIsDataOnly) {
  const std::string page = report::render_mc_html("{\"runs\":3}");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("</html>"), std::string::npos);
  EXPECT_NE(page.find("Kestrel Monte Carlo report (data only)"), std::string::npos);
  EXPECT_NE(page.find("no Node.js/npm"), std::string::npos);
  EXPECT_EQ(page.size(), report::mc_page_size() + 10);
  EXPECT_EQ(page_checks::embedded_data(page), "{\"runs\":3}");
  // the data is shown with textContent (never parsed as HTML)
  EXPECT_NE(page.find("textContent=document.getElementById('kestrel-data').textContent"), std::string::npos);
  EXPECT_EQ(code_scripts(page), 1u);
  page_checks::expect_self_contained(page);
}

TEST(ReportFallback, HostileDataStaysInside) {
  page_checks::expect_data_contained(report::render_mc_html("{}"), report::render_mc_html(kHostileMc), kHostileMc);
  std::ostringstream os;
  report::write_mc_html(kHostileMc, os);
  EXPECT_EQ(os.str(), report::render_mc_html(kHostileMc));
}
