// UnitInventory: what a replacement unit (AcceleratorUnits, hw/accelerator_units.h)
// declares so that the energy and area model prices it (docs/energy.md,
// docs/hw-model.md "Replacing a unit"): its operations by kind of operator, as the
// built-in units' are counted (datapath/op_counts.h, datapath/datapath_ops.h),
// and the register bits it holds. A replacement declares it by also
// implementing PricedUnitIf; one that does not is reported as not priced
// (`"priced": false` with its instance's name in hw.energy and hw.area), never
// priced as the built-in unit it replaces. Read once, after a run, when the
// energy and area are computed: nothing on the per-ray path.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "datapath/op_counts.h"

namespace vbsim::hw {

struct UnitInventory {
  /// The operations of one of the unit's operations: a box unit's for one box
  /// tested (a node of width w is w of them, as box_test_ops()), a triangle
  /// tester's for one triangle (triangle_test_ops(); the method's candidate
  /// compare is added as for the built-in tester), an avoidance unit's for one
  /// suspect (the method's MethodOps::suspect).
  OpCounts per_operation;
  /// The per-ray set-up (box unit and triangle tester: box_setup_ops(),
  /// triangle_setup_ops()); none for an avoidance unit.
  OpCounts per_ray;
  /// Register bits the unit holds (priced at the technology file's register-bit area).
  double storage_bits = 0;
};

/// Implemented (besides the unit's interface) by a replacement unit that
/// declares its inventory.
class PricedUnitIf {
 public:
  virtual ~PricedUnitIf() = default;
  virtual UnitInventory inventory() const = 0;
};

/// One replaced unit as the pricing sees it: the AcceleratorUnits field it
/// replaces ("box_unit", "triangle_tester", "avoidance_unit", "l1_cache",
/// "l2_cache", "dispatcher", "result_sink", "ray_source"), the hierarchical
/// name of its (first) instance, and its inventory when it declares one. Only
/// the box unit, the triangle tester and the avoidance unit can be priced from
/// an inventory; any other replaced unit is reported as not priced.
struct ReplacedUnit {
  std::string unit;
  std::string instance;
  std::optional<UnitInventory> inventory;
  bool priced() const {
    return inventory && (unit == "box_unit" || unit == "triangle_tester" || unit == "avoidance_unit");
  }
};
using ReplacedUnits = std::vector<ReplacedUnit>;

}  // namespace vbsim::hw
