// overrides.cpp: see overrides.h.
#include "scenario/overrides.h"

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

ListSizeFn list_sizes(const Scenario& sc)
{
  return [&sc](const schema::Section& list, size_t) { return list.count ? list.count(sc) : 0; };
}

namespace {
// The attitude key of `sec` that `name` spells in another form (form: its index), or null.
const schema::KeyDef* attitude_form(const schema::Section& sec, const std::string& name, int& form)
{
  for (const schema::KeyDef& k : sec.keys) {
    if (!k.attitude) continue;
    const std::vector<std::string> s = schema::attitude_spellings(k.name);
    for (size_t f = 1; f < s.size(); ++f)
      if (s[f] == name) {
        form = static_cast<int>(f);
        return &k;
      }
  }
  return nullptr;
}
}  // namespace

KeyTarget resolve_path(const std::vector<std::string>& parts, const ListSizeFn& list_size)
{
  KeyTarget t;
  const schema::Section* sec = &schema::schema();
  t.chain.push_back(sec);
  t.section = sec;
  for (size_t d = 0; d < parts.size(); ++d) {
    const std::string& p = parts[d];
    const std::vector<std::string> upto(parts.begin(), parts.begin() + static_cast<std::ptrdiff_t>(d) + 1);
    bool suffixed = false;
    if (const schema::KeyDef* k = sec->key(p, suffixed)) {
      t.key = k;
      t.suffixed = suffixed;
      t.rest.assign(parts.begin() + static_cast<std::ptrdiff_t>(d) + 1, parts.end());
      const bool listish = k->type == schema::Type::Vec3 || k->type == schema::Type::UnitVec3 ||
                           k->type == schema::Type::Inertia || k->type == schema::Type::Custom;
      if (!t.rest.empty() && !(listish && t.rest.size() == 1)) {
        t.error_key = normalise_path(parts);
        t.error = "'" + p + "' is a single value: cannot set '" + t.rest.front() + "' inside it";
      }
      return t;
    }
    if (const schema::KeyDef* k = attitude_form(*sec, p, t.form)) {  // sigma_R0N_quaternion, ...: set whole
      t.key = k;
      t.rest.assign(parts.begin() + static_cast<std::ptrdiff_t>(d) + 1, parts.end());
      if (!t.rest.empty()) {
        t.error_key = normalise_path(parts);
        t.error = "'" + p + "' is set whole: cannot set '" + t.rest.front() + "' inside it";
      }
      return t;
    }
    const schema::Section* c = sec->child(p);
    if (!c) {
      t.error_key = normalise_path(upto);
      t.error = "unknown key";
      const std::string near = did_you_mean(p, sec->known_names());
      if (!near.empty()) t.error += " (did you mean '" + near + "'?)";
      return t;
    }
    sec = c;
    t.chain.push_back(sec);
    t.section = sec;
    if (sec->list && d + 1 < parts.size()) {
      const size_t n = list_size(*sec, d + 1);
      ++d;
      if (!parse_index(parts[d], n, t.index)) {
        t.error_key = normalise_path(parts);
        t.error = "no list element '" + parts[d] + "' (the list has " + std::to_string(n) + " entries)";
        return t;
      }
    }
  }
  return t;  // a whole section (or one list element)
}

namespace {

// The node at parts[0..depth) of the document (undefined when absent).
// Read-only: YAML::Node::reset rebinds (plain assignment would overwrite
// the node it refers to).
YAML::Node node_at(const YAML::Node& root, const std::vector<std::string>& parts, size_t depth)
{
  YAML::Node cur;
  cur.reset(root);
  for (size_t d = 0; d < depth; ++d) {
    const YAML::Node here = cur;
    size_t k = 0;
    if (here.IsMap() && here[parts[d]].IsDefined()) cur.reset(here[parts[d]]);
    else if (here.IsSequence() && parse_index(parts[d], here.size(), k)) cur.reset(here[k]);
    else return YAML::Node(YAML::NodeType::Undefined);
  }
  return cur;
}

std::string no_element(const std::string& part, size_t size)
{
  return "no list element '" + part + "' (the list has " + std::to_string(size) + " entries)";
}

// The value of an override by the key's type: a word stays a word; anything
// else is YAML.  "" or why it is not a value.
std::string override_value(const KeyTarget& t, const std::string& text, const std::string& file, YAML::Node& value)
{
  const bool word =
      t.key && t.rest.empty() && (t.key->type == schema::Type::String || t.key->type == schema::Type::Choice);
  if (word) {
    value = YAML::Node(text);
    return "";
  }
  // the same bounds as a file (aliases, depth, one document, binary bytes)
  const std::vector<ScenarioIssue> bounds = check_yaml_text(text, file);
  if (!bounds.empty()) {
    const std::string& m = bounds.front().message;
    const std::string syntax = "YAML syntax error: ";
    return m.rfind(syntax, 0) == 0 ? "value is not valid YAML: " + m.substr(syntax.size()) : "value: " + m;
  }
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return std::string("value is not valid YAML: ") + e.msg;
  }
  return "";
}

