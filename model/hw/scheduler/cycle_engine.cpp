// make_cycle_engine: the scheduler (hw/scheduler/engine.h) instantiated for
// the run's triangle tester and memory, and its report of busy slots.
#include "hw/scheduler/cycle_engine.h"

#include <algorithm>
#include <sstream>

#include "datapath/testers.h"
#include "hw/scheduler/engine.h"
#include "hw/scheduler/engine_dispatch.h"
#include "hw/scheduler/engine_steps.h"
#include "hw/scheduler/engine_fast_forward.h"

namespace vbsim::hw {

namespace engine_detail {
namespace {

template <class Tester, class Memory>
std::string Engine<Tester, Memory>::slot_report(size_t max_slots) const {
  static const char* kinds[] = {"node", "leaf", "refill", "done"};
  std::ostringstream out;
  size_t shown = 0;
  for (uint32_t id = 0; id < slots_.size(); ++id) {
    const std::vector<uint32_t>& free = cores_[slots_[id].core].core->free_slots;
    if (std::find(free.begin(), free.end(), id) != free.end()) continue;
    if (shown++ == max_slots) {
      out << "  ...\n";
      break;
    }
    const Slot& s = slots_[id];
    out << "  " << cores_[s.core].core->name() << " slot " << id - cores_[s.core].core->first_slot() << ": ray "
        << s.tr.id << " (trace position " << s.trace_index << "), dispatched at cycle " << s.dispatched << ", next step "
        << kinds[s.pending.kind] << " " << s.pending.index;
    if (s.parked) out << ", waiting since cycle " << s.requested << " for a read";
    out << "\n";
  }
  out << source_.buffer_report();
  return out.str();
}

template <class Tester>
std::unique_ptr<CycleEngine> make_for_tester(const EngineParts& p) {
  bool builtin_units = true;
  for (const CoreBinding& c : p.cores)
    builtin_units &= c.box_builtin && c.triangle_builtin && c.avoidance_builtin;
  if (builtin_units && p.builtin_l1s) return std::make_unique<Engine<Tester, L1Cache>>(p);
  if (builtin_units && p.builtin_ideal) return std::make_unique<Engine<Tester, IdealMemory>>(p);
  return std::make_unique<Engine<Tester, MemoryReadIf>>(p);
}

}  // namespace
}  // namespace engine_detail

std::unique_ptr<CycleEngine> make_cycle_engine(const EngineParts& p) {
  switch (p.replayer.options().tester) {
    case TesterKind::MollerTrumbore: return engine_detail::make_for_tester<MollerTrumboreTester>(p);
    case TesterKind::PbrtWatertight: return engine_detail::make_for_tester<PbrtWatertightTester>(p);
    case TesterKind::ThreeHalfPlane:
    default: return engine_detail::make_for_tester<ThreeHalfPlaneTester>(p);
  }
}

}  // namespace vbsim::hw
