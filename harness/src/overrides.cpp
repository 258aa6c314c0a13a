// overrides.cpp: see overrides.h.
#include "overrides.h"

namespace harness {

std::vector<std::string> split_path(const std::string& p)
{
  std::vector<std::string> out;
  std::string cur;
  for (char c : p) {
    if (c == '.' || c == '[' || c == ']') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

namespace {
bool all_digits(const std::string& p) { return !p.empty() && p.find_first_not_of("0123456789") == std::string::npos; }
}  // namespace

std::string normalise_path(const std::vector<std::string>& parts)
{
  std::string s;
  for (const std::string& p : parts) {
    if (all_digits(p)) s += "[" + p + "]";
    else s += (s.empty() ? "" : ".") + p;
  }
  return s;
}

bool parse_index(const std::string& part, size_t size, size_t& out)
{
  if (!all_digits(part) || part.size() > 9) return false;  // 9 digits: far above any list here
  size_t v = 0;
  for (char c : part) v = v * 10 + static_cast<size_t>(c - '0');
  if (v >= size) return false;
  out = v;
  return true;
}

void apply_override(Ctx& ctx, YAML::Node& root, const Override& o)
{
  const std::vector<std::string> parts = split_path(o.path);
  const std::string norm = normalise_path(parts);
  ctx.overridden.insert(norm);
  ScenarioIssue is;
  is.file = ctx.file;
  is.key = norm;
  is.where = "--set " + o.path + "=" + o.value;
  if (parts.empty()) {
    is.message = "empty key path";
    ctx.issues->push_back(is);
    return;
  }
  YAML::Node value;
  try {
    value = YAML::Load(o.value);
  } catch (const YAML::Exception& e) {
    is.message = std::string("value is not valid YAML: ") + e.msg;
    ctx.issues->push_back(is);
    return;
  }
  if (!root.IsMap()) {
    is.message = "the scenario is not a map";
    ctx.issues->push_back(is);
    return;
  }
  // Walk down, creating maps as needed; list indices must exist.
  std::vector<YAML::Node> chain{root};
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    const std::string& p = parts[i];
    if (cur.IsSequence()) {
      size_t k = 0;
      if (!parse_index(p, cur.size(), k)) {
        is.message = "no list element '" + p + "' (the list has " + std::to_string(cur.size()) + " entries)";
        ctx.issues->push_back(is);
        return;
      }
      chain.push_back(cur[k]);
    } else if (cur.IsMap() || cur.IsNull()) {
      if (!cur[p].IsDefined() || cur[p].IsNull()) cur[p] = YAML::Node(YAML::NodeType::Map);
      chain.push_back(cur[p]);
    } else {
      is.message = "'" + p + "' is inside a scalar";
      ctx.issues->push_back(is);
      return;
    }
  }
  YAML::Node last = chain.back();
  const std::string& leaf = parts.back();
  if (last.IsSequence()) {
    size_t k = 0;
    if (!parse_index(leaf, last.size(), k)) {
      is.message = "no list element '" + leaf + "' (the list has " + std::to_string(last.size()) + " entries)";
      ctx.issues->push_back(is);
      return;
    }
    last[k] = value;
  } else if (last.IsMap()) {
    last[leaf] = value;
  } else {
    is.message = "cannot set a key inside a scalar";
    ctx.issues->push_back(is);
  }
}

}  // namespace harness
