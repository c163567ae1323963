// What a cycle-level configuration costs in host memory, for a warning before
// the run: every ray slot holds a ray, its emitted record and a traversal
// stepper with its on-chip stack, about 2.2 KB of host memory whatever
// stack_depth (measured with /usr/bin/time -v: 1,048,576 slots took 2.33 GB
// more than 64 slots; docs/reliability.md). Nothing else of the model grows
// with cores x slots_per_core.
#pragma once
#include <cstdint>

#include "hw/hw_config.h"

namespace vbsim::hw {

/// Host bytes a ray slot takes (measured; see above).
constexpr uint64_t kHostBytesPerSlot = 2300;
/// Configurations above this many host bytes of slots get a warning.
constexpr uint64_t kSlotMemoryWarningBytes = uint64_t{256} << 20;

/// Host bytes the ray slots of `cfg` take, about.
inline uint64_t slot_host_bytes(const HwConfig& cfg) {
  return uint64_t{cfg.cores} * cfg.slots_per_core * kHostBytesPerSlot;
}

}  // namespace vbsim::hw
