// An accelerator beside a clocked module of the user's own design. The design
// has a free-running sc_clock at the accelerator's clock frequency (which
// alone would keep sc_start() running for ever) and a ProgressMonitor clocked
// by it, which counts rising edges and samples at each how many rays the
// accelerator has finished; a CompletionWaiter thread waits on the
// accelerator's completion event. The accelerator calls sc_stop() at
// completion (set_stop_at_completion), so sc_start() returns, at the SystemC
// time of the last ray's finish. The accelerator is the preset's, with its
// built-in memory: its cycles are those of
// `vbsim replay TRACE -m validity-bit --mode cycle --preset PRESET`.
//
//   clocked_design TRACE [PRESET [STOP_AFTER_RAYS]]   prints "key value" lines
//
// PRESET is small by default. STOP_AFTER_RAYS ends the run early (the stop flag,
// set from the result callback once that many rays have finished): sc_start()
// returns then too, with a partial run and no completion.
//
// Built with the project, and out of tree against the installed package
// (testbench/examples/CMakeLists.txt: find_package(vbsim), vbsim::vbsim).
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include <systemc>

#include "datapath/self_intersection_method.h"
#include "hw/accelerator.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

#include "example_main.h"

namespace {

/// The user's clocked module: on every rising edge, counts it and samples the
/// accelerator's finished rays. (The accelerator's scheduler may run up to
/// sim.quantum_cycles ahead of SystemC time, so a sample may count rays that
/// finish a little after the edge; the completion event comes at the exact time.)
class ProgressMonitor final : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk;
  uint64_t edges = 0;
  uint64_t rays_done_sampled = 0;  ///< at the last edge
  uint64_t edges_with_progress = 0;  ///< edges at which more rays were done than at the one before

  ProgressMonitor(sc_core::sc_module_name name, const vbsim::hw::Accelerator& accelerator)
      : sc_core::sc_module(name), clk("clk"), accelerator_(accelerator) {
    SC_METHOD(sample);
    sensitive << clk.pos();
    dont_initialize();
  }

 private:
  SC_HAS_PROCESS(ProgressMonitor);
  void sample() {
    ++edges;
    const vbsim::hw::CycleEngine* engine = accelerator_.engine();
    const uint64_t done = engine ? engine->rays_done() : 0;
    edges_with_progress += done > rays_done_sampled;
    rays_done_sampled = done;
  }
  const vbsim::hw::Accelerator& accelerator_;
};

/// A thread of the user's design that waits for the accelerator to finish.
class CompletionWaiter final : public sc_core::sc_module {
 public:
  int notifications = 0;
  sc_core::sc_time at;

  CompletionWaiter(sc_core::sc_module_name name, const sc_core::sc_event& completion)
      : sc_core::sc_module(name), completion_(completion) {
    SC_THREAD(wait_for_completion);
  }

 private:
  SC_HAS_PROCESS(CompletionWaiter);
  void wait_for_completion() {
    for (;;) {
      wait(completion_);
      ++notifications;
      at = sc_core::sc_time_stamp();
    }
  }
  const sc_core::sc_event& completion_;
};

int run(int argc, char** argv) {
  if (argc < 2) throw std::invalid_argument("usage: clocked_design TRACE [PRESET [STOP_AFTER_RAYS]]");
  const std::string trace = argv[1];
  const std::string preset = argc > 2 ? argv[2] : "small";
  const uint64_t stop_after = argc > 3 ? std::stoull(argv[3]) : 0;  // 0: run to the end

  auto source = vbsim::open_trace(trace);
  const vbsim::SceneAndBvh sb = vbsim::load_trace_scene(source->header());
  source->set_triangle_count(sb.scene.size());
  vbsim::ReplayOptions options;
  std::string error;
  if (!vbsim::parse_method("validity-bit", options.method, error)) throw std::runtime_error(error);

  const vbsim::hw::HwConfig config = vbsim::hw::load_preset(preset, "clocked_design");
  vbsim::hw::Accelerator accelerator("accelerator", config, sb.scene, sb.bvh, options);
  accelerator.set_feed([&](vbsim::TraceRay& ray) { return source->next(ray); });
  uint64_t hits = 0, finished = 0;
  std::atomic<bool> stop{false};
  accelerator.set_stop_flag(&stop);
  accelerator.set_result_callback([&](const vbsim::TraceRay&, const vbsim::RayOutcome& out, uint64_t, uint64_t) {
    hits += out.answer >= 0;
    if (++finished == stop_after) stop = true;
  });
  uint64_t callback_cycles = 0;
  int callbacks = 0;
  accelerator.set_completion_callback([&](uint64_t cycles) {
    ++callbacks;
    callback_cycles = cycles;
  });
  accelerator.set_stop_at_completion(true);

  const vbsim::hw::CycleClock cycle(config.clock_mhz);
  sc_core::sc_clock clock("clock", cycle.period());  // free-running: never runs out of events
  ProgressMonitor monitor("monitor", accelerator);
  monitor.clk(clock);
  CompletionWaiter waiter("waiter", accelerator.completion_event());

  sc_core::sc_start();  // returns: the accelerator calls sc_stop() at completion (or when stopped early)
  accelerator.check();  // an error inside the model, a stuck or lost ray: thrown here

  const vbsim::hw::HwCounters c = accelerator.chip_counters();
  const double period_ns = cycle.period().to_seconds() * 1e9;
  std::printf("sc_start_returned 1\n");
  std::printf("partial %d\n", accelerator.partial() ? 1 : 0);
  std::printf("rays %llu\n", static_cast<unsigned long long>(c.rays));
  std::printf("hits %llu\n", static_cast<unsigned long long>(hits));
  std::printf("cycles %llu\n", static_cast<unsigned long long>(c.cycles));
  std::printf("period_ns %.3f\n", period_ns);
  std::printf("completion_callbacks %d\n", callbacks);
  std::printf("completion_callback_cycles %llu\n", static_cast<unsigned long long>(callback_cycles));
  std::printf("completion_notifications %d\n", waiter.notifications);
  std::printf("completion_time_ns %.3f\n", waiter.at.to_seconds() * 1e9);
  std::printf("systemc_time_ns %.3f\n", sc_core::sc_time_stamp().to_seconds() * 1e9);
  std::printf("clock_edges %llu\n", static_cast<unsigned long long>(monitor.edges));
  std::printf("edges_with_progress %llu\n", static_cast<unsigned long long>(monitor.edges_with_progress));
  std::printf("rays_done_sampled %llu\n", static_cast<unsigned long long>(monitor.rays_done_sampled));
  return 0;
}

}  // namespace

int sc_main(int argc, char** argv) { return vbsim_examples::run_example("clocked_design", run, argc, argv); }
