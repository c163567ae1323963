#include "hw/source/dispatcher.h"

namespace vbsim::hw {

Dispatcher::Dispatcher(sc_core::sc_module_name name, DispatchPolicy policy)
    : sc_core::sc_module(name), target("target"), policy_(policy) {
  target.bind(*this);
  declare_stat("rays", "rays", "rays handed to a core", dispatched_);
}

int Dispatcher::pick(const uint32_t* free_slots, uint32_t cores) {
  if (policy_ == DispatchPolicy::RoundRobin) {
    for (uint32_t k = 0; k < cores; ++k) {
      const uint32_t c = (next_ + k) % cores;
      if (free_slots[c] != 0) {
        next_ = (c + 1) % cores;
        ++dispatched_;
        return static_cast<int>(c);
      }
    }
    return -1;
  }
  int best = -1;
  for (uint32_t c = 0; c < cores; ++c)
    if (free_slots[c] != 0 && (best < 0 || free_slots[c] > free_slots[best])) best = static_cast<int>(c);
  dispatched_ += best >= 0;
  return best;
}

}  // namespace vbsim::hw
