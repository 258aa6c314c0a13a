// kestrel_report DATA.json OUT.html: writes the offline HTML report of a run
// from its report_data.json (the harness calls report::write_html itself;
// this tool is for tests and for re-rendering a run).
// Exit codes: 0 written, 1 input or output error, 2 usage.
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "report/report.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: kestrel_report DATA.json OUT.html\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::cerr << "kestrel_report: cannot read '" << argv[1] << "'\n";
    return 1;
  }
  std::ostringstream buf;
  buf << in.rdbuf();
  try {
    report::write_html(buf.str(), std::string(argv[2]));
  } catch (const std::exception& e) {
    std::cerr << "kestrel_report: " << e.what() << "\n";
    return 1;
  }
  if (!report::has_bundle()) {
    std::cerr << "kestrel_report: note: built without the report bundle (no Node.js/npm): data-only page\n";
  }
  return 0;
}
