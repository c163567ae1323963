#include "hw/core/ray_test_core.h"

namespace vbsim::hw {

namespace {

/// Binds `port` to the replacement `factory` makes (kept in `kept`), to the
/// built-in unit `shared` its group of cores shares, or to the built-in unit
/// made by `builtin`. Returns the built-in unit, or null.
template <class Unit, class If, class Make>
Unit* bind_unit(sc_core::sc_port<If>& port, const AcceleratorUnits::CoreUnitFactory& factory, const char* name,
                uint32_t core, const HwConfig& config, const char* interface_name, std::unique_ptr<Unit>& own,
                std::vector<std::unique_ptr<sc_core::sc_module>>& kept, Unit* shared, Make builtin) {
  if (factory) {
    kept.push_back(factory(name, core, config));
    port.bind(replacement_as<If>(*kept.back(), interface_name));
    return nullptr;
  }
  if (shared) {
    port.bind(*shared);
    return shared;
  }
  own = builtin(name);
  port.bind(*own);
  return own.get();
}

}  // namespace

RayTestCore::RayTestCore(sc_core::sc_module_name name, uint32_t index, const HwConfig& config,
                         const AcceleratorUnits& units, TesterKind tester, const AvoidanceConfig& avoidance_config,
                         bool avoidance_in_use, bool with_l1, const SharedUnits& shared)
    : sc_core::sc_module(name), box("box"), box_low("box_low"), triangle("triangle"), avoidance("avoidance"), memory("memory"),
      read_done_target("read_done_target"), index_(index), first_slot_(index * config.slots_per_core),
      slots_(config.slots_per_core), stack_depth_(config.stack_depth) {
  read_done_target.bind(*this);
  builtin_box_ = bind_unit(box, units.box_unit, "box_unit", index, config, "BoxUnitIf", box_unit_, replacements_,
                           shared.box, [&](const char* n) { return std::make_unique<BoxUnit>(n, config.box); });
  if (units.box_unit) replaced_box_ = replacements_.back().get();
  if (shared.box_low) {
    box_low_ = shared.box_low;
    box_low.bind(*box_low_);
  } else if (config.box_low.count > 0) {
    box_unit_low_ = std::make_unique<BoxUnit>("box_unit_low", config.box_low);
    box_low_ = box_unit_low_.get();
    box_low.bind(*box_low_);
  }
  builtin_triangle_ = bind_unit(triangle, units.triangle_tester, "triangle_tester", index, config, "TriangleTesterIf",
                                triangle_tester_, replacements_, shared.triangle, [&](const char* n) {
                                  return std::make_unique<TriangleTester>(n, for_tester(config, tester).triangle, tester);
                                });
  if (units.triangle_tester) replaced_triangle_ = replacements_.back().get();
  builtin_avoidance_ = bind_unit(avoidance, units.avoidance_unit, "avoidance_unit", index, config, "AvoidanceUnitIf",
                                 avoidance_unit_, replacements_, shared.avoidance, [&](const char* n) {
                                   return std::make_unique<AvoidanceUnit>(n, config.avoidance, avoidance_config,
                                                                          avoidance_in_use);
                                 });
  if (units.avoidance_unit) replaced_avoidance_ = replacements_.back().get();
  if (units.l1_cache) {
    replacements_.push_back(units.l1_cache("l1_cache", index, config));
    replaced_l1_ = replacements_.back().get();
    memory.bind(replacement_as<MemoryReadIf>(*replacements_.back(), "MemoryReadIf"));
    l2_client_ = dynamic_cast<L2ClientIf*>(replacements_.back().get());
    if (l2_client_) l2_client_->read_done().bind(read_done_target);
  } else if (with_l1) {
    l1_cache_ = std::make_unique<L1Cache>("l1_cache", config.memory.l1, index, first_slot_, slots_);
    l1_ = l1_cache_.get();
    memory.bind(l1_->target);
    l1_->done.bind(read_done_target);
  }
  for (uint32_t s = slots_; s-- > 0;) free_slots.push_back(first_slot_ + s);
  const CoreCounters& c = counters;
  declare_stat("rays", "rays", "rays finished on this core", c.rays);
  declare_stat("slot_cycles", "slot-cycles", "cycles its slots held a ray (dispatch to result), summed",
               c.slot_cycles);
  declare_stat("node_fetches", "reads", "node reads (each tests every child box: 2, 4 or 8)", c.node_fetches);
  declare_stat("leaf_fetches", "reads", "leaf reads (a leaf's triangles in one read)", c.leaf_fetches);
  declare_stat("refill_reads", "reads", "traversal stack refills from the spill area", c.refill_reads);
  declare_stat("memory_wait_cycles", "slot-cycles", "cycles node and leaf reads waited for their data",
               c.memory_wait_cycles);
  declare_stat("refill_wait_cycles", "slot-cycles", "cycles stack refills waited for their data",
               c.refill_wait_cycles);
  declare_stat("spills", "entries", "stack entries pushed past the on-chip stack", c.spills);
}

sc_core::sc_module* RayTestCore::replacement(const std::string& unit) const {
  if (unit == "box_unit") return replaced_box_;
  if (unit == "triangle_tester") return replaced_triangle_;
  if (unit == "avoidance_unit") return replaced_avoidance_;
  if (unit == "l1_cache") return replaced_l1_;
  return nullptr;
}

nlohmann::json RayTestCore::parameters() const {
  return {{"index", index_}, {"slots", slots_}, {"first_slot", first_slot_}, {"stack_depth", stack_depth_}};
}

}  // namespace vbsim::hw
