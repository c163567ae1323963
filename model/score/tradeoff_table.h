// Trade-off rows: one line per (family, method, tester) of a score table
// (score_table.h) with a method's headline figures side by side: its
// secondary-ray error rate (self_hit + false_hit + missed per million rays
// that leave a surface), the camera rays its tester missed (a conservative
// tester's price), its costs (bits per ray in flight, operations per ray,
// functional rays per second) and, in cycle mode, the cycle-level model's
// cycles per ray and rays per cycle on the same traces.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vbsim {

struct TradeoffRow {
  std::string family, method, tester;
  uint64_t secondary_scored = 0, secondary_errors = 0;
  double secondary_rate = 0, secondary_lower = 0, secondary_upper = 0;  ///< per million
  uint64_t camera_scored = 0, camera_misses = 0;
  double camera_miss_rate = 0, camera_lower = 0, camera_upper = 0;  ///< per million camera rays
  int bits_per_ray = 0;
  double ops_per_ray = 0, rays_per_s = 0;
  double energy_per_ray_pj = 0;         ///< the operations' energy per ray (no memory)
  double method_energy_per_ray_pj = 0;  ///< of which the method's own
  bool has_cycles = false;
  double cycles_per_ray = 0, rays_per_cycle = 0;
  bool has_cycle_energy = false;     ///< the table has the cycle-level energy and area (since they were added)
  double cycle_energy_per_ray_pj = 0;  ///< operations, memory and leakage per ray, cycle-level
  double chip_mm2 = 0;                 ///< the chip's area
  std::string cycle_preset;
  uint64_t offset_fallbacks = 0;
};

/// The rows of a `vbsim score` JSON document, in its order.
std::vector<TradeoffRow> tradeoff_rows(const nlohmann::json& score);

/// A markdown table of `rows` (one family's), secondary-ray errors first.
std::string tradeoff_markdown(const std::vector<TradeoffRow>& rows);

/// The same as a fixed-width text table for a terminal (the main job's):
/// method, tester, secondary errors per million and camera misses per million
/// with their 95% Wilson intervals, cycles per ray, bits per ray and the
/// operations' energy per ray.
std::string tradeoff_text(const std::vector<TradeoffRow>& rows);

}  // namespace vbsim
