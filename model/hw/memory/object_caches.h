// ObjectCaches: one core's memory as rtcore-systemc builds it (memory.objects),
// bound to the core's memory port in place of the L1, the L2 and the DRAM
// model. Three fully associative LRU caches of whole objects:
//
//   node_low   a node both of whose children are low precision (Bvh::low_precision_node)
//   node       any other node
//   triangle   a triangle (or a leaf's triangles read at once: one object)
//
// Each read is one lookup of one object, keyed by its address (BvhAddressMap
// says which region, so which cache, an address is in); a read of the stack
// spill area goes to DRAM uncached. A cache takes a lookup every
// `port_cycles` cycles. A hit's data are there `hit_latency` cycles after its
// lookup. A miss reads the object from DRAM: `dram_latency` +
// ceil(bytes x dram_latency_per_byte) cycles (bytes: the cache's object size,
// or the read's own), any number in flight, the core taking
// `responses_per_cycle` responses a cycle (the first free cycle at or after
// the arrival), and its data are there `hit_latency` cycles after it arrives.
// A miss is never merged: a lookup of an object whose read is still in flight
// misses and reads it again, as rtcore's reorder buffer does. As in rtcore, an
// object takes an entry when its data arrive, not when it misses: a read in
// flight holds no entry and evicts nothing; at its arrival the object goes to
// the front of the LRU order (already there from an earlier read: it moves to
// the front) and the least recently used entry leaves if the cache is full. A
// hit moves its object to the front. Arrivals are applied in cycle order
// before each lookup at or after them (a cache's lookups come in cycle order:
// its port issues them so).
#pragma once
#include <cstdint>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/memory/bvh_address_map.h"
#include "hw/memory/memory_interfaces.h"
#include "hw/memory/timed_queue.h"
#include "hw/observe/stat_provider.h"
#include "hw/unit_pipelines.h"
#include "scene/bvh.h"

namespace vbsim::hw {

/// What one object cache counted.
struct ObjectCacheCounters {
  uint64_t lookups = 0, hits = 0, misses = 0;
  uint64_t misses_in_flight = 0;  ///< misses of an object whose earlier read had not arrived
  uint64_t dram_bytes = 0;        ///< bytes its misses read
  void add(const ObjectCacheCounters& o) {
    lookups += o.lookups;
    hits += o.hits;
    misses += o.misses;
    misses_in_flight += o.misses_in_flight;
    dram_bytes += o.dram_bytes;
  }
};

class ObjectCaches final : public sc_core::sc_module, public MemoryReadIf, public StatProvider {
 public:
  sc_core::sc_export<MemoryReadIf> target;  ///< bound by the core

  /// `bvh` must outlive the module (its address map and node precisions route reads).
  ObjectCaches(sc_core::sc_module_name name, const HwConfig& config, const Bvh& bvh);

  uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) override;

  /// Functional warming (sampled simulation, hw/sampling/): the object a read
  /// of `addr` looks up goes to the front of its cache's LRU order, entering
  /// it (and evicting the least recently used when full) if absent, as its
  /// arrival would. No time, no counter; spill reads are uncached and ignored.
  void warm(uint64_t addr);
  const char* unit_kind() const override { return "ObjectCaches"; }
  nlohmann::json parameters() const override;
  const ObjectCacheCounters& counters(ObjectCachesConfig::Kind k) const { return caches_[k].counters; }
  uint64_t reads() const { return reads_; }
  uint64_t bytes() const { return bytes_; }
  uint64_t uncached_reads() const { return uncached_reads_; }
  uint64_t dram_reads() const { return dram_reads_; }
  uint64_t dram_bytes() const { return dram_bytes_; }

 private:
  struct Cache {
    ObjectCacheConfig config;
    std::list<uint64_t> order;  ///< resident addresses, most recently used first
    std::unordered_map<uint64_t, std::list<uint64_t>::iterator> entries;  ///< resident objects
    TimedQueue<uint64_t> fills;  ///< objects read, by arrival cycle (then issue order)
    std::unordered_map<uint64_t, uint32_t> in_flight;  ///< reads in flight per object
    std::unique_ptr<UnitPipelines> port;
    UnitCounters port_counters;
    ObjectCacheCounters counters;
  };

  /// The cycle the object's DRAM read arrives (after the core takes the response).
  uint64_t dram_read(uint32_t bytes, uint64_t at, uint64_t now);
  /// Every fill of `c` arriving at or before `at` enters the cache, in arrival order.
  static void apply_fills(Cache& c, uint64_t at);
  Cache* cache_of(uint64_t addr);

  ObjectCachesConfig config_;
  uint32_t dram_latency_;
  double dram_latency_per_byte_;
  const Bvh& bvh_;
  BvhAddressMap map_;
  Cache caches_[ObjectCachesConfig::kKinds];
  std::unique_ptr<UnitPipelines> responses_;  ///< null: any number a cycle
  UnitCounters response_counters_;
  uint64_t reads_ = 0, bytes_ = 0, uncached_reads_ = 0, dram_reads_ = 0, dram_bytes_ = 0;
};

}  // namespace vbsim::hw
