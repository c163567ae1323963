// Accelerator: the top module of the cycle-level model, the patent's FIG. 12
// as a SystemC module hierarchy (docs/hw-model.md):
//
//   accelerator                 Accelerator (this): the scheduler process
//     ray_source                RaySource: the ray-emission interface (sign bit, emission-time methods)
//     dispatcher                Dispatcher
//     core_0 .. core_{N-1}      RayTestCore (sc_vector): ray slots with their BvhSteppers, and
//       box_unit                  BoxUnit
//       triangle_tester           TriangleTester (three-half-plane, front/back bit)
//       avoidance_unit            AvoidanceUnit
//       l1_cache                  L1Cache
//     l2_cache                  L2Cache, whose misses leave through a TLM-2.0 initiator socket
//                               (or a replacement LineReadIf, the L2 and its memory: no socket, no dram)
//     memory_socket             (hierarchical) to
//     dram                      Dram, the built-in TLM-2.0 target (absent with external_memory)
//     memory                    IdealMemory in place of the caches (memory.ideal)
//     object_caches_<core>      ObjectCaches in place of each core's L1 and all behind it (memory.objects)
//     result_sink               ResultSink (replaced: the replacement, and ResultSink as result_accounting)
//
// Time: one SC_METHOD (activate) runs the one scheduler (CycleEngine). An
// activation at cycle c handles every event of [c, c + sim.quantum_cycles) and
// sleeps until the later of c + quantum and the next event (next_trigger, no
// clock); after the last ray one more activation lands SystemC time on the last
// cycle, so a run lasts cycles x period of SystemC time. With an approximately
// timed memory and requests outstanding it handles each cycle only when SystemC
// time has reached it and that time step has settled (no other process pending
// at it), and no further than the target's lookahead allows.
//
// Use in a user's sc_main: construct it (in any simulation context), bind
// memory_socket() when external_memory is set, give it a trace (set_feed) and a
// result callback, sc_start(), then check() and read report(). In a design
// whose other processes never stop (a free-running sc_clock), completion_event()
// says when every ray has finished and set_stop_at_completion() ends sc_start()
// there. Several runs in one process: one simulation context each
// (hw/simulation_context.h).
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>

#include <optional>

#include <nlohmann/json.hpp>
#include <systemc>
#include <tlm>

#include "energy/tech_file.h"
#include "hw/accelerator_units.h"
#include "hw/core/ray_test_core.h"
#include "hw/cycle_clock.h"
#include "hw/hw_config.h"
#include "hw/memory/dram.h"
#include "hw/memory/ideal_memory.h"
#include "hw/memory/l2_cache.h"
#include "hw/memory/object_caches.h"
#include "hw/observe/run_statistics.h"
#include "hw/observe/stat_provider.h"
#include "hw/scheduler/cycle_engine.h"
#include "hw/sink/result_sink.h"
#include "hw/source/dispatcher.h"
#include "hw/source/ray_feed.h"
#include "hw/source/ray_source.h"
#include "hw/unit_inventory.h"
#include "replay/functional_replayer.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::hw {

/// The built-in DRAM keeps an approximately timed lookahead promise: throws
/// std::invalid_argument naming memory.at_lookahead_cycles when it is above
/// memory.dram_latency.
void check_builtin_lookahead(const MemoryConfig& m);

/// The checks an Accelerator's configuration must pass, run before any part of
/// the module exists (a base class constructed first).
struct AcceleratorChecks {
  AcceleratorChecks(const HwConfig& config, const Bvh& bvh);
};

class Accelerator final : private AcceleratorChecks, public sc_core::sc_module, public StatProvider {
 public:
  /// Builds the hierarchy for `config` (checked: throws std::invalid_argument
  /// naming the field) on `scene`/`bvh` (which outlive it) with the method and
  /// tester of `options`; `units` may replace built-in units. Throws
  /// std::runtime_error when the BVH is deeper than the traversal stack.
  Accelerator(sc_core::sc_module_name name, const HwConfig& config, const Scene& scene, const Bvh& bvh,
              const ReplayOptions& options, const AcceleratorUnits& units = {});
  ~Accelerator() override;

  /// The L2's TLM-2.0 initiator socket, to bind to a memory target
  /// (external_memory); throws std::logic_error with an ideal memory.
  tlm::tlm_initiator_socket<>& memory_socket();

