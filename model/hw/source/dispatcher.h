// Dispatcher: hands each emitted ray to a core with a free ray slot
// (DispatchIf at `target`). round-robin: the next core after the last one
// chosen that has a free slot; least-loaded: the core with the most free slots
// (the lowest numbered on a tie).
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/observe/stat_provider.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

class Dispatcher final : public sc_core::sc_module, public DispatchIf, public StatProvider {
 public:
  sc_core::sc_export<DispatchIf> target;

  Dispatcher(sc_core::sc_module_name name, DispatchPolicy policy);

  int pick(const uint32_t* free_slots, uint32_t cores) override;

  const char* unit_kind() const override { return "Dispatcher"; }
  nlohmann::json parameters() const override { return {{"policy", dispatch_policy_name(policy_)}}; }

 private:
  DispatchPolicy policy_;
  uint32_t next_ = 0;  // round-robin: the core to try first
  uint64_t dispatched_ = 0;
};

}  // namespace vbsim::hw
