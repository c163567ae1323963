#include "hw/accelerator.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "datapath/closest_hit.h"
#include "hw/hw_stats.h"

namespace vbsim::hw {

namespace {

/// The L2's answer path of a core whose L1 was replaced: never called (such a
/// core's memory does not reach the L2).
class NoLineFill final : public LineFillIf {
 public:
  void line_filled(uint64_t, uint64_t) override {
    throw std::logic_error("L2: an answer for a core whose L1 was replaced");
  }
};

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

/// The counters of a core's unit: the built-in module's, or what the scheduler counted of its replacement.
void add_unit(UnitCounters& sum, const PipelineUnit* builtin, const UnitCounters& replaced) {
  if (builtin) return add(sum, builtin->counters());
  add(sum, replaced);
  sum.replaced = true;
}

}  // namespace

AcceleratorChecks::AcceleratorChecks(const HwConfig& config, const Bvh& bvh) {
  if (config.cores == 0 || config.slots_per_core == 0)
    throw std::invalid_argument("cores: the accelerator needs at least one core with one slot");
  check_memory_config(config.memory, static_cast<int>(config.cores));
  check_traversal_depth(bvh);
}

void check_builtin_lookahead(const MemoryConfig& m) {
  if (m.hierarchy() && m.tlm == TlmStyle::ApproximatelyTimed && m.at_lookahead_cycles > m.dram_latency)
    throw std::invalid_argument(fmt::format(
        "memory.at_lookahead_cycles: {} is more than memory.dram_latency ({}): the built-in DRAM answers {} cycles "
        "after a request at the soonest, so the scheduler may not run further ahead",
        m.at_lookahead_cycles, m.dram_latency, m.dram_latency));
}

Accelerator::Accelerator(sc_core::sc_module_name name, const HwConfig& config, const Scene& scene, const Bvh& bvh,
                         const ReplayOptions& options, const AcceleratorUnits& units)
    : AcceleratorChecks(config, bvh), sc_core::sc_module(name), config_(for_tester(config, options.tester)), bvh_(bvh), replayer_(scene, bvh, options),
      clock_(config.clock_mhz),
      at_(config.memory.hierarchy() && !units.l2_cache && config.memory.tlm == TlmStyle::ApproximatelyTimed),
      avoidance_in_use_(options.method.validity_bit && options.method.avoidance.policy != AvoidancePolicy::SignOnly),
      cores_("core") {
  if (!units.external_memory) check_builtin_lookahead(config.memory);
  if (units.ray_source) {
    source_module_ = units.ray_source("ray_source", config, replayer_);
    source_if_ = &replacement_as<RaySourceIf>(*source_module_, "RaySourceIf");
  } else {
    source_ = std::make_unique<RaySource>("ray_source", config, replayer_);
    source_if_ = source_.get();
  }
  if (units.dispatcher) {
    dispatcher_module_ = units.dispatcher("dispatcher", config);
    dispatcher_ = &replacement_as<DispatchIf>(*dispatcher_module_, "DispatchIf");
  } else {
    auto d = std::make_unique<Dispatcher>("dispatcher", config.dispatch);
    dispatcher_ = d.get();
    dispatcher_module_ = std::move(d);
  }
  const bool caches = config.memory.hierarchy();
  cores_.init(config.cores, [&](const char* n, size_t i) {
    return new RayTestCore(n, static_cast<uint32_t>(i), config, units, options.tester, options.method.avoidance,
                           avoidance_in_use_, caches);
  });
  if (config.memory.ideal) {
    ideal_ = std::make_unique<IdealMemory>("memory", config.memory.ideal_latency);
    for (RayTestCore& c : cores_)
      if (!units.l1_cache) c.memory.bind(ideal_->target);
  } else if (config.memory.objects.enabled) {
    if (units.l2_cache || units.external_memory)
      throw std::invalid_argument("memory.objects: object caches take no replaced L2 or external memory (they read DRAM themselves)");
    for (RayTestCore& c : cores_) {
      object_caches_.push_back(std::make_unique<ObjectCaches>(
          (std::string("object_caches_") + std::to_string(object_caches_.size())).c_str(), config, bvh));
      if (!units.l1_cache) c.memory.bind(object_caches_.back()->target);
    }
  } else if (units.l2_cache) {
    if (units.external_memory)
      throw std::invalid_argument("external_memory: a replaced L2 has no memory socket (the memory behind it is its own)");
    l2_replacement_ = units.l2_cache("l2_cache", config);
    // It answers every line with its arrival cycle: nothing wakes the scheduler
    // for a line it would answer later (kPendingCycle).
    LineReadIf& l2 = replacement_as<LineReadIf>(*l2_replacement_, "LineReadIf");
    for (RayTestCore& c : cores_) {
      if (L1Cache* l1 = c.l1()) l1->next.bind(l2);
      else if (L2ClientIf* client = c.l2_client()) client->next_level().bind(l2);
    }
  } else {
    l2_ = std::make_unique<L2Cache>("l2_cache", config.memory.l2, clock_, config.memory.tlm,
                                    config.memory.at_lookahead_cycles);
    no_fill_ = std::make_unique<NoLineFill>();
    for (RayTestCore& c : cores_) {
      if (L1Cache* l1 = c.l1()) {
        l1->next.bind(l2_->target);
        l2_->fill_out.bind(l1->fill_target);
        l1->connect_fast(l2_.get());
      } else if (L2ClientIf* client = c.l2_client()) {  // a replacement L1 that reaches the L2
        client->next_level().bind(l2_->target);
        l2_->fill_out.bind(client->fill_target());
      } else {
        l2_->fill_out.bind(*no_fill_);
      }
    }
    memory_socket_ = std::make_unique<tlm::tlm_initiator_socket<>>("memory_socket");
    l2_->socket.bind(*memory_socket_);
    if (!units.external_memory) {
      dram_ = std::make_unique<Dram>("dram", config.memory, clock_);
      memory_socket_->bind(dram_->socket);
    }
    l2_->set_response_callback([this] { kick_.notify(sc_core::SC_ZERO_TIME); });
    l2_->set_request_callback([this](uint64_t send) {
      limit_ = std::min(limit_, send + l2_->lookahead_cycles());  // a response may fall at send + lookahead
    });
  }
  if (units.result_sink) {
    sink_replacement_ = units.result_sink("result_sink", config);
    sink_ = std::make_unique<ResultSink>("result_accounting", config, replayer_);
    sink_->forward.bind(replacement_as<ResultSinkIf>(*sink_replacement_, "ResultSinkIf"));
  } else {
    sink_ = std::make_unique<ResultSink>("result_sink", config, replayer_);
  }
  for (RayTestCore& c : cores_)
    c.set_resume([this](uint32_t slot, uint64_t ready) { engine_->resume(slot, ready); });

  SC_METHOD(activate);
  sensitive << kick_;
  dont_initialize();
}

Accelerator::~Accelerator() = default;

tlm::tlm_initiator_socket<>& Accelerator::memory_socket() {
  if (!memory_socket_)
    throw std::logic_error(std::string(name()) +
                           (l2_replacement_ ? ": a replaced L2 has no memory socket" : ": an ideal memory has no memory socket"));
  return *memory_socket_;
}

void Accelerator::set_shader(RayShader& shader) {
  if (sink_replacement_)
    throw std::logic_error("a closed-loop shader needs the built-in result sink: the replacement receives the rays");
  source_if_->set_shader_feed([&shader](TraceRay& tr, uint64_t cycle) { return shader.next_ray(tr, cycle); });
  sink_->set_shader(&shader);
}

void Accelerator::set_tracing(VcdRecorder* vcd, TimelineRecorder* timeline) {
  vcd_ = vcd;
  timeline_ = timeline;
  for (RayTestCore& c : cores_)
    if (L1Cache* l1 = c.l1()) l1->set_tracing(vcd);
  if (l2_) l2_->set_tracing(timeline, vcd);
  if (dram_) dram_->set_tracing(vcd);
}

EngineParts Accelerator::engine_parts() {
  EngineParts p{config_, replayer_, bvh_, *source_if_, *dispatcher_, dynamic_cast<Dispatcher*>(dispatcher_), *sink_, {}, false, nullptr, false, nullptr, nullptr, {}, nullptr, {}, {}, 0, EngineParts::kNoWarmup, EngineParts::kNoWarmup};
  bool all_l1 = true, all_ideal = ideal_ != nullptr;
  for (RayTestCore& c : cores_) {
    MemoryReadIf* mem = c.memory.operator->();
    p.cores.push_back({&c, c.builtin_box(), c.box.operator->(), c.box_low_unit(), c.builtin_triangle(),
                       c.triangle.operator->(), c.builtin_avoidance(), c.avoidance.operator->(), mem});
    all_l1 &= c.l1() != nullptr && mem == static_cast<MemoryReadIf*>(c.l1());
    all_ideal &= ideal_ && mem == static_cast<MemoryReadIf*>(ideal_.get());
  }
  p.builtin_l1s = all_l1;
  p.builtin_ideal = all_ideal ? ideal_.get() : nullptr;
  p.avoidance_in_use = avoidance_in_use_;
  p.timeline = timeline_;
  p.vcd = vcd_;
  p.ray_times = ray_times_;
  if (statistics_) {
    const StatisticsOptions& o = statistics_->options();
    p.on_sample = [this](uint64_t cycle, bool interval, bool warmup) {
      statistics_->sample(statistics_sample(cycle, warmup), interval, warmup);
    };
    p.sample_interval = o.interval_path.empty() ? 0 : o.interval_cycles;
    if (o.warmup_rays) p.warmup_rays = o.warmup_rays;
    if (o.warmup_cycles) p.warmup_cycle = o.warmup_cycles;
  }
  if (l2_ && (!at_ || !memory_l1s_.empty())) {
    // Arrivals first, then the L1s' misses that leave now (their L2 lookups),
    // then the L2's requests that leave now: as the approximately timed path
    // does at each cycle it handles (apply_responses, release_due) before the
    // cycle's events.
    p.memory_clock = &memory_clock_;
    p.memory_step = [this](uint64_t at) {
      if (!at_) l2_->apply_responses(at);
      for (L1Cache* l1 : memory_l1s_) l1->send_due(at);
      if (!at_) l2_->release_lt(at);
    };
  }
  return p;
}

void Accelerator::start_of_simulation() {
  if (l2_) l2_->set_target_name(memory_target_name());
  memory_l1s_.clear();
  if (l2_) {  // the memory's work in time order (hw/memory_clock.h)
    if (!at_) l2_->set_memory_clock(&memory_clock_);
    if (config_.memory.l2_lookups_in_time_order)
      for (RayTestCore& c : cores_)
        if (L1Cache* l1 = c.l1()) {
          l1->set_memory_clock(&memory_clock_);
          memory_l1s_.push_back(l1);
        }
  }
  engine_ = make_cycle_engine(engine_parts());
  clock_.start_now();
  activations_ = 0;
  last_progress_ = std::chrono::steady_clock::now();
  kick_.notify(sc_core::SC_ZERO_TIME);
}

void Accelerator::activate() {
  try {
    if (activations_ == 0) engine_->start();  // the source's first emission at cycle 0
    const uint64_t now = clock_.now();
    const bool at_wait = at_busy();
    // Approximately timed, requests outstanding: a cycle is handled only once
    // every other process of this time step has run (their responses are in).
    if (at_wait && sc_core::sc_pending_activity_at_current_time()) {
      next_trigger(sc_core::SC_ZERO_TIME);
      return;
    }
    ++activations_;
    if (stop_ && stop_->load(std::memory_order_relaxed)) engine_->stop();
    limit_ = now + config_.quantum_cycles;
    if (at_ && !l2_->broken_promise().empty()) throw std::runtime_error(l2_->broken_promise());
    if (at_wait) {
      l2_->apply_responses(now);
      l2_->release_due(now);
      const uint64_t last = l2_->run_ahead_limit(now);
      if (last != kPendingCycle) limit_ = std::min(limit_, last + 1);
    }
    engine_->advance(limit_);
    if (l2_) l2_->handled_up_to(engine_->last_handled());
    if (progress_ && (activations_ & 255) == 0) {
      const auto t = std::chrono::steady_clock::now();
      if (t - last_progress_ > std::chrono::milliseconds(250)) {
        last_progress_ = t;
        progress_(*engine_);
      }
    }
    if (completion_due() && sink_->counters().last_cycle <= now) complete_run();
    if (!schedule_next(now) && !completed_ && stop_at_completion_) sc_core::sc_stop();  // ended early
  } catch (...) {
    error_ = std::current_exception();
    if (engine_) engine_->stop();
    if (stop_at_completion_) sc_core::sc_stop();
  }
}

void Accelerator::complete_run() {
  // schedule_next lands SystemC time on the last ray's cycle; a later one would misplace the event.
  if (clock_.now() != sink_->counters().last_cycle)
    throw std::logic_error(fmt::format("{}: completion at cycle {}, after the last ray's finish at cycle {}", name(),
                                       clock_.now(), sink_->counters().last_cycle));
  completed_ = true;
  if (completion_callback_) completion_callback_(sink_->counters().last_cycle);
  completion_.notify();  // immediate: waiters run in this evaluation phase, before sc_stop() takes effect
  if (stop_at_completion_) sc_core::sc_stop();
}

bool Accelerator::schedule_next(uint64_t now) {
  const bool at_wait = at_busy();
  if (engine_->stopped()) return false;
  if (!at_wait) {
    if (!engine_->finished()) {
      const uint64_t next = std::max(now + config_.quantum_cycles, engine_->next_event_cycle());
      next_trigger(clock_.period() * static_cast<double>(next - now));
    } else if (sink_->counters().last_cycle > now) {
      next_trigger(clock_.period() * static_cast<double>(sink_->counters().last_cycle - now));  // land on the last cycle
    } else if (at_ && engine_->waiting_for_memory() != 0) {
      next_trigger(kick_);  // a response will come
    } else {
      return false;
    }
    return true;
  }
  uint64_t next = std::min(l2_->next_send_cycle(), l2_->next_response_cycle());
  if (!engine_->finished()) next = std::min(next, engine_->next_event_cycle());
  if (next == kPendingCycle) {
    next_trigger(kick_);  // only the target's responses are left to wait for
    return true;
  }
  next = std::max(next, now + 1);
  next_trigger(clock_.period() * static_cast<double>(next - now), kick_);
  return true;
}

std::string Accelerator::memory_target_name() const {
  if (dram_) return dram_->name();
  const auto* target = dynamic_cast<const sc_core::sc_object*>(memory_socket_->get_interface());
  return target ? std::string(target->name())
                : fmt::format("the memory target bound to {}", memory_socket_->name());
}

void Accelerator::check() const {
  if (error_) std::rethrow_exception(error_);
  if (l2_ && !l2_->broken_promise().empty()) throw std::runtime_error(l2_->broken_promise());
  if (!engine_) throw std::runtime_error(std::string(name()) + ": the simulation did not start");
  if (engine_->stopped()) return;
  const uint64_t fed = engine_->rays_fed(), done = sink_->counters().rays;
  if (!engine_->complete() || fed != done) {
    std::string what = fmt::format(
        "{}: the run stopped making progress at cycle {}: {} of {} rays read finished, {} in slots, {} waiting for "
        "memory\n",
        name(), clock_.now(), done, fed, engine_->rays_in_flight(), engine_->waiting_for_memory());
    if (l2_) what += "  memory: " + l2_->outstanding_report() + "\n";
    what += engine_->slot_report(16);
    throw std::runtime_error(what);
  }
}

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
    add_unit(c.box, core.builtin_box(), k.replaced_units[CoreCounters::kBox]);
    if (const BoxUnit* low = core.box_low_unit()) add(c.box_low, low->counters());
    add_unit(c.triangle, core.builtin_triangle(), k.replaced_units[CoreCounters::kTriangle]);
    add_unit(c.avoidance, core.builtin_avoidance(), k.replaced_units[CoreCounters::kAvoidance]);
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
    const PipelineUnit* builtin[3] = {core.builtin_box(), core.builtin_triangle(), core.builtin_avoidance()};
    for (int u = 0; u < 3; ++u) {
      UnitCounters c;
      add_unit(c, builtin[u], k.replaced_units[u]);
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
  return j;
}

nlohmann::json Accelerator::emission_json() const {
  if (!source_) return {{"replaced", true}};
  const EmissionCounters& e = source_->emission();
  const SourceCounters& s = source_->counters();
  const SourceConfig& sc = config_.source;
  const uint64_t cycles = sink_->counters().last_cycle;
  const double lane_cycles = static_cast<double>(cycles) * sc.rays_per_cycle;
  const auto share = [&](uint64_t v) { return lane_cycles > 0 ? static_cast<double>(v) / lane_cycles : 0.0; };
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
          {"bundled_rays", e.bundled_rays}};
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
