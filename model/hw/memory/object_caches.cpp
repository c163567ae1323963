#include "hw/memory/object_caches.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vbsim::hw {

ObjectCaches::ObjectCaches(sc_core::sc_module_name name, const HwConfig& config, const Bvh& bvh)
    : sc_core::sc_module(name), target("target"), config_(config.memory.objects),
      dram_latency_(config.memory.dram_latency), dram_latency_per_byte_(config.memory.dram_latency_per_byte),
      bvh_(bvh), map_(bvh, config.address_base) {
  target.bind(*this);
  const std::string me = sc_core::sc_module::name();
  for (int k = 0; k < ObjectCachesConfig::kKinds; ++k) {
    Cache& c = caches_[k];
    c.config = config_.cache[k];
    c.port = std::make_unique<UnitPipelines>(UnitConfig{1, 1, config_.port_cycles}, c.port_counters,
                                             me + "." + object_cache_name(static_cast<ObjectCachesConfig::Kind>(k)));
    const std::string kind = object_cache_name(static_cast<ObjectCachesConfig::Kind>(k));
    declare_stat(kind + "_lookups", "objects", "lookups of the " + kind + " cache", c.counters.lookups);
    declare_stat(kind + "_hits", "objects", "lookups that found their object arrived", c.counters.hits);
    declare_stat(kind + "_misses", "objects", "lookups that read their object from DRAM", c.counters.misses);
    declare_stat(kind + "_misses_in_flight", "objects",
                 "misses of an object whose earlier read had not arrived (never merged)", c.counters.misses_in_flight);
  }
  if (config_.responses_per_cycle > 0)
    responses_ = std::make_unique<UnitPipelines>(UnitConfig{config_.responses_per_cycle, 1, 1}, response_counters_,
                                                 me + ".responses");
  declare_stat("reads", "reads", "reads of the core", reads_);
  declare_stat("uncached_reads", "reads", "reads outside the node and triangle regions (stack spills)", uncached_reads_);
  declare_stat("dram_reads", "reads", "objects read from DRAM", dram_reads_);
  declare_stat("dram_bytes", "bytes", "bytes read from DRAM", dram_bytes_);
}

nlohmann::json ObjectCaches::parameters() const {
  nlohmann::json j = {{"hit_latency", config_.hit_latency},
                      {"port_cycles", config_.port_cycles},
                      {"responses_per_cycle", config_.responses_per_cycle},
                      {"dram_latency", dram_latency_},
                      {"dram_latency_per_byte", dram_latency_per_byte_}};
  for (int k = 0; k < ObjectCachesConfig::kKinds; ++k)
    j[object_cache_name(static_cast<ObjectCachesConfig::Kind>(k))] = {{"entries", caches_[k].config.entries},
                                                                        {"bytes", caches_[k].config.bytes}};
  return j;
}

ObjectCaches::Cache* ObjectCaches::cache_of(uint64_t addr) {
  if (addr >= map_.node_base && addr < map_.tri_base) {
    const uint64_t node = (addr - map_.node_base) / map_.node_bytes;
    const bool low = node < bvh_.low_precision_node.size() && bvh_.low_precision_node[node] != 0;
    return &caches_[low ? ObjectCachesConfig::NodeLow : ObjectCachesConfig::Node];
  }
  if (addr >= map_.tri_base && addr < map_.spill_base) return &caches_[ObjectCachesConfig::Triangle];
  return nullptr;
}

void ObjectCaches::warm(uint64_t addr) {
  Cache* c = cache_of(addr);
  if (!c || c->config.entries == 0) return;
  const auto it = c->entries.find(addr);
  if (it != c->entries.end()) {
    c->order.splice(c->order.begin(), c->order, it->second);
    return;
  }
  if (c->entries.size() >= c->config.entries) {
    c->entries.erase(c->order.back());
    c->order.pop_back();
  }
  c->order.push_front(addr);
  c->entries.emplace(addr, c->order.begin());
}

uint64_t ObjectCaches::dram_read(uint32_t bytes, uint64_t at, uint64_t now) {
  ++dram_reads_;
  dram_bytes_ += bytes;
  const uint64_t arrival =
      at + dram_latency_ + static_cast<uint64_t>(std::ceil(static_cast<double>(bytes) * dram_latency_per_byte_));
  return responses_ ? responses_->issue(arrival, now) : arrival;
}

void ObjectCaches::apply_fills(Cache& c, uint64_t at) {
  uint64_t arrival, addr;
  while (c.fills.pop_due(at, arrival, addr)) {
    const auto flying = c.in_flight.find(addr);
    if (--flying->second == 0) c.in_flight.erase(flying);
    const auto it = c.entries.find(addr);
    if (it != c.entries.end()) {  // arrived again: to the front
      c.order.splice(c.order.begin(), c.order, it->second);
      continue;
    }
    if (c.entries.size() == c.config.entries) {  // evict the least recently used
      c.entries.erase(c.order.back());
      c.order.pop_back();
    }
    c.order.push_front(addr);
    c.entries.emplace(addr, c.order.begin());
  }
}

uint64_t ObjectCaches::read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t) {
  ++reads_;
  bytes_ += bytes;
  Cache* c = cache_of(addr);
  if (!c) {
    ++uncached_reads_;
    return dram_read(bytes, now, now) + config_.hit_latency;
  }
  const uint64_t at = c->port->issue(now, now);  // the lookup
  ++c->counters.lookups;
  apply_fills(*c, at);
  const auto it = c->entries.find(addr);
  if (it != c->entries.end()) {
    ++c->counters.hits;
    c->order.splice(c->order.begin(), c->order, it->second);
    return at + config_.hit_latency;
  }
  ++c->counters.misses;
  const uint32_t object = c->config.bytes ? c->config.bytes : bytes;
  c->counters.dram_bytes += object;
  const uint64_t arrival = dram_read(object, at, now);
  if (c->config.entries > 0) {
    uint32_t& flying = c->in_flight[addr];
    if (flying > 0) ++c->counters.misses_in_flight;  // its earlier read has not arrived: read again, never merged
    ++flying;
    c->fills.push(arrival, addr);
  }
  return arrival + config_.hit_latency;
}

}  // namespace vbsim::hw