  // ---- before sc_start ----
  void set_feed(RayFeed feed) { source_if_->set_feed(std::move(feed)); }
  /// How errors found in a ray (a child before its parent) name its line.
  void set_locator(RayLocator locate) {
    if (source_) source_->set_locator(std::move(locate));
  }
  /// Receives every finished ray's cycles (ready, emitted, started, finished) and slot.
  void set_ray_times(RayTimesSink sink) { ray_times_ = std::move(sink); }
  void set_result_callback(RayResultSink callback) { sink_->set_callback(std::move(callback)); }
  /// A closed-loop workload in place of a trace (replay/closed_loop.h; it
  /// outlives the run): the ray source asks it for rays, the result sink hands
  /// it every answer, after the result callback. Throws std::logic_error with
  /// a replaced result sink, or a replaced ray source that takes no shader.
  void set_shader(RayShader& shader);
  /// Keep parent rays for intended origins (default true; parentless benchmark rays need not).
  void set_track_parents(bool on) { replayer_.set_track_parents(on); }
  /// Set (e.g. by SIGINT) to end the run early; the run is then partial.
  void set_stop_flag(const std::atomic<bool>* stop) { stop_ = stop; }
  /// Called about every quarter second of wall time during the run.
  void set_progress(std::function<void(const CycleEngine&)> progress) { progress_ = std::move(progress); }
  /// Records per-instance values (VCD) and busy intervals (timeline); either may be null.
  void set_tracing(VcdRecorder* vcd, TimelineRecorder* timeline);
  /// Takes warm-up and interval samples for `statistics` (null: none; it outlives the run).
  void set_statistics(RunStatistics* statistics) { statistics_ = statistics; }
  /// The chip's cumulative counters now, as the sample of cycle `cycle`; with
  /// the rays' latencies by kind when `latencies`.
  StatsSample statistics_sample(uint64_t cycle, bool latencies) const;

  // ---- completion (a design with processes of its own, e.g. a free-running sc_clock) ----
  /// Notified once, immediately, when every ray of the feed has finished, at
  /// the SystemC time of the last ray's finish: start + cycles x clock period
  /// (chip_counters().cycles). A run that fails or is stopped early never
  /// notifies it.
  const sc_core::sc_event& completion_event() const { return completion_; }
  /// Called once at completion, before the processes waiting on
  /// completion_event() run, with the cycle of the last ray's finish.
  void set_completion_callback(std::function<void(uint64_t cycles)> callback) {
    completion_callback_ = std::move(callback);
  }
  /// On: sc_stop() when the run ends, so that sc_start() returns although
  /// other processes never stop: at completion (after the callback and the
  /// notification), or when the run ends early (an error inside the model, the
  /// stop flag, a run with nothing left to do and rays unfinished); check()
  /// tells which. Off (default): the simulation goes on as long as other
  /// processes have events (without any, sc_start() returns at completion).
  void set_stop_at_completion(bool on) { stop_at_completion_ = on; }
  bool completed() const { return completed_; }

  // ---- after sc_start ----
  /// Rethrows an error raised inside the simulation; throws std::runtime_error
  /// naming the stuck slots when the run ended with rays unfinished although it
  /// was not stopped (a deadlock, or a memory target that never answered), and
  /// when the rays read and the rays finished differ.
  void check() const;
  bool partial() const { return engine_ && engine_->stopped(); }
  /// The chip-wide totals, summed from the modules.
  HwCounters chip_counters() const;
  /// The memory section of the stats (the shape of earlier versions' `hw.memory.port`).
  nlohmann::json memory_stats() const;
  SystemCRun systemc_run() const;
  /// The `hw` section: chip-wide figures, memory, `instances` (every module's
  /// statistics), and the run's price: `energy` (operations, memory, leakage)
  /// and `area`, as `vbsim replay --mode cycle --stats` gives them, priced by
  /// technology() (docs/energy.md). Replaced units are priced from the
  /// inventories they declare (hw/unit_inventory.h), or marked not priced.
  nlohmann::json hw_json();
  /// The technology file hw_json() prices with; by default the shipped
  /// model/energy/tech/45nm.json of the data directory (io/data_dir.h), read on first use.
  void set_technology(const TechFile& tech) { tech_ = tech; }
  /// Reads it from `path`: ConfigError "FILE: field 'F': reason" on a bad file.
  void set_technology(const std::string& path) { tech_ = load_tech_file(path); }
  const TechFile& technology();
  /// The units replaced through AcceleratorUnits (each core's from one factory:
  /// core 0's instance stands for them), with the inventories they declare.
  ReplacedUnits replaced_units() const;
  /// The ray source's emission: waits for parents, for the window, for slots (`hw.emission`).
  nlohmann::json emission_json() const;
  std::string hw_table();
  FunctionalReplayer& replayer() { return replayer_; }
  /// Sampled simulation (hw/sampling/sampled_feed.h): the built-in ray source
  /// treats a parent it never read as fast-forwarded (false: a replaced
  /// source, which cannot); before the run.
  bool set_parents_fast_forwarded(bool on) {
    if (source_) source_->set_parents_fast_forwarded(on);
    return source_ != nullptr;
  }
  /// The built-in ray source, or null when replaced.
  const RaySource* ray_source() const { return source_.get(); }
  /// Fast-forwards the rays `feed` gives until its next detailed ray
  /// (CycleEngine::fast_forward); during the run, from the feed.
  void fast_forward(SampledFeed& feed) { engine_->fast_forward(feed); }
  RayTestCore& core(size_t i) { return cores_[i]; }
  size_t cores() const { return cores_.size(); }
  IdealMemory* ideal_memory() { return ideal_.get(); }  ///< null with the caches
  L2Cache* l2() { return l2_.get(); }                    ///< null with an ideal memory or a replaced L2
  sc_core::sc_module* l2_replacement() { return l2_replacement_.get(); }  ///< the replacement L2, or null
  const HwConfig& config() const { return config_; }
  const CycleEngine* engine() const { return engine_.get(); }

