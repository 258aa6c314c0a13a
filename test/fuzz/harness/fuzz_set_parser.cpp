// libFuzzer harness: --set overrides (one per line of the input) parsed with
// parse_override and applied to the shipped S1 scenario, then validated.
// Every input gives a valid scenario or problems naming the override (or
// the file's line); a string parse_override refuses is a usage error.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_input_common.h"

namespace {
const std::string& s1_text()
{
  static const std::string text = [] {
    std::ifstream in(KESTREL_FUZZ_S1);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }();
  return text;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<harness::Override> ov;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line) && ov.size() < 16) {
    try {
      ov.push_back(harness::parse_override(line));
    } catch (const std::invalid_argument&) {
      // `kestrel` reports it as a usage error (exit 2); nothing is loaded
    }
  }
  kestrel_fuzz::load_and_check(s1_text(), "s1_sun_pointing.yaml", ov);
  return 0;
}