// Puts `value` at `parts` of the document: walks down, creating maps as
// needed; list indices exist (resolved before) unless an element index of a
// vector key is out of its list.  "" or why it cannot be put there.
std::string put_value(YAML::Node& root, const std::vector<std::string>& parts, const KeyTarget& t,
                      const YAML::Node& value)
{
  std::vector<YAML::Node> chain{root};
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    const std::string& p = parts[i];
    size_t k = 0;
    if (cur.IsSequence()) {
      if (!parse_index(p, cur.size(), k)) return no_element(p, cur.size());
      chain.push_back(cur[k]);
    } else if (cur.IsMap() || cur.IsNull()) {
      if (!cur[p].IsDefined() || cur[p].IsNull()) cur[p] = YAML::Node(YAML::NodeType::Map);
      chain.push_back(cur[p]);
    } else {
      return "'" + p + "' is inside a scalar";
    }
  }
  YAML::Node last = chain.back();
  const std::string& leaf = parts.back();
  size_t k = 0;
  if (last.IsSequence()) {
    if (!parse_index(leaf, last.size(), k)) return no_element(leaf, last.size());
    last[k] = value;
  } else if (last.IsMap()) {
    last[leaf] = value;
    // One spelling replaces the other (Omega_0 and Omega_0_rpm; an attitude's forms).
    if (t.key && t.rest.empty() && !t.key->suffix.empty())
      last.remove(t.suffixed ? t.key->name : t.key->name + t.key->suffix);
    if (t.key && t.rest.empty() && t.key->attitude)
      for (const std::string& s : schema::attitude_spellings(t.key->name))
        if (s != leaf) last.remove(s);
  } else {
    return "cannot set a key inside a scalar";
  }
  return "";
}

}  // namespace

void apply_override(Ctx& ctx, YAML::Node& root, const Override& o)
{
  const std::vector<std::string> parts = split_path(o.path);
  const std::string norm = normalise_path(parts);
  ctx.overridden.insert(norm);
  ScenarioIssue is;
  is.file = ctx.file;
  is.key = norm;
  is.where = "--set " + o.path + "=" + o.value;
  auto fail = [&](const std::string& msg) {
    is.message = msg;
    ctx.issues->push_back(is);
  };
  if (parts.empty()) {
    is.key = "(--set)";
    return fail("empty key path");
  }
  if (!root.IsMap()) return fail("the scenario is not a map");
  // Resolve against the key definitions first.
  const KeyTarget t = resolve_path(parts, [&root, &parts](const schema::Section&, size_t depth) {
    const YAML::Node l = node_at(root, parts, depth);
    return l.IsSequence() ? l.size() : size_t{0};
  });
  if (!t.error.empty()) {
    is.key = t.error_key;
    if (t.error.rfind("unknown key", 0) == 0) is.where = "--set " + norm;
    return fail(t.error);
  }
  // One element of a vector key: only of a list the document has.
  if (t.key && !t.rest.empty() && !node_at(root, parts, parts.size() - 1).IsSequence())
    return fail("'" + t.key->name + "' is not a list in the file: set the whole vector");
  YAML::Node value;
  std::string bad = override_value(t, o.value, ctx.file, value);
  if (bad.empty()) bad = put_value(root, parts, t, value);
  if (!bad.empty()) fail(bad);
}

// ---- the typed setter (harness/scenario.h) -------------------------------------

