// Object caches (memory.objects, hw/memory/object_caches.h), as rtcore-systemc's core
// has them: routing by region and node precision, hits and misses, misses
// never merged, LRU eviction, one lookup per port interval, one DRAM response
// a cycle, uncached spill reads, every answer computed by hand.
#include <catch2/catch.hpp>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/memory/bvh_address_map.h"
#include "hw/memory/object_caches.h"

using namespace vbsim;
using namespace vbsim::hw;

namespace {

/// Four nodes (0 and 1 marked low precision) and three triangles; only the
/// address map and the marks matter to the caches.
Bvh four_nodes() {
  Bvh b;
  b.nodes.resize(4);
  b.tris.resize(3);
  b.low_precision_node = {1, 1, 0, 0};
  b.depth = 3;
  return b;
}

HwConfig objects_config() {
  HwConfig c;
  c.address_base = 0;
  c.memory.objects.enabled = true;
  c.memory.objects.cache[ObjectCachesConfig::NodeLow] = {1, 8};   // one object of 8 bytes
  c.memory.objects.cache[ObjectCachesConfig::Node] = {2, 0};      // two objects, the reads' own bytes
  c.memory.objects.cache[ObjectCachesConfig::Triangle] = {0, 36}; // none: every read goes to DRAM
  c.memory.objects.hit_latency = 2;
  c.memory.objects.port_cycles = 1;
  c.memory.objects.responses_per_cycle = 1;
  c.memory.dram_latency = 10;
  c.memory.dram_latency_per_byte = 1.0;
  return c;
}

}  // namespace

TEST_CASE("object caches answer every read as worked by hand", "[memory][objects]") {
  const Bvh bvh = four_nodes();
  const HwConfig cfg = objects_config();
  ObjectCaches oc("object_caches_hand", cfg, bvh);
  const BvhAddressMap map(bvh, 0);
  using K = ObjectCachesConfig;
  // Node 0 (low): a miss, DRAM 10 + 8 bytes x 1 = 18, data 2 later.
  CHECK(oc.read(map.node(0), 64, 0, 0) == 0 + 18 + 2);
  // Again at 5, its read in flight: a miss of its own (never merged), 5 + 18 + 2.
  CHECK(oc.read(map.node(0), 64, 5, 0) == 5 + 18 + 2);
  CHECK(oc.counters(K::NodeLow).misses_in_flight == 1);
  // At 30 it has arrived (18): a hit.
  CHECK(oc.read(map.node(0), 64, 30, 0) == 32);
  // Node 2 (full precision): the node cache, the read's 64 bytes: 30 + 10 + 64 + 2.
  CHECK(oc.read(map.node(2), 64, 30, 0) == 106);
  // Node 1 (low) evicts node 0 from the one-entry cache; node 0 then misses again.
  CHECK(oc.read(map.node(1), 64, 40, 0) == 40 + 18 + 2);
  CHECK(oc.read(map.node(0), 64, 100, 0) == 100 + 18 + 2);
  CHECK(oc.counters(K::NodeLow).lookups == 5);
  CHECK(oc.counters(K::NodeLow).hits == 1);
  CHECK(oc.counters(K::NodeLow).misses == 4);
  // A triangle: no entries, always DRAM with 36 bytes: 110 + 10 + 36 + 2, and again.
  CHECK(oc.read(map.triangle(1), 40, 110, 0) == 158);
  CHECK(oc.read(map.triangle(1), 40, 200, 0) == 248);
  CHECK(oc.counters(K::Triangle).misses == 2);
  CHECK(oc.counters(K::Triangle).dram_bytes == 72);
  // Two misses arriving at the same cycle: the core takes one response a cycle.
  CHECK(oc.read(map.node(3), 64, 300, 0) == 300 + 74 + 2);
  CHECK(oc.read(map.triangle(2), 40, 328, 0) == 328 + 46 + 1 + 2);  // would arrive at 374 too: 375
  // A spill read: uncached, DRAM with its own bytes.
  CHECK(oc.read(map.stack_entry(0, 0), 16, 400, 0) == 400 + 26 + 2);
  CHECK(oc.uncached_reads() == 1);
  CHECK(oc.dram_reads() == 10);  // every read but the hit
}

TEST_CASE("an object cache takes one lookup per port interval", "[memory][objects]") {
  const Bvh bvh = four_nodes();
  HwConfig cfg = objects_config();
  cfg.memory.objects.port_cycles = 3;
  ObjectCaches oc("object_caches_port", cfg, bvh);
  const BvhAddressMap map(bvh, 0);
  CHECK(oc.read(map.node(2), 64, 0, 0) == 0 + 74 + 2);
  CHECK(oc.read(map.node(3), 64, 0, 1) == 3 + 74 + 2);  // looked up at 3
  CHECK(oc.read(map.node(1), 64, 0, 2) == 0 + 18 + 2);       // another cache: its own port
}

TEST_CASE("an object cache takes an entry when its data arrive, as rtcore's does", "[memory][objects]") {
  const Bvh bvh = four_nodes();
  const HwConfig cfg = objects_config();  // the low-precision node cache holds one object
  ObjectCaches oc("object_caches_fill", cfg, bvh);
  const BvhAddressMap map(bvh, 0);
  using K = ObjectCachesConfig;
  CHECK(oc.read(map.node(0), 64, 0, 0) == 20);       // a miss: arrives at 18
  CHECK(oc.read(map.node(0), 64, 30, 0) == 32);      // a hit
  CHECK(oc.read(map.node(1), 64, 40, 0) == 40 + 20); // a miss: node 1 arrives at 58
  // At 50 node 1 is on its way and holds no entry: node 0 is still there (allocating
  // at the miss would have evicted it at 40).
  CHECK(oc.read(map.node(0), 64, 50, 0) == 52);
  // Node 1 arrived at 58 and took the one entry: node 0 misses at 60.
  CHECK(oc.read(map.node(0), 64, 60, 0) == 60 + 20);
  CHECK(oc.read(map.node(1), 64, 70, 0) == 72);      // node 1 is there until node 0 arrives at 78
  CHECK(oc.read(map.node(1), 64, 78, 0) == 78 + 20); // node 0 arrived at 78, before this lookup
  CHECK(oc.counters(K::NodeLow).hits == 3);
  CHECK(oc.counters(K::NodeLow).misses == 4);
  CHECK(oc.counters(K::NodeLow).misses_in_flight == 0);
}

TEST_CASE("two reads of one object in flight fill one entry", "[memory][objects]") {
  const Bvh bvh = four_nodes();
  HwConfig cfg = objects_config();
  cfg.memory.objects.cache[ObjectCachesConfig::Node] = {2, 0};  // two objects, the reads' own bytes (64: 74 cycles)
  ObjectCaches oc("object_caches_twice", cfg, bvh);
  const BvhAddressMap map(bvh, 0);
  using K = ObjectCachesConfig;
  CHECK(oc.read(map.node(2), 64, 0, 0) == 76);   // arrives at 74
  CHECK(oc.read(map.node(2), 64, 10, 0) == 86);  // in flight: read again, arrives at 84
  CHECK(oc.read(map.node(3), 64, 80, 0) == 156); // arrives at 154
  // Node 2's second arrival (84) moves it to the front instead of taking the second entry;
  // node 3 arrives at 154 into the free entry, so both are there at 160.
  CHECK(oc.read(map.node(2), 64, 160, 0) == 162);
  CHECK(oc.read(map.node(3), 64, 161, 0) == 163);
  CHECK(oc.counters(K::Node).misses_in_flight == 1);
  CHECK(oc.counters(K::Node).hits == 2);
}
