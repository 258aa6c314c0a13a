// kestrel_report [--mc] DATA.json OUT.html: writes the offline HTML report of
// a run from its report_data.json, or with --mc the Monte Carlo report of a
// campaign from its mc_report_data.json (the harness calls report::write_html
// and report::write_mc_html itself; this tool is for tests and for
// re-rendering).
// Exit codes: 0 written, 1 input or output error, 2 usage.
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "report/report.hpp"

int main(int argc, char** argv) {
  const bool mc = argc == 4 && std::string(argv[1]) == "--mc";
  if (argc != 3 && !mc) {
    std::cerr << "usage: kestrel_report [--mc] DATA.json OUT.html\n";
    return 2;
  }
  const std::string in_path = argv[mc ? 2 : 1];
  const std::string out_path = argv[mc ? 3 : 2];
  std::ifstream in(in_path, std::ios::binary);
  if (!in) {
    std::cerr << "kestrel_report: cannot read '" << in_path << "'\n";
    return 1;
  }
  std::ostringstream buf;
  buf << in.rdbuf();
  try {
    if (mc) {
      report::write_mc_html(buf.str(), out_path);
    } else {
      report::write_html(buf.str(), out_path);
    }
  } catch (const std::exception& e) {
    std::cerr << "kestrel_report: " << e.what() << "\n";
    return 1;
  }
  if (!report::has_bundle()) {
    std::cerr << "kestrel_report: note: built without the report bundle (no Node.js/npm): data-only page\n";
  }
  return 0;
}
