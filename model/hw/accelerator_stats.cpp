// Accelerator: the chip's statistics, summed from its modules: the counters,
// the samples of warm-up and intervals, the memory section, the `hw` JSON
// section and its human table.
#include "hw/accelerator.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "hw/observe/hw_energy.h"
#include "hw/observe/hw_stats.h"

namespace vbsim::hw {

namespace {

double ratio(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

nlohmann::json level_json(const LevelCounters& c) {
  return {{"accesses", c.accesses},
          {"hits", c.hits},
          {"misses", c.misses},
          {"merges", c.merges},
          {"hit_rate", ratio(c.hits, c.accesses)},
          {"mshr_stall_cycles", c.mshr_stall_cycles}};
}

void add(UnitCounters& sum, const UnitCounters& c) {
  sum.ops += c.ops;
  sum.wait_cycles += c.wait_cycles;
  sum.busy_cycles += c.busy_cycles;
}

/// The counters of core `core`'s unit of configuration `u`: the built-in
/// module's (a unit its group shares counted once, at the group's first core),
/// or what the scheduler counted of its replacement.
void add_unit(UnitCounters& sum, const PipelineUnit* builtin, const UnitConfig& u, uint32_t core,
              const UnitCounters& replaced) {
  if (builtin) {
    if (core % u.share == 0) add(sum, builtin->counters());
    return;
  }
  add(sum, replaced);
  sum.replaced = true;
}

}  // namespace

HwCounters Accelerator::chip_counters() const {
  HwCounters c;
  const SinkCounters& s = sink_->counters();
  c.cycles = s.last_cycle;
  c.rays = s.rays;
  c.latency_histogram = s.latency_histogram;
  c.latency_min = s.latency_min;
  c.latency_max = s.latency_max;
  for (const RayTestCore& core : cores_) {
    const CoreCounters& k = core.counters;
    const uint32_t i = core.index();
    add_unit(c.box, core.builtin_box(), config_.box, i, k.replaced_units[CoreCounters::kBox]);
    if (const BoxUnit* low = core.box_low_unit(); low && i % config_.box_low.share == 0) add(c.box_low, low->counters());
    add_unit(c.triangle, core.builtin_triangle(), config_.triangle, i, k.replaced_units[CoreCounters::kTriangle]);
    add_unit(c.avoidance, core.builtin_avoidance(), config_.avoidance, i, k.replaced_units[CoreCounters::kAvoidance]);
    add(c.controller, k.controller);
    for (int i = 0; i < kRayKindCount; ++i) c.avoidance_ops_by_kind[i] += k.avoidance_ops_by_kind[i];
    c.node_fetches += k.node_fetches;
    c.leaf_fetches += k.leaf_fetches;
    c.refill_reads += k.refill_reads;
    c.memory_wait_cycles += k.memory_wait_cycles;
    c.refill_wait_cycles += k.refill_wait_cycles;
    c.spills += k.spills;
    c.slot_cycles += k.slot_cycles;
  }
  c.source_replaced = !source_;
  if (!source_) return c;  // a replacement source: its counts are its own
  const SourceCounters& src = source_->counters();
  c.no_free_slot_cycles = src.no_free_slot_cycles;
  c.source_busy_cycles = src.busy_cycles;
  c.sign_bits_computed = src.sign_bits_computed;
  c.emission_ops = src.emission_ops;
  c.emission_unit_ops = src.emission_unit_ops;
  return c;
}

StatsSample Accelerator::statistics_sample(uint64_t cycle, bool latencies) const {
  StatsSample s;
  s.cycle = cycle;
  const SinkCounters& sink = sink_->counters();
  s.rays = sink.rays;
  s.latency_sum = sink.latency_sum;
  if (latencies) s.latency_by_kind = sink.latency_by_kind;
  for (const RayTestCore& core : cores_) {
    const CoreCounters& k = core.counters;
    const uint32_t i = core.index();
    const PipelineUnit* builtin[3] = {core.builtin_box(), core.builtin_triangle(), core.builtin_avoidance()};
    const UnitConfig* configs[3] = {&config_.box, &config_.triangle, &config_.avoidance};
    for (int u = 0; u < 3; ++u) {
      UnitCounters c;
      add_unit(c, builtin[u], *configs[u], i, k.replaced_units[u]);
      s.unit_ops[u] += c.ops;
      s.unit_replaced[u] = s.unit_replaced[u] || c.replaced;
    }
    s.node_fetches += k.node_fetches;
    s.leaf_fetches += k.leaf_fetches;
    if (const L1Cache* l1 = core.l1()) {
      const LevelCounters c = l1->counters();
      s.l1.hits += c.hits;
      s.l1.misses += c.misses;
      s.l1.merges += c.merges;
      s.l1.mshr_stall_cycles += c.mshr_stall_cycles;
      s.l1_miss_service_cycles += l1->miss_service_cycles();
      s.l1_misses_filled += l1->misses_filled();
    }
  }
  if (l2_) {
    s.caches = true;
    s.l2 = l2_->counters();
    s.l2_misses_filled = l2_->dram_reads_filled();
    s.l2_miss_service_cycles = l2_->dram_read_cycles() + s.l2_misses_filled * config_.memory.l2.hit_latency;
    s.dram_reads = l2_->dram_requests();
    s.dram_bytes = dram_ ? dram_->channel().counters().bytes : s.dram_reads * config_.memory.l2.line_bytes;
  }
  return s;
}

nlohmann::json Accelerator::object_caches_stats() const {
  // Every core's object caches summed; "l1" their lookups together (one per read
  // but the uncached), as the hierarchy's L1 reports, so that tools reading it work.
  LevelCounters all;
  nlohmann::json by_kind = nlohmann::json::object();
  uint64_t reads = 0, bytes = 0, uncached = 0, dram_reads = 0, dram_bytes = 0;
  for (int k = 0; k < ObjectCachesConfig::kKinds; ++k) {
    ObjectCacheCounters sum;
    for (const auto& o : object_caches_) sum.add(o->counters(static_cast<ObjectCachesConfig::Kind>(k)));
    all.accesses += sum.lookups;
    all.hits += sum.hits;
    all.misses += sum.misses;
    by_kind[object_cache_name(static_cast<ObjectCachesConfig::Kind>(k))] = {
        {"lookups", sum.lookups},       {"hits", sum.hits},
        {"misses", sum.misses},         {"misses_in_flight", sum.misses_in_flight},
        {"dram_bytes", sum.dram_bytes}, {"hit_rate", ratio(sum.hits, sum.lookups)}};
  }
  for (const auto& o : object_caches_) {
    reads += o->reads();
    bytes += o->bytes();
    uncached += o->uncached_reads();
    dram_reads += o->dram_reads();
    dram_bytes += o->dram_bytes();
  }
  return {{"model", "objects"},
          {"reads", reads},
          {"bytes", bytes},
          {"uncached_reads", uncached},
          {"objects", std::move(by_kind)},
          {"l1", level_json(all)},
          {"dram", {{"reads", dram_reads}, {"bytes", dram_bytes}}}};
}

nlohmann::json Accelerator::memory_stats() const {
  if (ideal_) {
    return {{"model", "ideal"}, {"latency", ideal_->latency()}, {"reads", ideal_->reads()}, {"bytes", ideal_->bytes()}};
  }
  if (!object_caches_.empty()) return object_caches_stats();
  LevelCounters l1_sum;
  nlohmann::json per_core = nlohmann::json::array();
  uint64_t reads = 0, bytes = 0, first_now = 0, last_ready = 0;
  bool any = false;
  for (const RayTestCore& core : cores_) {
    const L1Cache* l1 = core.l1();
    if (!l1) continue;
    const LevelCounters c = l1->counters();
    l1_sum.accesses += c.accesses;
    l1_sum.hits += c.hits;
    l1_sum.misses += c.misses;
    l1_sum.merges += c.merges;
    l1_sum.mshr_stall_cycles += c.mshr_stall_cycles;
    per_core.push_back(level_json(c));
    if (l1->reads()) {
      first_now = any ? std::min(first_now, l1->first_read_cycle()) : l1->first_read_cycle();
      last_ready = std::max(last_ready, l1->last_ready_cycle());
      any = true;
    }
    reads += l1->reads();
    bytes += l1->bytes();
  }
  nlohmann::json l1 = level_json(l1_sum);
  l1["per_core"] = std::move(per_core);
  const uint64_t span = reads ? last_ready - first_now : 0;
  nlohmann::json dram;
  if (dram_) {
    const DramCounters& d = dram_->channel().counters();
    const double bytes_per_cycle = span ? static_cast<double>(d.bytes) / static_cast<double>(span) : 0.0;
    dram = {{"reads", d.reads},
            {"bytes", d.bytes},
            {"busy_cycles", dram_->channel().busy_cycles()},
            {"bytes_per_cycle", bytes_per_cycle},
            {"bandwidth_use", bytes_per_cycle / config_.memory.dram_bytes_per_cycle}};
  } else if (l2_) {
    dram = {{"target", "external"}, {"reads", l2_->dram_requests()}};
  } else {
    dram = {{"target", "behind the replaced L2"}, {"reads", 0}};  // the replacement's own business
  }
  // A replaced L2 counts nothing here (its statistics are its own).
  nlohmann::json l2 = level_json(l2_ ? l2_->counters() : LevelCounters{});
  if (!l2_) l2["replaced"] = true;
  const DramCounters none;
  const DramCounters& d = dram_ ? dram_->channel().counters() : none;
  return {
      {"model", "hierarchy"},
      {"reads", reads},
      {"bytes", bytes},
      {"line_requests", l1_sum.accesses},  // every line a read spans is one L1 access
      {"span_cycles", span},
      {"l1", std::move(l1)},
      {"l2", std::move(l2)},
      {"dram", std::move(dram)},
      {"stall_cycles",
       {{"l1_mshr_full", l1_sum.mshr_stall_cycles},
        {"l2_mshr_full", l2_ ? l2_->counters().mshr_stall_cycles : 0},
        {"dram_outstanding_full", d.outstanding_stall_cycles},
        {"dram_bandwidth", d.bandwidth_stall_cycles}}},
  };
}

SystemCRun Accelerator::systemc_run() const {
  SystemCRun r;
  r.start_ps = clock_.origin().to_seconds() * 1e12;
  r.end_ps = sc_core::sc_time_stamp().to_seconds() * 1e12;
  r.cycles = clock_.now();
  r.activations = activations_;
  r.period_ps = clock_.period().to_seconds() * 1e12;
  return r;
}

nlohmann::json Accelerator::hw_json() {
  const HwCounters c = chip_counters();
  const nlohmann::json mem = memory_stats();
  const SystemCRun sc = systemc_run();
  nlohmann::json j = hw_stats_json({c, config_, replayer_.stats(), mem, sc});
  j["emission"] = emission_json();
  j["instances"] = gather_instance_stats(*this);
  // Exact latency percentiles and the miss latency per cache level, over the whole run.
  const StatsSample end = statistics_sample(c.cycles + 1, true);
  j["latency_distribution"] = latency_distribution_json(end.latency_by_kind);
  j["miss_latency"] = RunStatistics::miss_latency_json(StatsSample{}, end);
  if (statistics_ && statistics_->options().warmup()) {
    j["warmup"] = statistics_->warmup_json();
    j["measured"] = statistics_->measured_json();
  }
  // Energy and area, from the counters the run kept (nothing per cycle).
  const TechFile& tech = technology();
  const ReplacedUnits replaced = replaced_units();
  j["energy"] = hw_energy_json(tech, config_, replayer_.options(), replayer_.stats(), c, j["memory"]["port"], replaced);
  j["area"] = hw_area_json(tech, hw_area(tech, config_, replayer_.options(), replaced), replaced);
  return j;
}

const TechFile& Accelerator::technology() {
  if (!tech_) tech_ = load_tech_file(default_tech_path());
  return *tech_;
}

ReplacedUnits Accelerator::replaced_units() const {
  ReplacedUnits out;
  const auto add = [&out](const char* unit, const sc_core::sc_module* m) {
    if (!m) return;
    ReplacedUnit r{unit, m->name(), std::nullopt};
    if (const auto* priced = dynamic_cast<const PricedUnitIf*>(m)) r.inventory = priced->inventory();
    out.push_back(std::move(r));
  };
  if (cores_.size() > 0)
    for (const char* unit : {"box_unit", "triangle_tester", "avoidance_unit", "l1_cache"})
      add(unit, cores_[0].replacement(unit));
  add("dispatcher", dispatcher_replaced_ ? dispatcher_module_.get() : nullptr);
  add("l2_cache", l2_replacement_.get());
  add("result_sink", sink_replacement_.get());
  add("ray_source", source_module_.get());
  return out;
}

nlohmann::json Accelerator::emission_json() const {
  if (!source_) return {{"replaced", true}};
  const EmissionCounters& e = source_->emission();
  const SourceCounters& s = source_->counters();
  const SourceConfig& sc = config_.source;
  const uint64_t cycles = sink_->counters().last_cycle;
  const double lane_cycles = static_cast<double>(cycles) * sc.rays_per_cycle;
  const auto share = [&](uint64_t v) { return lane_cycles > 0 ? static_cast<double>(v) / lane_cycles : 0.0; };
  nlohmann::json shader_cores = nullptr;  // none: the method's arithmetic is the emission path's
  if (const ShaderCorePool* pool = source_->shader_cores()) {
    const uint64_t capacity = pool->capacity(cycles);
    shader_cores = {{"rays", pool->rays()},
                    {"ops", pool->ops()},
                    {"lane_cycles", pool->lane_cycles()},
                    {"mean_wait_cycles", pool->rays() ? static_cast<double>(pool->wait_cycles()) /
                                                            static_cast<double>(pool->rays())
                                                      : 0.0},
                    {"utilisation", capacity ? static_cast<double>(pool->ops()) / static_cast<double>(capacity) : 0.0}};
  }
  return {{"dependencies", sc.dependencies},
          {"rays_per_cycle", sc.rays_per_cycle},
          {"window", sc.window},
          {"shading_latency_cycles", config_.shader.latency_cycles},
          {"children_waited", e.children_waited},
          {"mean_dependency_wait_cycles",
           e.children_waited ? static_cast<double>(e.dependency_wait_cycles) / static_cast<double>(e.children_waited)
                             : 0.0},
          {"missing_parents", missing_parents_name(sc.missing_parents)},
          {"parents_not_found", e.parents_not_found},
          {"first_parent_not_found", source_->first_parent_not_found()},
          {"lane_cycles",
           {{"busy", s.busy_cycles},
            {"idle_for_dependencies", e.lane_idle_dependency_cycles},
            {"idle_for_window", e.lane_idle_window_cycles},
            {"idle_for_shader", e.lane_idle_shader_cycles},
            {"holding_for_a_slot", s.no_free_slot_cycles}}},
          {"share_of_lane_cycles",
           {{"busy", share(s.busy_cycles)},
            {"idle_for_dependencies", share(e.lane_idle_dependency_cycles)},
            {"idle_for_window", share(e.lane_idle_window_cycles)},
            {"idle_for_shader", share(e.lane_idle_shader_cycles)},
            {"holding_for_a_slot", share(s.no_free_slot_cycles)}}},
          {"bundles", e.bundles},
          {"bundled_rays", e.bundled_rays},
          {"shader_cores", shader_cores}};
}

std::string Accelerator::hw_table() {
  const HwCounters c = chip_counters();
  const nlohmann::json mem = memory_stats();
  const SystemCRun sc = systemc_run();
  std::string table = hw_summary_table({c, config_, replayer_.stats(), mem, sc});
  const nlohmann::json e = emission_json();
  if (!source_) {
    table += "  emission: a replacement ray source (its figures are its own)\n";
    table += run_statistics_lines(statistics_sample(c.cycles + 1, true), statistics_);
    return table;
  }
  const auto& share = e["share_of_lane_cycles"];
  table += fmt::format(
      "  emission ({} lane{}, window {}, dependencies {}): lanes busy {:.1f}%, idle for parents {:.1f}%, idle for "
      "the window {:.1f}%,{} holding for a slot {:.1f}%; {} children waited {:.1f} cycles on average\n",
      config_.source.rays_per_cycle, config_.source.rays_per_cycle == 1 ? "" : "s", config_.source.window,
      config_.source.dependencies ? "on" : "off", 100 * share["busy"].get<double>(),
      100 * share["idle_for_dependencies"].get<double>(), 100 * share["idle_for_window"].get<double>(),
      // A closed-loop shader's waits (none in a replay, whose line stays as it was).
      e["lane_cycles"]["idle_for_shader"].get<uint64_t>()
          ? fmt::format(" idle for the shader {:.1f}%,", 100 * share["idle_for_shader"].get<double>())
          : std::string(),
      100 * share["holding_for_a_slot"].get<double>(), e["children_waited"].get<uint64_t>(),
      e["mean_dependency_wait_cycles"].get<double>());
  table += run_statistics_lines(statistics_sample(c.cycles + 1, true), statistics_);
  return table;
}

nlohmann::json Accelerator::parameters() const {
  const MemoryConfig& m = config_.memory;
  return {{"preset", config_.preset},
          {"clock_mhz", config_.clock_mhz},
          {"cores", config_.cores},
          {"slots_per_core", config_.slots_per_core},
          {"memory", m.ideal                ? "ideal"
                     : m.objects.enabled  ? "object caches"
                     : l2_replacement_    ? "hierarchy, replaced L2"
                     : dram_              ? "hierarchy, built-in DRAM"
                                          : "hierarchy, external target"},
          {"tlm", m.hierarchy() ? tlm_style_name(m.tlm) : "none"},
          {"quantum_cycles", config_.quantum_cycles},
          {"method", replayer_.options().method.name()},
          {"tester", tester_name(replayer_.options().tester)}};
}

}  // namespace vbsim::hw
