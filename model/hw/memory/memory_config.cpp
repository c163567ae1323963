// check_memory_config: the checks of the memory configuration (errors name the
// field the engine's config parser fills), and the TLM style's names.
#include <cmath>
#include <stdexcept>
#include <string>

#include "hw/memory/memory_config.h"

namespace vbsim::hw {

namespace {

bool is_power_of_two(uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }

[[noreturn]] void reject(const std::string& field, const std::string& why) {
  throw std::invalid_argument("memory." + field + ": " + why);
}

void check_cache(const CacheConfig& c, const std::string& name, uint32_t min_hit_latency) {
  if (c.line_bytes == 0 || !is_power_of_two(c.line_bytes))
    reject(name + ".line_bytes", "must be a power of two, got " + std::to_string(c.line_bytes));
  if (c.ways == 0 || c.ways > kMaxCacheWays)
    reject(name + ".ways", "must be 1 to " + std::to_string(kMaxCacheWays) + ", got " + std::to_string(c.ways));
  if (c.size_bytes == 0) reject(name + ".size_bytes", "must be greater than 0");
  const uint64_t set_bytes = uint64_t{c.ways} * c.line_bytes;
  if (c.size_bytes < set_bytes)
    reject(name + ".ways", std::to_string(c.ways) + " ways of " + std::to_string(c.line_bytes) +
                               "-byte lines do not fit in " + std::to_string(c.size_bytes) + " bytes");
  if (c.size_bytes % set_bytes != 0)
    reject(name + ".size_bytes", std::to_string(c.size_bytes) + " is not a whole number of sets of " +
                                     std::to_string(c.ways) + " ways x " + std::to_string(c.line_bytes) +
                                     " bytes");
  if (c.hit_latency < min_hit_latency)
    reject(name + ".hit_latency", "must be at least " + std::to_string(min_hit_latency) + " cycle");
  if (c.mshrs == 0) reject(name + ".mshrs", "must be at least 1");
  if (c.port_cycles == 0) reject(name + ".port_cycles", "must be at least 1");
}

}  // namespace

namespace {

/// ceil(line_bytes x dram_latency_per_byte): the per-byte part of a line
/// request's latency (per_byte in [0, 1000], checked first).
uint64_t dram_line_extra_cycles(const MemoryConfig& config) {
  // A product such as 64 x 0.1 lands a hair above the whole number it means.
  const double extra = std::ceil(config.l2.line_bytes * config.dram_latency_per_byte - 1e-9);
  return extra > 0 ? static_cast<uint64_t>(extra) : 0;
}

}  // namespace

uint32_t dram_line_latency(const MemoryConfig& config) {
  return config.dram_latency + static_cast<uint32_t>(dram_line_extra_cycles(config));
}

const char* tlm_style_name(TlmStyle s) { return s == TlmStyle::LooselyTimed ? "lt" : "at"; }

void check_memory_config(const MemoryConfig& config, int cores) {
  if (!config.hierarchy()) return;  // an ideal memory or object caches: no hierarchy to check
  if (cores < 1) throw std::invalid_argument("cores: must be at least 1, got " + std::to_string(cores));
  // An L1 hit is the fastest answer and must take at least one cycle (port contract).
  check_cache(config.l1, "l1", 1);
  check_cache(config.l2, "l2", 0);
  if (config.l2.ports != 0) reject("l2.ports", "the L2's ports are not modelled (only memory.l1.ports)");
  if (config.l2.line_bytes != config.l1.line_bytes)
    reject("l2.line_bytes", "must equal memory.l1.line_bytes (" + std::to_string(config.l1.line_bytes) +
                                "), got " + std::to_string(config.l2.line_bytes));
  if (config.dram_latency == 0) reject("dram_latency", "must be at least 1 cycle");
  const double per_byte = config.dram_latency_per_byte;
  if (!std::isfinite(per_byte) || per_byte < 0 || per_byte > 1000)
    reject("dram_latency_per_byte", "must be a number from 0 to 1000");
  if (uint64_t{config.dram_latency} + dram_line_extra_cycles(config) > 100000000)
    reject("dram_latency_per_byte", "a line request would take more than 10^8 cycles");
  const double bpc = config.dram_bytes_per_cycle;
  if (!std::isfinite(bpc) || bpc <= 0) reject("dram_bytes_per_cycle", "must be a positive number");
  if (config.l2.line_bytes / bpc > 1048576.0)
    reject("dram_bytes_per_cycle", "too small: one line would take more than 2^20 cycles");
  if (config.dram_max_outstanding == 0) reject("dram_max_outstanding", "must be at least 1");
}

const char* object_cache_name(ObjectCachesConfig::Kind k) {
  switch (k) {
    case ObjectCachesConfig::NodeLow: return "node_low";
    case ObjectCachesConfig::Node: return "node";
    case ObjectCachesConfig::Triangle: return "triangle";
    default: return "?";
  }
}

}  // namespace vbsim::hw
