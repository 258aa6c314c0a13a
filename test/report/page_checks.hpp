// Helpers of the report page tests (test_report_embed.cpp, test_report_fallback.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <regex>
#include <string>

namespace page_checks {

inline std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// the text of <script id="kestrel-data" ...>...</script>
inline std::string embedded_data(const std::string& page) {
  const std::string open = "<script id=\"kestrel-data\" type=\"application/json\">";
  const std::size_t a = page.find(open);
  EXPECT_NE(a, std::string::npos);
  const std::size_t b = page.find("</script>", a + open.size());
  EXPECT_NE(b, std::string::npos);
  return page.substr(a + open.size(), b - a - open.size());
}

inline std::string unescape_lt(std::string s) {
  for (std::size_t p = s.find("\\u003c"); p != std::string::npos; p = s.find("\\u003c", p + 1)) s.replace(p, 6, "<");
  return s;
}

// No external scripts, style sheets, images, frames or imports; every <script> inline.
inline void expect_self_contained(const std::string& page_text) {
  const std::string page = lower(page_text);
  const std::regex ext(R"re((src|href|action|poster|data)\s*=\s*["']?\s*(https?:|//|ftp:|file:))re");
  EXPECT_FALSE(std::regex_search(page, ext));
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(page.find("<iframe"), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
  EXPECT_FALSE(std::regex_search(page, std::regex(R"(url\(\s*["']?(https?:|//))")));
  EXPECT_FALSE(std::regex_search(page, std::regex(R"(<script[^>]*\ssrc\s*=)")));
}

// `page` (with `data` spliced in) has exactly the elements of `base` (the
// same page with "{}"), and the data round-trips but for '<' -> \u003c.
inline void expect_data_contained(const std::string& base_page, const std::string& page, const std::string& data) {
  const std::string base = lower(base_page);
  const std::string lp = lower(page);
  EXPECT_EQ(count(lp, "</script"), count(base, "</script"));
  EXPECT_EQ(count(lp, "<script"), count(base, "<script"));
  EXPECT_EQ(count(lp, "<!--"), count(base, "<!--"));
  const std::string embedded = embedded_data(page);
  EXPECT_EQ(embedded.find('<'), std::string::npos);
  EXPECT_EQ(unescape_lt(embedded), data) << "the JSON text is unchanged but for '<' -> \\u003c";
}

}  // namespace page_checks
