// yaml_json.cpp: the node tree of a JSON document (yaml_of_json, the kept
// tree of a campaign's draws, a scalar's text as dump() writes it); see
// yaml_reader.h.
#include <array>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "scenario/yaml_reader.h"

namespace harness {

std::string json_scalar_text(const nlohmann::json& j)
{
  if (j.is_number_float()) {
    const double x = j.get<double>();
    if (std::isfinite(x)) {  // the serializer's own shortest round-trip digits (non-finite: dump's "null")
      std::array<char, 64> b{};
      const char* const e = nlohmann::detail::to_chars(b.data(), b.data() + b.size(), x);
      return std::string(b.data(), static_cast<size_t>(e - b.data()));
    }
  } else if (j.is_number_unsigned()) {
    return std::to_string(j.get<uint64_t>());
  } else if (j.is_number_integer()) {
    return std::to_string(j.get<int64_t>());
  } else if (j.is_boolean()) {
    return j.get<bool>() ? "true" : "false";
  }
  return j.dump();
}

namespace {

bool is_container(const nlohmann::json& j) { return j.is_object() || j.is_array(); }

// A scalar or null node of j (not an object or array).
YAML::Node yaml_scalar_of_json(const nlohmann::json& j)
{
  if (j.is_string()) return YAML::Node(j.get_ref<const std::string&>());
  if (j.is_null() || j.is_discarded()) return YAML::Node(YAML::NodeType::Null);
  return YAML::Node(json_scalar_text(j));  // a number or a boolean, as the text writes it
}

// The elements of object or array j into n (a map or a sequence), top
// down: each new node joins the tree's node memory alone (yaml-cpp merges
// a subtree's memory node by node into its parent's when it is inserted).
// leaves (not null): each scalar and null node in turn, in j's order.
void fill_yaml(YAML::Node& n, const nlohmann::json& j, std::vector<YAML::Node>* leaves)
{
  const bool map = j.is_object();
  for (auto it = j.begin(); it != j.end(); ++it) {
    const nlohmann::json& v = it.value();
    YAML::Node c = is_container(v) ? YAML::Node(v.is_object() ? YAML::NodeType::Map : YAML::NodeType::Sequence)
                                   : yaml_scalar_of_json(v);
    if (map) n.force_insert(it.key(), c);
    else n.push_back(c);
    if (is_container(v)) fill_yaml(c, v, leaves);
    else if (leaves) leaves->push_back(c);  // c is the node in the tree (its memory joined the tree's)
  }
}

// Whether b has a's shape: the same containers with the same keys in the
// same order and the same sizes, null where a has null; the leaves whose
// value differs (type, or bits of a double: -0.0 and 0.0 write differently)
// go to changed with their position among the leaves.
bool same_shape(const nlohmann::json& a, const nlohmann::json& b, size_t& leaf,
                std::vector<std::pair<size_t, const nlohmann::json*>>& changed)
{
  if (is_container(a) || is_container(b)) {
    if (a.type() != b.type() || a.size() != b.size()) return false;
    if (a.is_object()) {
      for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib)
        if (ia.key() != ib.key() || !same_shape(ia.value(), ib.value(), leaf, changed)) return false;
    } else {
      for (size_t i = 0; i < a.size(); ++i)
        if (!same_shape(a[i], b[i], leaf, changed)) return false;
    }
    return true;
  }
  if (a.is_null() != b.is_null()) return false;  // a null node against a scalar
  bool same = a.type() == b.type();
  if (same && a.is_number_float()) {
    const double x = a.get<double>(), y = b.get<double>();
    same = std::memcmp(&x, &y, sizeof x) == 0;
  } else if (same) {
    same = a == b;
  }
  if (!same) changed.emplace_back(leaf, &b);
  ++leaf;
  return true;
}

// The tree of j; leaves as fill_yaml's.
YAML::Node tree_of_json(const nlohmann::json& j, std::vector<YAML::Node>* leaves)
{
  if (!is_container(j)) return yaml_scalar_of_json(j);
  YAML::Node root(j.is_object() ? YAML::NodeType::Map : YAML::NodeType::Sequence);
  fill_yaml(root, j, leaves);
  return root;
}

}  // namespace

YAML::Node yaml_of_json(const nlohmann::json& j) { return tree_of_json(j, nullptr); }

const YAML::Node& KeptYamlTree::tree_of(nlohmann::json j)
{
  std::vector<std::pair<size_t, const nlohmann::json*>> changed;
  size_t leaf = 0;
  if (is_container(j) && kept_ && same_shape(json_, j, leaf, changed) && leaf == leaves_.size()) {
    kept_ = false;  // until every changed scalar is set: an exception here leaves the tree to be built anew
    for (const auto& [i, v] : changed)  // a scalar's text set in place (no new node)
      leaves_[i] = v->is_string() ? v->get_ref<const std::string&>() : json_scalar_text(*v);
    kept_ = true;
    ++reused_;
  } else {
    kept_ = false;
    // The old tree goes whole with its memory: assigning a new node to the
    // old handle would make yaml-cpp keep the old nodes in the new tree's memory.
    leaves_.clear();
    tree_.reset();
    tree_.emplace(tree_of_json(j, &leaves_));
    kept_ = is_container(j);
    ++built_;
  }
  json_ = std::move(j);
  return *tree_;
}

}  // namespace harness
