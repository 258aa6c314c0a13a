// kestrel::report: the offline HTML run report and Monte Carlo report.
//
// One self-contained HTML file per run: the page (template, style sheet and
// the bundled report code with uPlot and three.js, built at build time by
// report/CMakeLists.txt) with the run's report_data.json embedded in a
// <script type="application/json"> element.  The page fetches nothing.
// Schema of report_data.json: docs/report.md.
//
// The Monte Carlo report of a campaign (`kestrel mc`) is a second page built
// the same way, with the campaign's mc_report_data.json embedded the same
// way (schema: docs/report.md, "Monte Carlo report").
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>

namespace report {

// The run data made safe to embed in a <script> element: every '<' becomes
// the JSON escape \u003c (in valid JSON '<' occurs only inside strings, where
// the escape means the same character), so neither "</script>" nor "<!--"
// can appear in the embedded text.  Nothing else changes.
std::string escape_json_for_script(const std::string& report_data_json);

// The whole page for one run.  The JSON is embedded as given (escaped as
// above) and parsed by the page; the page shows an error instead of the
// sections if it is not valid JSON.
std::string render_html(const std::string& report_data_json);

// render_html() to a stream.
void write_html(const std::string& report_data_json, std::ostream& out);

// render_html() to a file (created or truncated).  Throws std::runtime_error
// naming the path if it cannot be written.
void write_html(const std::string& report_data_json, const std::string& out_html_path);

// True when the page was built with the report bundle (Node.js and npm were
// found at build time); false for the fallback page that shows only the
// embedded data.
bool has_bundle();

// The live view's page (report/live.html with src/live.js, the same bundled
// libraries; docs/live.md): served by `kestrel run --live`, it reads
// everything from the server that serves it.
const std::string& live_page();

// Size in bytes of the page without the data.
std::size_t page_size();

// The Monte Carlo report page of a campaign: as render_html()/write_html(),
// with the Monte Carlo page and the campaign's mc_report_data.json (embedded
// as given, escaped by escape_json_for_script()).  Without the bundle
// (has_bundle() false) it is a data-only page.
std::string render_mc_html(const std::string& mc_report_data_json);
void write_mc_html(const std::string& mc_report_data_json, std::ostream& out);
// Throws std::runtime_error naming the path if it cannot be written.
void write_mc_html(const std::string& mc_report_data_json, const std::string& out_html_path);
// The same page from the data file at mc_report_data_path, read a piece at
// a time (memory bounded whatever the campaign's size); the same bytes as
// write_mc_html() of the file's text.
void write_mc_html_file(const std::string& mc_report_data_path, const std::string& out_html_path);

// Size in bytes of the Monte Carlo page without the data.
std::size_t mc_page_size();

}  // namespace report