namespace {
// The settable key `path` names in sc (a thrown ScenarioError otherwise).
KeyTarget settable_key(const Scenario& sc, const std::string& path, const char* verb)
{
  const std::vector<std::string> parts = split_path(path);
  ScenarioIssue is;
  is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
  is.key = normalise_path(parts);
  is.where = std::string(verb) + " " + path;
  auto fail = [&is](const std::string& msg) {
    is.message = msg;
    throw ScenarioError({is});
  };
  if (parts.empty()) fail("empty key path");
  const KeyTarget t = resolve_path(parts, list_sizes(sc));
  if (!t.error.empty()) {
    is.key = t.error_key;
    fail(t.error);
  }
  if (!t.key) fail("names a section, not a key: set its keys one by one");
  if (t.form > 0) fail("an attitude form is read from a file or --set only; set '" + t.key->name + "' (the MRP)");
  if (!t.rest.empty()) fail("set the whole vector, not one element");
  for (const schema::Section* s : t.chain) {
    if (s->input_only) fail("'" + s->name + "' " + s->note);
    if (s->present && !s->present(sc)) fail("there is no '" + s->name + "' in this scenario");
  }
  if (!t.key->set) fail("cannot be set with set_parameter (a list sized by the scenario); use --set or the file");
  return t;
}
}  // namespace

void set_parameter(Scenario& sc, const std::string& path, const ParameterValue& value)
{
  const KeyTarget t = settable_key(sc, path, "set_parameter");
  const std::string why = t.key->set(*t.key, sc, t.index, value, t.suffixed);
  if (why.empty()) return;
  ScenarioIssue is;
  is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
  is.key = normalise_path(split_path(path));
  is.where = "set_parameter " + path;
  is.message = why;
  throw ScenarioError({is});
}

ParameterValue get_parameter(const Scenario& sc, const std::string& path)
{
  const KeyTarget t = settable_key(sc, path, "get_parameter");
  nlohmann::json j = nlohmann::json::object();
  if (t.key->write) t.key->write(*t.key, j, sc, t.index);
  const double f = t.suffixed ? t.key->factor : 1.0;
  auto absent = [&]() -> ParameterValue {
    ScenarioIssue is;
    is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
    is.key = normalise_path(split_path(path));
    is.where = "get_parameter " + path;
    is.message = "has no value in this scenario (an optional key not given)";
    throw ScenarioError({is});
  };
  if (!j.contains(t.key->name)) return absent();
  const nlohmann::json& v = j[t.key->name];
  switch (t.key->type) {
    case schema::Type::Real: return ParameterValue(v.get<double>() / f);
    case schema::Type::Integer: return ParameterValue(v.get<long long>());
    case schema::Type::Unsigned: return ParameterValue(v.get<uint64_t>());
    case schema::Type::Bool: return ParameterValue(v.get<bool>());
    case schema::Type::String:
    case schema::Type::Choice: return ParameterValue(v.get<std::string>());
    case schema::Type::Vec3:
    case schema::Type::UnitVec3:
      return ParameterValue(Eigen::Vector3d(v.at(0).get<double>() / f, v.at(1).get<double>() / f, v.at(2).get<double>() / f));
    case schema::Type::Inertia: {
      Eigen::Matrix3d m;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = v.at(static_cast<size_t>(r)).at(static_cast<size_t>(c)).get<double>();
      return ParameterValue(m);
    }
    case schema::Type::Custom: break;
  }
  return absent();
}

void validate_scenario(const Scenario& sc)
{
  try {
    load_scenario_text(scenario_to_json_text(sc), "(canonical form)");
  } catch (const ScenarioError& e) {
    std::vector<ScenarioIssue> issues = e.issues();
    for (ScenarioIssue& is : issues) {
      is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
      is.line = 0;
      is.column = 0;
      is.where.clear();
    }
    throw ScenarioError(issues);
  }
}

namespace {
void collect_paths(const schema::Section& s, const std::string& prefix, std::vector<std::string>& out)
{
  for (const schema::KeyDef& k : s.keys) {
    out.push_back(join(prefix, k.name));
    if (!k.suffix.empty()) out.push_back(join(prefix, k.name + k.suffix));
  }
  for (const schema::Section& c : s.children)
    collect_paths(c, c.list ? join(prefix, c.name) + "[i]" : join(prefix, c.name), out);
}
}  // namespace

std::vector<std::string> scenario_key_paths()
{
  std::vector<std::string> out;
  collect_paths(schema::schema(), "", out);
  return out;
}

}  // namespace harness
