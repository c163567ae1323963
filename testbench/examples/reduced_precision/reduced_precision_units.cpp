#include "reduced_precision/reduced_precision_units.h"

#include <memory>
#include <stdexcept>
#include <string>

#include "datapath/datapath_ops.h"
#include "datapath/reduced_precision.h"
#include "hw/core/pipeline_units.h"

namespace vbsim::hw {

namespace {

int checked_bits(int bits, const char* name) {
  if (bits < 0 || bits > 23)
    throw std::invalid_argument(std::string(name) + ": bits must be 0 .. 23, not " + std::to_string(bits));
  return bits;
}

}  // namespace

ReducedPrecisionBoxUnit::ReducedPrecisionBoxUnit(sc_core::sc_module_name name, const UnitConfig& timing, int bits)
    : sc_core::sc_module(name), target("target"), bits_(checked_bits(bits, sc_core::sc_module::name())),
      latency_(timing.latency), pipes_(timing, counters_, sc_core::sc_module::name()) {
  target.bind(*this);
}

BoxAnswer ReducedPrecisionBoxUnit::test_boxes(const BoxOp& op) {
  BoxOp rounded = op;
  BvhNode node;
  BvhNode4 node4;
  BvhNode8 node8;
  Bounds3f root;
  if (op.node_record) {
    node = round_outward(*op.node_record, bits_);
    rounded.node_record = &node;
  } else if (op.node4_record) {
    node4 = round_outward(*op.node4_record, bits_);
    rounded.node4_record = &node4;
  } else if (op.node8_record) {
    node8 = round_outward(*op.node8_record, bits_);
    rounded.node8_record = &node8;
  } else {
    root = round_outward(*op.root, bits_);
    rounded.root = &root;
  }
  BoxAnswer a = BoxUnit::compute(rounded);
  const uint64_t issue = pipes_.issue(op.ready, op.now);
  a.schedule = {issue, issue + latency_};
  return a;
}

UnitInventory ReducedPrecisionBoxUnit::inventory() const {
  UnitInventory i;
  i.per_operation = box_test_ops() + rounding_ops();
  i.per_ray = box_setup_ops();
  return i;
}

UnitInventory ReducedPrecisionTriangleTester::inventory() const {
  UnitInventory i;
  i.per_operation = triangle_test_ops(kind_) + rounding_ops();
  i.per_ray = triangle_setup_ops(kind_);
  return i;
}

ReducedPrecisionTriangleTester::ReducedPrecisionTriangleTester(sc_core::sc_module_name name, const UnitConfig& timing,
                                                               TesterKind kind, int bits)
    : sc_core::sc_module(name), target("target"), kind_(kind), bits_(checked_bits(bits, sc_core::sc_module::name())),
      latency_(timing.latency), pipes_(timing, counters_, sc_core::sc_module::name()) {
  target.bind(*this);
}

TriangleAnswer ReducedPrecisionTriangleTester::test_triangle(const TriangleOp& op) {
  const Triangle tri = round_nearest(*op.triangle, bits_);
  TriangleOp rounded = op;
  rounded.triangle = &tri;
  TriangleAnswer a = TriangleTester::compute(kind_, rounded);
  const uint64_t issue = pipes_.issue(op.ready, op.now);
  a.schedule = {issue, issue + latency_};
  return a;
}

AcceleratorUnits::CoreUnitFactory reduced_precision_box_unit(int bits) {
  return [bits](const char* name, uint32_t, const HwConfig& c) {
    return std::make_unique<ReducedPrecisionBoxUnit>(name, c.box, bits);
  };
}

AcceleratorUnits::CoreUnitFactory reduced_precision_triangle_tester(int bits, TesterKind kind) {
  return [bits, kind](const char* name, uint32_t, const HwConfig& c) {
    return std::make_unique<ReducedPrecisionTriangleTester>(name, for_tester(c, kind).triangle, kind, bits);
  };
}

}  // namespace vbsim::hw
