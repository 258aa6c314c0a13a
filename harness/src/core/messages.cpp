#include "harness/core/messages.h"

#include <sstream>

namespace harness {

namespace {
std::string dot_quote(const std::string& s)
{
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}
}  // namespace

bool DataFlow::has_message(const std::string& name) const
{
  for (const auto& c : channels_)
    if (c->name() == name) return true;
  return false;
}

void DataFlow::check_new_message(const std::string& name) const
{
  if (name.empty()) throw std::invalid_argument("dataflow: empty message name");
  if (has_message(name)) throw std::invalid_argument("dataflow: message '" + name + "' registered twice");
}

void DataFlow::add_component(const std::string& name, const std::string& kind)
{
  for (auto& c : components_) {
    if (c.first == name) {
      if (c.second.empty()) c.second = kind;
      return;
    }
  }
  components_.emplace_back(name, kind);
}

void DataFlow::add_edge(const std::string& component, const std::string& message, bool writes)
{
  if (!has_message(message))
    throw std::invalid_argument("dataflow: message '" + message + "' is not registered");
  add_component(component);
  if (writes) {
    const std::string w = writer_of(message);
    if (!w.empty() && w != component)
      throw std::invalid_argument("dataflow: message '" + message + "' already written by '" + w +
                                  "', cannot also be written by '" + component + "'");
  }
  for (const auto& e : edges_)
    if (e.component == component && e.message == message && e.writes == writes) return;
  edges_.push_back(DataFlowEdge{component, message, writes});
}

std::vector<std::string> DataFlow::messages() const
{
  std::vector<std::string> out;
  for (const auto& c : channels_) out.push_back(c->name());
  return out;
}

std::string DataFlow::writer_of(const std::string& message) const
{
  for (const auto& e : edges_)
    if (e.writes && e.message == message) return e.component;
  return "";
}

std::vector<std::string> DataFlow::readers_of(const std::string& message) const
{
  std::vector<std::string> out;
  for (const auto& e : edges_)
    if (!e.writes && e.message == message) out.push_back(e.component);
  return out;
}

std::string DataFlow::to_dot(const std::string& graph_name) const
{
  std::ostringstream os;
  os << "digraph " << dot_quote(graph_name) << " {\n";
  os << "  rankdir=LR;\n";
  os << "  node [fontname=\"Helvetica\", fontsize=10];\n";
  for (const auto& c : components_) {
    os << "  " << dot_quote("c:" + c.first) << " [shape=box, style=\"rounded,filled\", fillcolor=\"#dde8f5\", label="
       << dot_quote(c.second.empty() ? c.first : c.first + " (" + c.second + ")") << "];\n";
  }
  for (const auto& ch : channels_) {
    os << "  " << dot_quote("m:" + ch->name()) << " [shape=ellipse, label=" << dot_quote(ch->name())
       << "];\n";
  }
  for (const auto& e : edges_) {
    if (e.writes)
      os << "  " << dot_quote("c:" + e.component) << " -> " << dot_quote("m:" + e.message) << ";\n";
    else
      os << "  " << dot_quote("m:" + e.message) << " -> " << dot_quote("c:" + e.component) << ";\n";
  }
  os << "}\n";
  return os.str();
}

}  // namespace harness
