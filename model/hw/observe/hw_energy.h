// The cycle-level model's energy and area (docs/energy.md): the operations'
// dynamic energy (energy/operation_energy.h), the memory's (SRAM accesses by
// array size, DRAM per 64 bits, stack spills), leakage over the run's time,
// and the area of every unit instance from its operators, priced by a
// technology file. Computed once after a run from the counters the run kept:
// nothing is added to the per-cycle path.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "energy/tech_file.h"
#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/unit_inventory.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"

namespace vbsim::hw {

/// Area of one instance of each unit, in mm², and the chip's.
struct HwArea {
  double box_unit = 0;         ///< one box unit: every child box of a node (bvh.width) and the per-ray set-up
  double triangle_tester = 0;  ///< one tester: its test, set-up and the candidate compare
  double avoidance_unit = 0;   ///< one avoidance unit (0 when the method has none)
  double emission_unit = 0;    ///< the ray source's emission-time arithmetic, per emission lane
  double ray_records = 0;      ///< one core's ray records (slots x bits per ray)
  double method_record_bits = 0;  ///< of those, the bits the method adds beyond the 259-bit record
  double stack = 0;            ///< one core's on-chip traversal stacks (slots x depth x 96 bits)
  double l1_cache = 0, l2_cache = 0;  ///< data arrays (0 with an ideal memory)
  uint32_t box_units = 0, triangle_testers = 0, avoidance_units = 0, emission_lanes = 0, cores = 0;
  double chip() const;
  double avoidance_units_chip() const { return avoidance_unit * avoidance_units; }
  double method_record_bits_chip() const { return method_record_bits * cores; }
};

/// A pipeline group with `issue_interval` k shares each operator over k
/// operations: its operators are ceil(ops / k) of each kind. A `replaced` box
/// unit, triangle tester or avoidance unit is priced from its declared
/// inventory (unit_inventory.h), one that declares none at 0 (not priced); a
/// replaced L1 or L2 (and what is behind it) or ray source is not priced.
HwArea hw_area(const TechFile& tech, const HwConfig& cfg, const ReplayOptions& opt, const ReplacedUnits& replaced = {});
/// With replaced units: `replaced_units` [{unit, instance, priced}] and
/// `priced` (false when one of them is not).
nlohmann::json hw_area_json(const TechFile& tech, const HwArea& a, const ReplacedUnits& replaced = {});
/// The area table `vbsim hw --area` prints.
std::string hw_area_table(const TechFile& tech, const HwArea& a);

/// One line for every memory array of `cfg` (L1, L2, object caches) whose size
/// lies outside the technology file's SRAM table, whose access energy is then
/// extrapolated (TechFile::sram_64bit_pj): "  warning: the L1 (4 KB) is outside
/// FILE's SRAM table (8 KB to 1 MB): its access energy is extrapolated ...".
/// Empty when every array is inside the table, or with an ideal memory.
std::string sram_range_lines(const TechFile& tech, const HwConfig& cfg);

/// The `hw.energy` section: dynamic (operations and memory) and static (leakage
/// of the chip's area over cycles / clock) energy, per ray, per unit instance,
/// Mrays/J. `memory` is the hw section's memory.port (Accelerator::memory_stats).
/// Replaced units are priced as hw_area says, their operations' energy from
/// their inventories' (0 for a unit not priced), and listed as hw_area_json does.
nlohmann::json hw_energy_json(const TechFile& tech, const HwConfig& cfg, const ReplayOptions& opt,
                              const ReplayStats& stats, const HwCounters& counters, const nlohmann::json& memory,
                              const ReplacedUnits& replaced = {});
/// Two lines for the terminal table.
std::string hw_energy_lines(const nlohmann::json& energy, const nlohmann::json& area);

}  // namespace vbsim::hw
