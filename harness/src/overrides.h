// overrides: `--set key.path=value` applied to a scenario document before
// it is read, so every override goes through the same checks as the file
// and problems name the `--set` instead of a line.
//
// Private to the harness library.
#ifndef HARNESS_SRC_OVERRIDES_H
#define HARNESS_SRC_OVERRIDES_H

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "harness/scenario.h"
#include "yaml_reader.h"

namespace harness {

// "a.b[2].c" or "a.b.2.c" -> {"a", "b", "2", "c"}.
std::vector<std::string> split_path(const std::string& p);
// {"a", "b", "2", "c"} -> "a.b[2].c" (the form issues use).
std::string normalise_path(const std::vector<std::string>& parts);
// A list index written in a path: all digits and below `size`.  Absurd
// values (too many digits) are simply out of range, never an exception.
bool parse_index(const std::string& part, size_t size, size_t& out);

// Applies one override to the document `root`; problems go to ctx.issues
// (and ctx.overridden records the path for attributing later problems).
void apply_override(Ctx& ctx, YAML::Node& root, const Override& o);

}  // namespace harness

#endif  // HARNESS_SRC_OVERRIDES_H
