// Accelerator: building the hierarchy (its modules, their bindings) and the
// scheduler's parts. The SystemC process that keeps time is in
// accelerator_run.cpp, the statistics and reports in accelerator_stats.cpp.
#include "hw/accelerator.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "datapath/closest_hit.h"

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
    dispatcher_replaced_ = true;
    dispatcher_ = &replacement_as<DispatchIf>(*dispatcher_module_, "DispatchIf");
  } else {
    auto d = std::make_unique<Dispatcher>("dispatcher", config.dispatch);
    dispatcher_ = d.get();
    dispatcher_module_ = std::move(d);
  }
  build_shared_units(units, options);
  const bool caches = config.memory.hierarchy();
  cores_.init(config.cores, [&](const char* n, size_t i) {
    return new RayTestCore(n, static_cast<uint32_t>(i), config, units, options.tester, options.method.avoidance,
                           avoidance_in_use_, caches, core_shared_[i]);
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

void Accelerator::build_shared_units(const AcceleratorUnits& units, const ReplayOptions& options) {
  core_shared_.assign(config_.cores, SharedUnits{});
  // One instance of kind `kind` for each group of `u.share` cores, each core's
  // entry `field` pointing at its group's.
  const auto share = [&](const char* key, const char* kind, const UnitConfig& u, bool replaced, auto make,
                         auto field) {
    if (u.share <= 1 || u.count == 0) return;
    if (replaced)
      throw std::invalid_argument(
          fmt::format("hw.{}.share: a replaced {} is built per core (share must be 1)", key, kind));
    for (uint32_t g = 0; g < unit_groups(u, config_.cores); ++g) {
      auto unit = make(fmt::format("shared_{}_{}", kind, g).c_str());
      for (uint32_t c = g * u.share; c < std::min(config_.cores, (g + 1) * u.share); ++c)
        core_shared_[c].*field = unit.get();
      shared_units_.push_back(std::move(unit));
    }
  };
  share("box", "box_unit", config_.box, bool(units.box_unit),
        [&](const char* n) { return std::make_unique<BoxUnit>(n, config_.box); }, &SharedUnits::box);
  share("box_low", "box_unit_low", config_.box_low, false,
        [&](const char* n) { return std::make_unique<BoxUnit>(n, config_.box_low); }, &SharedUnits::box_low);
  share("triangle", "triangle_tester", config_.triangle, bool(units.triangle_tester),
        [&](const char* n) { return std::make_unique<TriangleTester>(n, config_.triangle, options.tester); },
        &SharedUnits::triangle);
  share("avoidance", "avoidance_unit", config_.avoidance, bool(units.avoidance_unit),
        [&](const char* n) {
          return std::make_unique<AvoidanceUnit>(n, config_.avoidance, options.method.avoidance, avoidance_in_use_);
        },
        &SharedUnits::avoidance);
}

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

}  // namespace vbsim::hw
