#include "hw/observe/stat_provider.h"

#include <systemc>

namespace vbsim::hw {

namespace {

void collect(const sc_core::sc_object& obj, std::vector<std::pair<std::string, const StatProvider*>>& out) {
  if (const auto* p = dynamic_cast<const StatProvider*>(&obj)) out.emplace_back(obj.name(), p);
  for (const sc_core::sc_object* child : obj.get_child_objects()) collect(*child, out);
}

}  // namespace

nlohmann::json StatProvider::stat_values() const {
  nlohmann::json j = nlohmann::json::object();
  for (const StatDeclaration& s : stats_) j[s.name] = s.value();
  return j;
}

void StatProvider::declare_stat(std::string name, std::string unit, std::string description, const uint64_t& counter) {
  const uint64_t* c = &counter;
  stats_.push_back({std::move(name), std::move(unit), std::move(description), [c] { return nlohmann::json(*c); }});
}

void StatProvider::declare_stat(std::string name, std::string unit, std::string description,
                                std::function<nlohmann::json()> value) {
  stats_.push_back({std::move(name), std::move(unit), std::move(description), std::move(value)});
}

std::vector<std::pair<std::string, const StatProvider*>> stat_providers(const sc_core::sc_object& root) {
  std::vector<std::pair<std::string, const StatProvider*>> out;
  collect(root, out);
  return out;
}

nlohmann::json gather_instance_stats(const sc_core::sc_object& root) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, p] : stat_providers(root)) j[name] = p->stat_values();
  return j;
}

}  // namespace vbsim::hw
