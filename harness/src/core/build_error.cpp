#include "core/build_error.h"

namespace harness {

ScenarioError config_error(const Scenario& sc, const std::string& key, const std::string& msg)
{
  ScenarioIssue is;
  is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
  is.key = key;
  is.message = msg;
  for (std::string k = key; !k.empty();) {
    auto it = sc.key_lines.find(k);
    if (it != sc.key_lines.end()) {
      is.line = it->second.first;
      is.column = it->second.second;
      break;
    }
    const size_t cut = k.find_last_of(".[");
    if (cut == std::string::npos) break;
    k = k.substr(0, cut);
  }
  return ScenarioError({is});
}

}  // namespace harness
