// kestrel::report: splices the run (or campaign) data into the page built at build time.
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
extern const char kMcPagePrefix[];
extern const std::size_t kMcPagePrefixSize;
extern const char kMcPageSuffix[];
extern const std::size_t kMcPageSuffixSize;
extern const bool kHasBundle;
extern const char kLivePage[];
extern const std::size_t kLivePageSize;
}  // namespace detail

namespace {

// A page split at its data placeholder.
struct Page {
  const char* prefix;
  std::size_t prefix_size;
  const char* suffix;
  std::size_t suffix_size;
};

Page run_page() { return {detail::kPagePrefix, detail::kPagePrefixSize, detail::kPageSuffix, detail::kPageSuffixSize}; }
Page mc_page() {
  return {detail::kMcPagePrefix, detail::kMcPagePrefixSize, detail::kMcPageSuffix, detail::kMcPageSuffixSize};
}

std::string render(const Page& p, const std::string& json) {
  const std::string data = escape_json_for_script(json);
  std::string page;
  page.reserve(p.prefix_size + data.size() + p.suffix_size);
  page.append(p.prefix, p.prefix_size);
  page += data;
  page.append(p.suffix, p.suffix_size);
  return page;
}

void write(const Page& p, const std::string& json, std::ostream& out) {
  out.write(p.prefix, static_cast<std::streamsize>(p.prefix_size));
  const std::string data = escape_json_for_script(json);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  out.write(p.suffix, static_cast<std::streamsize>(p.suffix_size));
}

void write_file(const Page& p, const std::string& json, const std::string& out_html_path) {
  std::ofstream f(out_html_path, std::ios::binary | std::ios::trunc);
  if (!f) {
    throw std::runtime_error("report: cannot open '" + out_html_path + "' for writing: " + std::strerror(errno));
  }
  write(p, json, f);
  f.flush();
  if (!f) {
    throw std::runtime_error("report: error writing '" + out_html_path + "'");
  }
}

}  // namespace

std::string escape_json_for_script(const std::string& json) {
  // '<' becomes \u003c (no "</script>" can end the element early); the text
  // between two '<' is copied whole, not a character at a time.
  std::string out;
  out.reserve(json.size() + json.size() / 64 + 16);
  std::size_t from = 0;
  for (std::size_t lt = json.find('<'); lt != std::string::npos; lt = json.find('<', from)) {
    out.append(json, from, lt - from);
    out += "\\u003c";
    from = lt + 1;
  }
  out.append(json, from, std::string::npos);
  return out;
}

std::string render_html(const std::string& report_data_json) { return render(run_page(), report_data_json); }

void write_html(const std::string& report_data_json, std::ostream& out) { write(run_page(), report_data_json, out); }

void write_html(const std::string& report_data_json, const std::string& out_html_path) {
  write_file(run_page(), report_data_json, out_html_path);
}

std::string render_mc_html(const std::string& mc_report_data_json) { return render(mc_page(), mc_report_data_json); }

void write_mc_html(const std::string& mc_report_data_json, std::ostream& out) {
  write(mc_page(), mc_report_data_json, out);
}

void write_mc_html(const std::string& mc_report_data_json, const std::string& out_html_path) {
  write_file(mc_page(), mc_report_data_json, out_html_path);
}

void write_mc_html_file(const std::string& mc_report_data_path, const std::string& out_html_path) {
  std::ifstream in(mc_report_data_path, std::ios::binary);
  if (!in) {
    throw std::runtime_error("report: cannot read '" + mc_report_data_path + "': " + std::strerror(errno));
  }
  std::ofstream f(out_html_path, std::ios::binary | std::ios::trunc);
  if (!f) {
    throw std::runtime_error("report: cannot open '" + out_html_path + "' for writing: " + std::strerror(errno));
  }
  const Page p = mc_page();
  f.write(p.prefix, static_cast<std::streamsize>(p.prefix_size));
  // escaping is a character at a time: a piece at a time gives the same page
  std::string piece(1 << 18, '\0');
  while (in) {
    in.read(&piece[0], static_cast<std::streamsize>(piece.size()));
    const std::string data = escape_json_for_script(piece.substr(0, static_cast<std::size_t>(in.gcount())));
    f.write(data.data(), static_cast<std::streamsize>(data.size()));
  }
  if (in.bad()) {
    throw std::runtime_error("report: error reading '" + mc_report_data_path + "'");
  }
  f.write(p.suffix, static_cast<std::streamsize>(p.suffix_size));
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

std::size_t mc_page_size() { return detail::kMcPagePrefixSize + detail::kMcPageSuffixSize; }

}  // namespace report
