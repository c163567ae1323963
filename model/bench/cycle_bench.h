// Cycle-level speed benchmark: times the cycle-level replay (SystemC-driven
// engine) and Embree on the same rays (bench_workload.h) in one run.
// A benchmark, not a test.
#pragma once
#include "bench/functional_bench.h"
#include <nlohmann/json.hpp>

#include "hw/hw_config.h"

namespace vbsim {

struct CycleBenchResult {
  BenchResult speed;        ///< vbsim_* are the cycle-level replay's figures
  uint64_t cycles = 0;      ///< simulated cycles of the last repetition
  double rays_per_cycle = 0;
  nlohmann::json energy, area;  ///< hw.energy and hw.area of the last repetition (docs/energy.md)
};

CycleBenchResult run_cycle_bench(const Scene& scene, const ReplayOptions& opt, const hw::HwConfig& cfg,
                                 const BenchWorkload& w, const BenchParams& p);

}  // namespace vbsim
