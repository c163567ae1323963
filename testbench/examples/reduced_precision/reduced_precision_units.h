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
#pragma once
#include <cstdint>

#include <systemc>

#include "datapath/testers.h"
#include "hw/accelerator_units.h"
#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/unit_interfaces.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

class ReducedPrecisionBoxUnit final : public sc_core::sc_module, public BoxUnitIf {
 public:
  sc_core::sc_export<BoxUnitIf> target;

  /// Timing `timing`, bounds with `bits` fraction bits (0 .. 23).
  ReducedPrecisionBoxUnit(sc_core::sc_module_name name, const UnitConfig& timing, int bits);
  BoxAnswer test_boxes(const BoxOp& op) override;
  int bits() const { return bits_; }

 private:
  int bits_;
  uint32_t latency_;
  UnitCounters counters_;
  UnitPipelines pipes_;
};

class ReducedPrecisionTriangleTester final : public sc_core::sc_module, public TriangleTesterIf {
 public:
  sc_core::sc_export<TriangleTesterIf> target;

  /// Timing `timing`, tester `kind` on vertices with `bits` fraction bits (0 .. 23).
  ReducedPrecisionTriangleTester(sc_core::sc_module_name name, const UnitConfig& timing, TesterKind kind, int bits);
  TriangleAnswer test_triangle(const TriangleOp& op) override;
  int bits() const { return bits_; }

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
