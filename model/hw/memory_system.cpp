// make_memory: the memory a configuration describes.
#include <stdexcept>

#include "hw/memory_port.h"

namespace vbsim::hw {

std::unique_ptr<MemoryPort> make_memory(const MemoryConfig& config, int /*cores*/) {
  if (config.ideal) return std::make_unique<IdealMemory>(config.ideal_latency);
  throw std::runtime_error("memory: the cache hierarchy is not available in this build");
}

}  // namespace vbsim::hw
