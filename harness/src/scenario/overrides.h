// overrides: a key path (`--set key.path=value`, set_parameter) resolved
// against the key definitions (scenario_schema.h).
//
// --set: the path must name a key or a section the schema knows (else an
// "unknown key" issue with a did-you-mean hint, naming the --set); list
// indices must exist in the document (absurd ones are a clean message, never
// an exception).  The value becomes a YAML node by the key's type -- a word
// for string and choice keys, YAML for numbers, flags, vectors and whole
// sections -- and is put into the document, so the reader checks it like the
// file and names the --set in any problem.  Setting one spelling of a key
// with a unit suffix (Omega_0 / Omega_0_rpm) drops the other from that map.
//
// Private to the harness library.
#ifndef HARNESS_SRC_OVERRIDES_H
#define HARNESS_SRC_OVERRIDES_H

#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "harness/scenario/scenario.h"
#include "scenario/scenario_schema.h"
#include "scenario/yaml_reader.h"

namespace harness {

// "a.b[2].c" or "a.b.2.c" -> {"a", "b", "2", "c"}.
std::vector<std::string> split_path(const std::string& p);
// {"a", "b", "2", "c"} -> "a.b[2].c" (the form issues use).
std::string normalise_path(const std::vector<std::string>& parts);
// A list index written in a path: all digits and below `size`.  Absurd
// values (too many digits) are simply out of range, never an exception.
bool parse_index(const std::string& part, size_t size, size_t& out);

// What a key path names in the schema.
struct KeyTarget {
  const schema::KeyDef* key = nullptr;            // null: a whole section (or list element)
  const schema::Section* section = nullptr;       // the key's section, or the section named
  std::vector<const schema::Section*> chain;      // every section on the way, top first
  bool suffixed = false;                          // key written with its unit suffix
  int form = 0;                                   // attitude key: its spelling (attitude_spellings), 0 the MRP
  size_t index = 0;                               // element of the (innermost) list
  std::vector<std::string> rest;                  // parts after a vector key (an element index)
  std::string error;                              // non-empty: the path does not resolve
  std::string error_key;                          // the key path the error names
};
// `list_size(list, depth)`: elements of the list named by parts[0..depth).
using ListSizeFn = std::function<size_t(const schema::Section&, size_t)>;
KeyTarget resolve_path(const std::vector<std::string>& parts, const ListSizeFn& list_size);
// The lists' sizes in a scenario (resolve_path against a Scenario).
ListSizeFn list_sizes(const Scenario& sc);

// Applies one override to the document `root`; problems go to ctx.issues
// (and ctx.overridden records the path for attributing later problems).
void apply_override(Ctx& ctx, YAML::Node& root, const Override& o);

}  // namespace harness

#endif  // HARNESS_SRC_OVERRIDES_H
