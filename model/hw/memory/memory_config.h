// The memory system's configuration: a private L1 per core, a shared L2 and a
// DRAM target behind a TLM-2.0 socket (docs/memory-model.md), or an ideal memory.
#pragma once
#include <cstdint>

namespace vbsim::hw {

/// One cache level. Sizes in bytes; latencies in core clock cycles.
/// The most ways a cache may have (a lookup compares every way of its set).
constexpr uint32_t kMaxCacheWays = 65536;

struct CacheConfig {
  uint32_t size_bytes = 0;
  uint32_t ways = 0;
  uint32_t line_bytes = 64;
  uint32_t hit_latency = 0;  ///< cycles from request to data on a hit
  uint32_t mshrs = 0;        ///< misses in flight at once (outstanding-miss limit)
  /// A request for a line whose miss is in flight waits for that miss (true),
  /// or is a miss of its own: an MSHR and a request to the next level (false).
  bool merge_misses = true;
  /// The L1 only: reads it accepts at once (0: any number, no port limit), each
  /// port taking a new read `port_cycles` cycles after its previous one. A read
  /// that finds every port busy waits; its lookups happen when a port takes it.
  uint32_t ports = 0;
  uint32_t port_cycles = 1;
};

/// How the L2's misses cross the TLM-2.0 socket to the DRAM target.
enum class TlmStyle {
  LooselyTimed,        ///< b_transport with delay annotation (exact with the built-in DRAM)
  ApproximatelyTimed,  ///< nb_transport_fw/bw, base protocol phases, responses when the target sends them
};
const char* tlm_style_name(TlmStyle s);  ///< "lt" / "at"

/// One object cache of ObjectCachesConfig.
struct ObjectCacheConfig {
  uint32_t entries = 0;  ///< objects it holds (0: none, every read goes to DRAM)
  uint32_t bytes = 0;    ///< bytes of one object as DRAM sends it (0: the read's own bytes)
};

/// Object caches per core, as rtcore-systemc's core has them, in place of the
/// L1, the L2 and the DRAM model (hw/memory/object_caches.h): three fully associative
/// LRU caches of whole records (nodes both of whose children are low precision,
/// other nodes, triangles), each read one lookup of one object; a miss reads
/// the object from DRAM in dram_latency + ceil(bytes x dram_latency_per_byte)
/// cycles, any number in flight, never merged with another miss.
struct ObjectCachesConfig {
  bool enabled = false;
  enum Kind : uint8_t { NodeLow, Node, Triangle, kKinds };
  ObjectCacheConfig cache[kKinds];
  uint32_t hit_latency = 2;  ///< cycles from a lookup to a hit's data (and from a fill's arrival to its data)
  uint32_t port_cycles = 1;  ///< a cache takes a lookup every this many cycles
  uint32_t responses_per_cycle = 1;  ///< DRAM responses a core takes a cycle (0: any number)
};
const char* object_cache_name(ObjectCachesConfig::Kind k);  ///< "node_low", "node", "triangle"

/// The memory system of the accelerator: a private L1 per core, a shared L2, DRAM.
struct MemoryConfig {
  bool ideal = false;          ///< every read takes ideal_latency cycles, no caches
  uint32_t ideal_latency = 1;  ///< cycles per read of the ideal memory
  CacheConfig l1{16 * 1024, 4, 64, 2, 8};
  CacheConfig l2{1024 * 1024, 8, 64, 14, 32};
  uint32_t dram_latency = 120;        ///< cycles from an L2 miss to its line arriving (unloaded)
  /// Further unloaded cycles per byte a request reads (a line: line_bytes of
  /// them), rounded up to whole cycles per request: dram_line_latency().
  double dram_latency_per_byte = 0;
  double dram_bytes_per_cycle = 16;   ///< DRAM bandwidth in bytes per core clock cycle
  uint32_t dram_max_outstanding = 32; ///< DRAM requests in flight at once
  TlmStyle tlm = TlmStyle::LooselyTimed;
  /// Approximately timed: the target's promise that no response comes sooner
  /// than this many cycles after its request, so the scheduler may handle
  /// events up to that far ahead of the oldest request in flight (1: lock-step).
  uint32_t at_lookahead_cycles = 1;
  /// An L1 miss that waits for an MSHR is looked up in the shared L2 at the
  /// cycle it leaves the L1 (true), so that the L2 takes every lookup in time
  /// order, at a cost in simulation speed; false: when it is found, stamped
  /// with that cycle (the L2's accesses_out_of_time_order counts them).
  bool l2_lookups_in_time_order = false;
  /// Enabled: object caches in place of the hierarchy (ideal must be false).
  ObjectCachesConfig objects;
  /// Whether the L1 / L2 / DRAM hierarchy is built (neither ideal nor object caches).
  bool hierarchy() const { return !ideal && !objects.enabled; }
};

/// The unloaded latency of one line request: dram_latency plus
/// ceil(line_bytes x dram_latency_per_byte) cycles.
uint32_t dram_line_latency(const MemoryConfig& config);

/// Throws std::invalid_argument naming the field ("memory.l1.ways: ...") when
/// `config` cannot describe a hierarchy for `cores` cores. Ideal memories pass.
void check_memory_config(const MemoryConfig& config, int cores);

}  // namespace vbsim::hw
