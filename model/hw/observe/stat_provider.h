// Part contract (hw/observe/): what a run tells about itself, never what it
// does: statistics declared by each module (this file) and gathered by walking
// the module tree, the `hw` section and its table (hw/observe/hw_stats.h),
// energy and area (hw/observe/hw_energy.h), warm-up and interval samples,
// latency distributions, the hierarchy report, and the VCD and timeline
// recorders (with the scopes they record). Every part may declare statistics
// and write to a recorder it is given; nothing here is called while a cycle is
// decided, so observing never changes a cycle or a hit.
//
// StatProvider: what a module of the accelerator tells about itself - its
// parameters and its statistics, each statistic declared where it is counted
// with a name, a unit and a one-line description. The `hw.instances` section of
// the stats JSON is gathered by walking the SystemC object tree and asking every
// object that is a StatProvider (gather_instance_stats), keyed by hierarchical
// instance name; `vbsim hw --hierarchy` prints the parameters, `vbsim hw
// --statistics` the declarations.
//
// A statistic reads its counter when the statistics are gathered (after a run),
// so counting costs nothing beyond the increment itself.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sc_core {
class sc_object;
}

namespace vbsim::hw {

struct StatDeclaration {
  std::string name;         ///< short name, unique within the module ("hits")
  std::string unit;         ///< "lines", "cycles", "operations", "ratio", ...
  std::string description;  ///< one line
  std::function<nlohmann::json()> value;
};

class StatProvider {
 public:
  virtual ~StatProvider() = default;
  /// The unit's class as the hierarchy shows it ("BoxUnit").
  virtual const char* unit_kind() const = 0;
  /// The parameters this instance was built with (JSON object).
  virtual nlohmann::json parameters() const = 0;
  const std::vector<StatDeclaration>& statistics() const { return stats_; }
  /// The statistics' values, by name (JSON object).
  nlohmann::json stat_values() const;

 protected:
  /// A counter the module increments; read when the statistics are gathered.
  void declare_stat(std::string name, std::string unit, std::string description, const uint64_t& counter);
  /// Several declarations at once (a part's own list, e.g. cache_level_statistics).
  void declare_stats(std::vector<StatDeclaration> stats) {
    for (StatDeclaration& s : stats) stats_.push_back(std::move(s));
  }
  /// A value derived when the statistics are gathered.
  void declare_stat(std::string name, std::string unit, std::string description,
                    std::function<nlohmann::json()> value);

 private:
  std::vector<StatDeclaration> stats_;
};

/// Every StatProvider at or below `root`, in the tree's order (parents before
/// their children, children in creation order), with its hierarchical name.
std::vector<std::pair<std::string, const StatProvider*>> stat_providers(const sc_core::sc_object& root);

/// {"accelerator.core_0.box_unit": {"ops": 12, ...}, ...} for everything below `root`.
nlohmann::json gather_instance_stats(const sc_core::sc_object& root);

}  // namespace vbsim::hw
