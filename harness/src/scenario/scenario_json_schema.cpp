// scenario_json_schema.cpp: a JSON Schema (draft-07) of the scenario file,
// generated from the key definitions (scenario_schema.h), for editors
// (`kestrel schema`, docs/scenario-schema.md).
//
// It carries the structure: the keys of every section (an unknown key is
// refused), their types (number, integer with its bounds, boolean, string,
// one of a set of words, 3-vector, inertia), the required keys and sections,
// list capacities, and a key given in two spellings (Omega_0 and
// Omega_0_rpm).  Value ranges held in code (a mass > 0, a unit vector, a
// positive-definite inertia) and the rules across keys stay with `kestrel
// validate`, which remains the authority.
#include <cstdint>
#include <limits>

#include "harness/scenario/scenario.h"
#include "scenario/scenario_schema.h"

namespace harness {

namespace {

using nlohmann::json;
using schema::KeyDef;
using schema::Section;
using schema::Type;

// The sections read_scenario() requires (scenario.cpp).
const std::vector<std::string> kRequiredSections = {"rates", "spacecraft", "fsw"};

json vec3_schema() { return schema::json_vec3(); }

json key_schema(const KeyDef& k)
{
  json j = json::object();
  switch (k.type) {
    case Type::Real: j["type"] = "number"; break;
    case Type::Integer: j = {{"type", "integer"}, {"minimum", k.lo}, {"maximum", k.hi}}; break;
    case Type::Unsigned:
      j = {{"type", "integer"}, {"minimum", 0}, {"maximum", std::numeric_limits<uint64_t>::max()}};
      break;
    case Type::Bool: j["type"] = "boolean"; break;
    case Type::String: j["type"] = "string"; break;
    case Type::Choice: j["enum"] = k.options; break;
    case Type::Vec3: j = vec3_schema(); break;
    case Type::UnitVec3:
      j = vec3_schema();
      j["description"] = "unit vector";
      break;
    case Type::Inertia:
      j["oneOf"] = json::array({vec3_schema(), {{"type", "array"}, {"items", vec3_schema()}, {"minItems", 3},
                                                {"maxItems", 3}}});
      j["description"] = "3 diagonal values or a 3x3 matrix";
      break;
    case Type::Custom:
      if (k.shape.is_object()) j = k.shape;
      break;
  }
  std::string doc = k.doc.empty() ? k.required : k.doc;
  if (j.contains("description")) doc = j["description"].get<std::string>() + (doc.empty() ? "" : ", " + doc);
  if (!doc.empty()) j["description"] = doc;
  return j;
}

json section_schema(const Section& s, bool with_required = true);

// The object of a section's keys and sub-sections.
json object_schema(const Section& s, bool with_required)
{
  json props = json::object(), required = json::array(), all_of = json::array();
  for (const KeyDef& k : s.keys) {
    props[k.name] = key_schema(k);
    if (!k.suffix.empty()) {
      json alt = key_schema(k);
      alt["description"] = k.name + " in its alternative unit (" + k.suffix.substr(1) + "); give one spelling only";
      props[k.name + k.suffix] = alt;
      // not both spellings; a required key in either
      all_of.push_back({{"not", {{"required", json::array({k.name, k.name + k.suffix})}}}});
      if (!k.required.empty() && with_required) {
        json either = json::array();
        either.push_back({{"required", json::array({k.name})}});
        either.push_back({{"required", json::array({k.name + k.suffix})}});
        all_of.push_back({{"anyOf", either}});
      }
    } else if (!k.required.empty() && with_required) {
      required.push_back(k.name);
    }
    if (k.attitude) {  // the MRP or one of its other forms, never two
      const std::vector<std::string> forms = schema::attitude_spellings(k.name);
      for (size_t f = 1; f < forms.size(); ++f) props[forms[f]] = schema::attitude_form_json(k.name, forms[f]);
      for (size_t a = 0; a < forms.size(); ++a)
        for (size_t b = a + 1; b < forms.size(); ++b)
          all_of.push_back({{"not", {{"required", json::array({forms[a], forms[b]})}}}});
    }
  }
  for (const Section& c : s.children) props[c.name] = section_schema(c);
  json j = {{"type", "object"}, {"additionalProperties", false}, {"properties", props}};
  if (!required.empty()) j["required"] = required;
  if (!all_of.empty()) j["allOf"] = all_of;
  return j;
}

json section_schema(const Section& s, bool with_required)
{
  if (!s.list) return object_schema(s, with_required);
  json j = {{"type", "array"}, {"items", object_schema(s, with_required)}};
  if (s.capacity > 0) j["maxItems"] = s.capacity;
  return j;
}

}  // namespace

namespace schema {

json json_vec3() { return {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 3}, {"maxItems", 3}}; }

json json_list_of(json item, size_t min_items, size_t max_items)
{
  json j = {{"type", "array"}, {"items", std::move(item)}};
  if (min_items > 0) j["minItems"] = min_items;
  if (max_items > 0) j["maxItems"] = max_items;
  return j;
}

json json_object_of(json properties, std::vector<std::string> required)
{
  json j = {{"type", "object"}, {"additionalProperties", false}, {"properties", std::move(properties)}};
  if (!required.empty()) j["required"] = required;
  return j;
}

}  // namespace schema

std::string scenario_json_schema_text(int indent)
{
  const Section& top = schema::schema();
  json j = object_schema(top, true);
  for (const std::string& r : kRequiredSections) j["required"].push_back(r);
  // wheels: a key missing from a wheel is taken from wheel_defaults, so a
  // wheel's required keys are required only when there are no defaults.
  if (const Section* w = top.child("wheels"); w && top.child("wheel_defaults")) {
    j["properties"]["wheel_defaults"] = section_schema(*top.child("wheel_defaults"), false);  // any subset
    j["properties"]["wheels"] = section_schema(*w, false);
    const json strict = object_schema(*w, true);
    json then = {{"properties", {{"wheels", {{"items", json::object()}}}}}};
    for (const char* part : {"required", "allOf"})
      if (strict.contains(part)) then["properties"]["wheels"]["items"][part] = strict[part];
    json no_defaults = {{"not", {{"required", json::array({"wheel_defaults"})}}}};
    j["allOf"].push_back({{"if", no_defaults}, {"then", then}});
  }
  json out = {{"$schema", "http://json-schema.org/draft-07/schema#"},
              {"title", "Kestrel scenario"},
              {"description", "A Kestrel scenario file (generated by `kestrel schema` from the harness's key table). "
                              "It checks keys, types and required keys; `kestrel validate` also checks value ranges "
                              "and the rules across keys."}};
  out.update(j);
  return out.dump(indent) + "\n";
}

}  // namespace harness
