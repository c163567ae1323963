// An accelerator inside a user's own SystemC design. This program's sc_main
// builds a vbsim::hw::Accelerator from a preset, binds its memory socket to a
// memory target written here (every line `latency` cycles after its request,
// loosely timed), feeds it a trace and prints the statistics it reads back.
//
//   embed_accelerator [TRACE] [LATENCY_CYCLES]   (default: the bundled trace, 80 cycles)
//
// Built with the project, and out of tree against the installed package
// (testbench/examples/CMakeLists.txt: find_package(vbsim), vbsim::vbsim).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include <systemc>
#include <tlm>

#include "datapath/self_intersection_method.h"
#include "hw/accelerator.h"
#include "io/data_dir.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

#include "example_main.h"

namespace {

/// The user's memory: a TLM-2.0 target that answers every read `latency`
/// cycles after it arrives, with unlimited bandwidth.
class UserMemory : public sc_core::sc_module, public tlm::tlm_fw_transport_if<> {
 public:
  tlm::tlm_target_socket<> socket;
  uint64_t reads = 0;

  UserMemory(sc_core::sc_module_name name, const sc_core::sc_time& latency)
      : sc_core::sc_module(name), socket("socket"), latency_(latency) {
    socket.bind(*this);
  }
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) override {
    ++reads;
    delay += latency_;
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload&, tlm::tlm_phase&, sc_core::sc_time&) override {
    SC_REPORT_ERROR("UserMemory", "loosely timed only");
    return tlm::TLM_COMPLETED;
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }

 private:
  sc_core::sc_time latency_;
};

int run(int argc, char** argv) {
#ifdef VBSIM_SOURCE_DIR
  const std::string trace = argc > 1 ? argv[1] : std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
#else
  if (argc < 2) throw std::invalid_argument("usage: embed_accelerator TRACE [LATENCY_CYCLES]");
  const std::string trace = argv[1];
#endif
  const unsigned latency = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 80;

  auto source = vbsim::open_trace(trace);
  const vbsim::SceneAndBvh sb = vbsim::load_trace_scene(source->header());
  source->set_triangle_count(sb.scene.size());
  vbsim::ReplayOptions options;
  std::string error;
  vbsim::parse_method("validity-bit", options.method, error);

  const vbsim::hw::HwConfig config = vbsim::hw::load_preset("small", "embed_accelerator");
  vbsim::hw::AcceleratorUnits units;
  units.external_memory = true;  // the memory behind the L2 is ours
  vbsim::hw::Accelerator accelerator("accelerator", config, sb.scene, sb.bvh, options, units);
  const vbsim::hw::CycleClock clock(config.clock_mhz);
  UserMemory memory("user_memory", clock.cycles(latency));
  accelerator.memory_socket().bind(memory.socket);

  accelerator.set_feed([&](vbsim::TraceRay& ray) { return source->next(ray); });
  uint64_t hits = 0;
  accelerator.set_result_callback(
      [&](const vbsim::TraceRay&, const vbsim::RayOutcome& out, uint64_t, uint64_t) { hits += out.answer >= 0; });

  sc_core::sc_start();
  accelerator.check();  // an error inside the model, a stuck or lost ray: thrown here

  const vbsim::hw::HwCounters c = accelerator.chip_counters();
  const nlohmann::json hw = accelerator.hw_json();
  std::printf("rays %llu\n", static_cast<unsigned long long>(c.rays));
  std::printf("hits %llu\n", static_cast<unsigned long long>(hits));
  std::printf("cycles %llu\n", static_cast<unsigned long long>(c.cycles));
  std::printf("rays_per_cycle %.6f\n", hw["rays_per_cycle"].get<double>());
  std::printf("user_memory_reads %llu\n", static_cast<unsigned long long>(memory.reads));
  std::printf("l2_dram_requests %llu\n",
              hw["instances"]["accelerator.l2_cache"]["dram_requests"].get<unsigned long long>());
  std::printf("core_0_l1_hit_rate %.4f\n", hw["instances"]["accelerator.core_0.l1_cache"]["hit_rate"].get<double>());
  std::printf("systemc_time_ns %.1f\n", sc_core::sc_time_stamp().to_seconds() * 1e9);
  // The run's price (docs/energy.md), with the shipped technology file
  // (accelerator.set_technology(path) chooses another).
  std::printf("energy_pj_per_ray %.6g\n", hw["energy"]["per_ray_pj"].get<double>());
  std::printf("chip_mm2 %.6g\n", hw["area"]["chip_mm2"].get<double>());
  std::printf("presets_dir %s\n", vbsim::presets_dir().c_str());
  return 0;
}

}  // namespace

int sc_main(int argc, char** argv) { return vbsim_examples::run_example("embed_accelerator", run, argc, argv); }
