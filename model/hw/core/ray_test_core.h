// Part contract (hw/core/): a ray-test core and its units (box unit, triangle
// tester with its front/back bit, intersection-avoidance unit: the built-in
// modules in hw/core/pipeline_units.h, their reservation tables in
// hw/unit_pipelines.h, the operations they take in
// hw/core/unit_operations.h). A unit decides when an operation issues and
// completes and computes what it answers through the plain-C++ datapath. The
// units are called by the scheduler (hw/scheduler/) through the core's ports;
// they call nothing else. The core holds its L1 (hw/memory/l1_cache.h) as a
// child module and binds it to its memory port, which the scheduler reads
// through; the units never reach the memory.
//
// RayTestCore: one of the patent's ray-test cores (FIG. 12), as a SystemC
// module holding its units: the box unit, the triangle tester (front/back bit),
// the intersection-avoidance unit and its L1 cache (or none: an ideal memory is
// bound to its memory port). It reaches them through its ports `box`,
// `triangle`, `avoidance` and `memory`, so another module can be bound instead
// (AcceleratorUnits); a replacement L1 implementing L2ClientIf has its
// read_done() port bound to the core's `read_done_target`. Its ray slots are the accelerator-wide slot ids
// [first_slot(), first_slot() + slots()); each slot holds one ray record (the
// datapath's Ray with its parent sign bit) and its BvhStepper, kept with the
// other cores' slots in one array by the scheduler for the host's caches.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <systemc>

#include "hw/accelerator_units.h"
#include "hw/core/pipeline_units.h"
#include "hw/hw_counters.h"
#include "hw/memory/l1_cache.h"
#include "hw/observe/stat_provider.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

/// Built-in units a group of cores shares (hw.<unit>.share > 1), owned by the
/// accelerator; null: the core builds its own.
struct SharedUnits {
  BoxUnit* box = nullptr;
  BoxUnit* box_low = nullptr;
  TriangleTester* triangle = nullptr;
  AvoidanceUnit* avoidance = nullptr;
};

class RayTestCore final : public sc_core::sc_module, public ReadDoneIf, public StatProvider {
 public:
  sc_core::sc_port<BoxUnitIf> box;
  /// The low-precision box pool (hw.box_low), bound when it has units.
  sc_core::sc_port<BoxUnitIf, 1, sc_core::SC_ZERO_OR_MORE_BOUND> box_low;
  sc_core::sc_port<TriangleTesterIf> triangle;
  sc_core::sc_port<AvoidanceUnitIf> avoidance;
  sc_core::sc_port<MemoryReadIf> memory;
  sc_core::sc_export<ReadDoneIf> read_done_target;  ///< where a pending read's answer arrives

  /// Core `index` of `config`; its units are built-in unless `units` replaces
  /// them, its own unless `shared` names its group's; `with_l1`: builds its L1
  /// (false: the accelerator binds `memory`).
  RayTestCore(sc_core::sc_module_name name, uint32_t index, const HwConfig& config, const AcceleratorUnits& units,
              TesterKind tester, const AvoidanceConfig& avoidance_config, bool avoidance_in_use, bool with_l1,
              const SharedUnits& shared = {});

  uint32_t index() const { return index_; }
  uint32_t first_slot() const { return first_slot_; }
  uint32_t slots() const { return slots_; }

  /// The built-in units bound to the ports, or null where a replacement is bound.
  BoxUnit* builtin_box() const { return builtin_box_; }
  BoxUnit* box_low_unit() const { return box_low_; }  ///< the low-precision pool, or null
  TriangleTester* builtin_triangle() const { return builtin_triangle_; }
  AvoidanceUnit* builtin_avoidance() const { return builtin_avoidance_; }
  L1Cache* l1() const { return l1_; }  ///< the built-in L1, or null
  /// A replacement L1 that reaches the L2 (L2ClientIf), or null.
  L2ClientIf* l2_client() const { return l2_client_; }
  /// The replacement bound in the built-in unit's place (AcceleratorUnits
  /// field `unit`: box_unit, triangle_tester, avoidance_unit, l1_cache), or null.
  sc_core::sc_module* replacement(const std::string& unit) const;

  /// Pending reads' answers go to `resume(slot, ready)` (the scheduler).
  void set_resume(std::function<void(uint32_t, uint64_t)> resume) { resume_ = std::move(resume); }
  void read_done(uint32_t slot, uint64_t ready) override { resume_(slot, ready); }

  CoreCounters counters;             ///< counted by the scheduler as it runs this core's slots
  std::vector<uint32_t> free_slots;  ///< accelerator-wide ids of the free slots (the last is taken next)

  const char* unit_kind() const override { return "RayTestCore"; }
  nlohmann::json parameters() const override;

 private:
  uint32_t index_, first_slot_, slots_, stack_depth_;
  std::vector<std::unique_ptr<sc_core::sc_module>> replacements_;
  BoxUnit* builtin_box_ = nullptr;
  BoxUnit* box_low_ = nullptr;
  TriangleTester* builtin_triangle_ = nullptr;
  AvoidanceUnit* builtin_avoidance_ = nullptr;
  L1Cache* l1_ = nullptr;
  L2ClientIf* l2_client_ = nullptr;
  sc_core::sc_module* replaced_box_ = nullptr;
  sc_core::sc_module* replaced_triangle_ = nullptr;
  sc_core::sc_module* replaced_avoidance_ = nullptr;
  sc_core::sc_module* replaced_l1_ = nullptr;
  std::unique_ptr<BoxUnit> box_unit_;
  std::unique_ptr<BoxUnit> box_unit_low_;
  std::unique_ptr<TriangleTester> triangle_tester_;
  std::unique_ptr<AvoidanceUnit> avoidance_unit_;
  std::unique_ptr<L1Cache> l1_cache_;
  std::function<void(uint32_t, uint64_t)> resume_;
};

}  // namespace vbsim::hw
