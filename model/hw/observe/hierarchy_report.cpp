#include "hw/observe/hierarchy_report.h"

#include <cxxabi.h>

#include <cstdlib>
#include <map>
#include <typeinfo>
#include <set>

#include <fmt/format.h>
#include <systemc>
#include <tlm>

#include "hw/observe/stat_provider.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

namespace {

bool is_module(const sc_core::sc_object& o) { return dynamic_cast<const sc_core::sc_module*>(&o) != nullptr; }

/// The instance that implements the interface `iface` (its sc_object's name), or "".
std::string owner_of(const sc_core::sc_interface* iface) {
  if (!iface) return "";
  if (const auto* o = dynamic_cast<const sc_core::sc_object*>(iface)) return o->name();
  return "(an object outside the hierarchy)";
}

/// Every interface a port of interface `IF` is bound to, by owner, when `o` is one.
template <class IF>
bool list_bindings(const sc_core::sc_object& o, std::string& out) {
  const auto* p = dynamic_cast<const sc_core::sc_port_b<IF>*>(&o);
  if (!p) return false;
  for (int i = 0; i < p->size(); ++i) out += (i ? ", " : "") + owner_of(p->get_interface(i));
  return true;
}

/// What a port, export or socket reaches, by name.
std::string bound_to(const sc_core::sc_object& o) {
  if (const auto* p = dynamic_cast<const sc_core::sc_port_base*>(&o)) {
    std::string out;
    if (!list_bindings<BoxUnitIf>(o, out) && !list_bindings<TriangleTesterIf>(o, out) &&
        !list_bindings<AvoidanceUnitIf>(o, out) && !list_bindings<MemoryReadIf>(o, out) &&
        !list_bindings<LineReadIf>(o, out) && !list_bindings<LineFillIf>(o, out) &&
        !list_bindings<ReadDoneIf>(o, out))
      out = owner_of(p->get_interface());
    return out.empty() ? "(unbound)" : out;
  }
  if (const auto* e = dynamic_cast<const sc_core::sc_export_base*>(&o))
    return owner_of(const_cast<sc_core::sc_export_base*>(e)->get_interface());
  return "";
}

/// The short form of a port's kind ("sc_port", "sc_export", "tlm_initiator_socket").
std::string port_kind(const sc_core::sc_object& o) { return o.kind(); }

nlohmann::json params_of(const sc_core::sc_object& o) {
  if (const auto* p = dynamic_cast<const StatProvider*>(&o)) return p->parameters();
  return nlohmann::json::object();
}

/// The module's class: what a vbsim unit calls itself, else its C++ class name
/// without namespaces (a user's module), else SystemC's kind.
std::string class_of(const sc_core::sc_object& o) {
  if (const auto* p = dynamic_cast<const StatProvider*>(&o)) return p->unit_kind();
  if (!is_module(o)) return o.kind();
  int status = 0;
  char* name = abi::__cxa_demangle(typeid(o).name(), nullptr, nullptr, &status);
  std::string s = status == 0 && name ? name : o.kind();
  std::free(name);
  const size_t colon = s.rfind("::");
  return colon == std::string::npos ? s : s.substr(colon + 2);
}

std::string params_line(const nlohmann::json& params) {
  std::string s;
  for (const auto& [k, v] : params.items()) {
    const std::string value = v.is_string() ? v.get<std::string>() : v.dump();
    s += fmt::format("{}{}={}", s.empty() ? "" : " ", k, value);
  }
  return s;
}

void text(const sc_core::sc_object& o, const std::string& indent, std::string& out) {
  out += fmt::format("{}{}  [{}]", indent, o.basename(), class_of(o));
  const std::string params = params_line(params_of(o));
  if (!params.empty()) out += "  " + params;
  out += "\n";
  for (const sc_core::sc_object* c : o.get_child_objects()) {
    if (is_module(*c) || !(dynamic_cast<const sc_core::sc_port_base*>(c) || dynamic_cast<const sc_core::sc_export_base*>(c)))
      continue;
    const std::string to = bound_to(*c);
    if (to == o.name()) continue;  // an export of the module's own interface
    out += fmt::format("{}    .{} ({}) -> {}\n", indent, c->basename(), port_kind(*c), to);
  }
  for (const sc_core::sc_object* c : o.get_child_objects())
    if (is_module(*c)) text(*c, indent + "  ", out);
}

nlohmann::json json_of(const sc_core::sc_object& o) {
  nlohmann::json ports = nlohmann::json::array(), children = nlohmann::json::array();
  for (const sc_core::sc_object* c : o.get_child_objects()) {
    if (is_module(*c)) children.push_back(json_of(*c));
    else if (dynamic_cast<const sc_core::sc_port_base*>(c) || dynamic_cast<const sc_core::sc_export_base*>(c))
      ports.push_back({{"name", c->name()}, {"kind", port_kind(*c)}, {"bound_to", bound_to(*c)}});
  }
  return {{"name", o.name()}, {"class", class_of(o)}, {"parameters", params_of(o)}, {"ports", ports},
          {"children", children}};
}

}  // namespace

std::string hierarchy_text(const sc_core::sc_object& root) {
  std::string out;
  text(root, "", out);
  return out;
}

nlohmann::json hierarchy_json(const sc_core::sc_object& root) { return json_of(root); }

nlohmann::json statistics_json(const sc_core::sc_object& root) {
  nlohmann::json j = nlohmann::json::array();
  std::set<std::string> seen;
  for (const auto& [name, p] : stat_providers(root)) {
    if (!seen.insert(p->unit_kind()).second) continue;
    nlohmann::json stats = nlohmann::json::array();
    for (const StatDeclaration& s : p->statistics())
      stats.push_back({{"name", s.name}, {"unit", s.unit}, {"description", s.description}});
    j.push_back({{"class", p->unit_kind()}, {"example", name}, {"statistics", stats}});
  }
  return j;
}

std::string statistics_text(const sc_core::sc_object& root) {
  std::string out;
  for (const auto& k : statistics_json(root)) {
    out += fmt::format("{} (e.g. {})\n", k["class"].get<std::string>(), k["example"].get<std::string>());
    for (const auto& s : k["statistics"])
      out += fmt::format("  {:<26} {:<12} {}\n", s["name"].get<std::string>(), s["unit"].get<std::string>(),
                         s["description"].get<std::string>());
  }
  return out;
}

}  // namespace vbsim::hw