  const char* unit_kind() const override { return "Accelerator"; }
  nlohmann::json parameters() const override;

 private:
  /// The units groups of cores share (hw.<unit>.share > 1), into shared_units_ and core_shared_.
  void build_shared_units(const AcceleratorUnits& units, const ReplayOptions& options);
  SC_HAS_PROCESS(Accelerator);
  void start_of_simulation() override;
  void activate();
  /// Arms the next activation; false when none is armed (the run has ended).
  bool schedule_next(uint64_t now);
  bool completion_due() const { return !completed_ && engine_->complete() && !engine_->stopped(); }
  /// The notification, the callback and (stop_at_completion) sc_stop().
  void complete_run();
  bool at_busy() const { return at_ && l2_ && (l2_->busy() || l2_->next_response_cycle() != kPendingCycle); }
  EngineParts engine_parts();
  /// The hierarchical name of the module answering the L2's requests.
  std::string memory_target_name() const;

  HwConfig config_;
  const Bvh& bvh_;
  FunctionalReplayer replayer_;
  CycleClock clock_;
  bool at_;
  bool avoidance_in_use_;
  std::unique_ptr<RaySource> source_;               // the built-in source, null when replaced
  std::unique_ptr<sc_core::sc_module> source_module_;  // a replacement (units.ray_source)
  RaySourceIf* source_if_ = nullptr;                 // the one the scheduler drives
  std::unique_ptr<sc_core::sc_module> dispatcher_module_;
  bool dispatcher_replaced_ = false;
  std::optional<TechFile> tech_;
  DispatchIf* dispatcher_ = nullptr;
  std::vector<std::unique_ptr<sc_core::sc_module>> shared_units_;  ///< units groups of cores share (hw.<unit>.share)
  std::vector<SharedUnits> core_shared_;                           ///< per core: its group's shared units
  sc_core::sc_vector<RayTestCore> cores_;
  std::unique_ptr<IdealMemory> ideal_;
  std::vector<std::unique_ptr<ObjectCaches>> object_caches_;  ///< per core, with memory.objects
  nlohmann::json object_caches_stats() const;
  std::unique_ptr<L2Cache> l2_;
  std::unique_ptr<sc_core::sc_module> l2_replacement_;  // a replacement L2 (then l2_ is null)
  std::unique_ptr<tlm::tlm_initiator_socket<>> memory_socket_;
  std::unique_ptr<Dram> dram_;
  std::unique_ptr<ResultSink> sink_;
  std::unique_ptr<sc_core::sc_module> sink_replacement_;  // a replacement result sink, or null
  std::unique_ptr<LineFillIf> no_fill_;  // the L2's answer path for cores whose L1 was replaced

  MemoryClock memory_clock_;
  std::vector<L1Cache*> memory_l1s_;  // the built-in L1s, whose misses the memory step sends
  std::unique_ptr<CycleEngine> engine_;
  RayTimesSink ray_times_;
  VcdRecorder* vcd_ = nullptr;
  TimelineRecorder* timeline_ = nullptr;
  RunStatistics* statistics_ = nullptr;
  const std::atomic<bool>* stop_ = nullptr;
  std::function<void(const CycleEngine&)> progress_;
  sc_core::sc_event kick_;
  sc_core::sc_event completion_;
  std::function<void(uint64_t)> completion_callback_;
  bool stop_at_completion_ = false;
  bool completed_ = false;
  uint64_t limit_ = 0;  // the scheduler handles events before this cycle (lowered by AT requests)
  uint64_t activations_ = 0;
  std::exception_ptr error_;
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace vbsim::hw
