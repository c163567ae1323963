// Replacement units that change WHAT is computed, for an architect to start
// from: a box unit and a triangle tester that hold their operands with fewer
// mantissa bits (datapath/reduced_precision.h). Bound through AcceleratorUnits
// (the factories below); their timing is the built-in units' (the same
// UnitConfig: `count` pipelines of `latency`), so what changes in a run is the
// work the rays do and the hits they find. Measured on the bundled trace in
// docs/hw-model.md ("Reduced precision"); testbench/module/
// reduced_precision_units_test.cpp checks the claims below.
//
//   ReducedPrecisionBoxUnit       node bounds (and the root's) rounded outward to
//                                 `bits` fraction bits, then the full-precision
//                                 slab test: a box can only grow, so a ray meets
//                                 every box it met before (more box and triangle
//                                 tests, more cycles) and its closest hit stays
//                                 the same.
//   ReducedPrecisionTriangleTester  vertices rounded to nearest with `bits`
//                                 fraction bits, then the configured tester: the
//                                 triangles move, so hits change (counted against
//                                 the full-precision run).
//
// Both declare their operation inventory (PricedUnitIf, hw/unit_inventory.h),
// so that hw_json()'s energy and area price them: the built-in unit's
// operations plus the rounding, counted from datapath/reduced_precision.h at
// full width (a technology file has no narrower operators).
#pragma once
#include <cstdint>

#include <systemc>

#include "datapath/testers.h"
#include "hw/accelerator_units.h"
#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/unit_interfaces.h"
#include "hw/unit_inventory.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

class ReducedPrecisionBoxUnit final : public sc_core::sc_module, public BoxUnitIf, public PricedUnitIf {
 public:
  sc_core::sc_export<BoxUnitIf> target;

  /// Timing `timing`, bounds with `bits` fraction bits (0 .. 23).
  ReducedPrecisionBoxUnit(sc_core::sc_module_name name, const UnitConfig& timing, int bits);
  BoxAnswer test_boxes(const BoxOp& op) override;
  int bits() const { return bits_; }
  /// Rounding one box's six bounds outward (round_magnitude): per bound a test
  /// of the dropped bits and an add or mask (2 int), the direction chosen by
  /// the sign (1 select).
  static OpCounts rounding_ops() { return ops::iadd(12) + ops::fsel(6); }
  /// Per box: the built-in slab test and the rounding; per ray: the built-in set-up.
  UnitInventory inventory() const override;

 private:
  int bits_;
  uint32_t latency_;
  UnitCounters counters_;
  UnitPipelines pipes_;
};

class ReducedPrecisionTriangleTester final : public sc_core::sc_module, public TriangleTesterIf, public PricedUnitIf {
 public:
  sc_core::sc_export<TriangleTesterIf> target;

  /// Timing `timing`, tester `kind` on vertices with `bits` fraction bits (0 .. 23).
  ReducedPrecisionTriangleTester(sc_core::sc_module_name name, const UnitConfig& timing, TesterKind kind, int bits);
  TriangleAnswer test_triangle(const TriangleOp& op) override;
  int bits() const { return bits_; }
  /// Rounding a triangle's nine coordinates to nearest (round_nearest): per
  /// coordinate the tie bit's test, the add and the mask (3 int).
  static OpCounts rounding_ops() { return ops::iadd(27); }
  /// Per triangle: the configured tester's test and the rounding; per ray: its set-up.
  UnitInventory inventory() const override;

 private:
  TesterKind kind_;
  int bits_;
  uint32_t latency_;
  UnitCounters counters_;
  UnitPipelines pipes_;
};

/// AcceleratorUnits::box_unit making a ReducedPrecisionBoxUnit with the configuration's box timing.
AcceleratorUnits::CoreUnitFactory reduced_precision_box_unit(int bits);
/// AcceleratorUnits::triangle_tester making a ReducedPrecisionTriangleTester of
/// `kind` (the run's tester) with that tester's timing (for_tester).
AcceleratorUnits::CoreUnitFactory reduced_precision_triangle_tester(int bits, TesterKind kind);

}  // namespace vbsim::hw
