// Shared by the scenario input harnesses: what every input must give.
#ifndef KESTREL_FUZZ_INPUT_COMMON_H
#define KESTREL_FUZZ_INPUT_COMMON_H

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "harness/scenario/scenario.h"

namespace kestrel_fuzz {

// Loads and checks as `kestrel validate` does.  Either the scenario is valid
// (and passes the run's configuration checks) or every problem has a place:
// file:line:col in `file`, or the --set it came from.  Anything else, or any
// other exception, aborts (a finding).
inline void load_and_check(const std::string& text, const std::string& file,
                           const std::vector<harness::Override>& overrides)
{
  try {
    const harness::Scenario sc = harness::load_scenario_text(text, file, overrides);
    harness::check_run_configuration(sc);
  } catch (const harness::ScenarioError& e) {
    if (e.issues().empty()) {
      std::fprintf(stderr, "ScenarioError without an issue\n");
      std::abort();
    }
    for (const harness::ScenarioIssue& is : e.issues()) {
      const bool placed = !is.where.empty() || (is.line > 0 && is.column > 0);
      if (!placed || is.file.empty() || is.key.empty() || is.message.empty()) {
        std::fprintf(stderr, "issue without a place: %s\n", is.str().c_str());
        std::abort();
      }
    }
  }
}

}  // namespace kestrel_fuzz

#endif  // KESTREL_FUZZ_INPUT_COMMON_H
