// PrecisionStudy: one trace replayed cycle-level with the built-in units and
// with reduced-precision replacements (reduced_precision/reduced_precision_units.h),
// and what each changes against the full-precision run: box and triangle tests,
// cycles, rays whose answer differs, self-hits. The figures of
// docs/hw-model.md ("Reduced precision") come from it (the program
// testbench/examples/precision_study.cpp prints them).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "hw/accelerator_units.h"
#include "hw/hw_config.h"
#include "replay/replay_options.h"

namespace vbsim::hw {

/// One run's figures.
struct PrecisionRun {
  std::string units;            ///< "built-in", "box N bits", "triangle N bits"
  int bits = 23;
  uint64_t rays = 0, cycles = 0;
  uint64_t box_tests = 0, triangle_tests = 0;
  uint64_t changed = 0;         ///< rays whose answer (triangle, or miss) differs from the built-in run's
  uint64_t self_hits = 0;       ///< verdict self_hit
  uint64_t box_ops = 0, triangle_ops = 0;  ///< the units' operations (the scheduler's count)
};

/// The bundled-trace study: `trace` (a .jsonl trace) under `cfg` and `opt`,
/// first with the built-in units, then with the box unit at each of `box_bits`
/// and the triangle tester at each of `triangle_bits`. The first run is the
/// built-in one.
std::vector<PrecisionRun> precision_study(const std::string& trace, const HwConfig& cfg, const ReplayOptions& opt,
                                          const std::vector<int>& box_bits, const std::vector<int>& triangle_bits);

/// One run of the study with `units` (changed rays counted against `reference`'s answers, by trace position).
PrecisionRun precision_run(const std::string& trace, const HwConfig& cfg, const ReplayOptions& opt,
                           const AcceleratorUnits& units, const std::vector<int32_t>* reference,
                           std::vector<int32_t>* answers);

}  // namespace vbsim::hw
