// AcceleratorUnits: replacements for the accelerator's built-in units. Each
// factory, when set, is called while the enclosing module is being built (so
// the new module becomes its child in the hierarchy, under the given name) and
// returns a module implementing the unit's interface (hw/unit_interfaces.h),
// which the enclosing module's port is bound to:
//
//   box_unit         BoxUnitIf         (in each core) the root's box, every child box of a node
//   triangle_tester  TriangleTesterIf  (in each core) one triangle: candidate, t, u, v, front/back bit
//   avoidance_unit   AvoidanceUnitIf   (in each core) one suspect candidate: reject or accept
//   l1_cache         MemoryReadIf      (in each core) the core's whole memory path, or, when it
//                                       also implements L2ClientIf, an L1 whose misses the
//                                       accelerator binds to the L2 (unit_interfaces.h)
//   dispatcher       DispatchIf
//   l2_cache         LineReadIf        the shared L2 and the memory behind it (the cores' L1s, and
//                                       replacement L1s implementing L2ClientIf, are bound to it);
//                                       it answers every line with its arrival cycle (nothing wakes
//                                       the scheduler for a kPendingCycle answer: the run stops,
//                                       its slots reported stuck); no TLM socket, no built-in DRAM
//                                       then; memory.ideal: not built
//   result_sink      ResultSinkIf      where finished rays go (bound to the built-in sink's port
//                                       `forward`; the built-in one stays as result_accounting for
//                                       the run's cycles and latencies; verdicts are the replacement's)
//
//   ray_source       RaySourceIf       (hw/source/ray_source_if.h) reads the feed, emits each ray through
//                                       the replayer it is given (FunctionalReplayer::emit, in trace
//                                       order) and dispatches it through SourceHost; the built-in
//                                       source's statistics (hw.source's counts, hw.emission) are
//                                       then absent, marked `replaced`
//
// The memory behind the built-in L2 is replaced at the TLM-2.0 socket instead
// (Accelerator::memory_socket with external_memory set; refused with l2_cache). A replaced unit
// decides when its operations happen and what they answer (the operation
// carries its payload: hw/core/unit_operations.h); a replacement that answers as
// the datapath does keeps every hit, one that computes otherwise (e.g.
// testbench/examples/reduced_precision/reduced_precision_units.h) changes what the rays hit.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>

#include <systemc>

#include "hw/hw_config.h"
#include "replay/functional_replayer.h"

namespace vbsim::hw {

struct AcceleratorUnits {
  /// name: the instance's name; core: the core it belongs to; config: the accelerator's.
  using CoreUnitFactory =
      std::function<std::unique_ptr<sc_core::sc_module>(const char* name, uint32_t core, const HwConfig& config)>;
  using UnitFactory = std::function<std::unique_ptr<sc_core::sc_module>(const char* name, const HwConfig& config)>;

  CoreUnitFactory box_unit, triangle_tester, avoidance_unit, l1_cache;
  UnitFactory dispatcher, l2_cache, result_sink;
  /// replayer: the emission step a replacement source runs on each ray (outlives it).
  using SourceFactory = std::function<std::unique_ptr<sc_core::sc_module>(const char* name, const HwConfig& config,
                                                                          FunctionalReplayer& replayer)>;
  SourceFactory ray_source;
  /// Leave the L2's TLM-2.0 socket (Accelerator::memory_socket) for the user to
  /// bind to their own memory target instead of the built-in Dram.
  bool external_memory = false;
};

/// `m` as interface `If`: throws std::invalid_argument naming the instance
/// when the replacement does not implement it.
template <class If>
If& replacement_as(sc_core::sc_module& m, const char* interface_name) {
  if (auto* i = dynamic_cast<If*>(&m)) return *i;
  throw std::invalid_argument(std::string(m.name()) + ": a replacement unit must implement " + interface_name);
}

}  // namespace vbsim::hw
