// kestrel::report: splices the run data into the page built at build time.
#include "report/report.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace report {
namespace detail {
extern const char kPagePrefix[];
extern const std::size_t kPagePrefixSize;
extern const char kPageSuffix[];
extern const std::size_t kPageSuffixSize;
extern const bool kHasBundle;
extern const char kLivePage[];
extern const std::size_t kLivePageSize;
}  // namespace detail

std::string escape_json_for_script(const std::string& json) {
  std::string out;
  out.reserve(json.size() + json.size() / 64 + 16);
  for (char c : json) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

std::string render_html(const std::string& report_data_json) {
  const std::string data = escape_json_for_script(report_data_json);
  std::string page;
  page.reserve(detail::kPagePrefixSize + data.size() + detail::kPageSuffixSize);
  page.append(detail::kPagePrefix, detail::kPagePrefixSize);
  page += data;
  page.append(detail::kPageSuffix, detail::kPageSuffixSize);
  return page;
}

void write_html(const std::string& report_data_json, std::ostream& out) {
  out.write(detail::kPagePrefix, static_cast<std::streamsize>(detail::kPagePrefixSize));
  const std::string data = escape_json_for_script(report_data_json);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  out.write(detail::kPageSuffix, static_cast<std::streamsize>(detail::kPageSuffixSize));
}

void write_html(const std::string& report_data_json, const std::string& out_html_path) {
  std::ofstream f(out_html_path, std::ios::binary | std::ios::trunc);
  if (!f) {
    throw std::runtime_error("report: cannot open '" + out_html_path + "' for writing: " + std::strerror(errno));
  }
  write_html(report_data_json, f);
  f.flush();
  if (!f) {
    throw std::runtime_error("report: error writing '" + out_html_path + "'");
  }
}

bool has_bundle() { return detail::kHasBundle; }

const std::string& live_page()
{
  static const std::string page(detail::kLivePage, detail::kLivePageSize);
  return page;
}

std::size_t page_size() { return detail::kPagePrefixSize + detail::kPageSuffixSize; }

}  // namespace report
