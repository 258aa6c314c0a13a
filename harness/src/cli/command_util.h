// command_util: what the `kestrel` commands share (commands.cpp,
// mc_commands.cpp).  Private to the harness library.
#ifndef HARNESS_SRC_COMMAND_UTIL_H
#define HARNESS_SRC_COMMAND_UTIL_H

#include <ostream>
#include <string>
#include <vector>

#include "harness/scenario/scenario.h"

namespace harness {

// The --set arguments as overrides; false (after a message on err) when one is malformed.
bool parse_sets(const std::vector<std::string>& sets, std::vector<Override>& out, std::ostream& err);
// Every problem of a rejected scenario, then "scenario rejected (N problems)".
void print_issues(const ScenarioError& e, std::ostream& err);

}  // namespace harness

#endif  // HARNESS_SRC_COMMAND_UTIL_H
