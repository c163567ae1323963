// The elaborated module tree of an accelerator as text and JSON (`vbsim hw
// --hierarchy`): every module instance with its class and parameters, and
// every port, export and socket with what it is bound to; and the statistics
// each kind of module declares (`vbsim hw --statistics`).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace sc_core {
class sc_object;
}

namespace vbsim::hw {

/// An indented tree below `root` (elaborated: ports bound).
std::string hierarchy_text(const sc_core::sc_object& root);
/// {"name", "kind", "parameters", "ports": [{"name", "kind", "bound_to"}], "children": [...]}.
nlohmann::json hierarchy_json(const sc_core::sc_object& root);
/// For each module class below `root`, once: its statistics (name, unit, description).
std::string statistics_text(const sc_core::sc_object& root);
nlohmann::json statistics_json(const sc_core::sc_object& root);

}  // namespace vbsim::hw
