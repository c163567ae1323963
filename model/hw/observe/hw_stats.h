// The `hw` section of a cycle-level run's stats JSON, and its human table.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "replay/replay_stats.h"

namespace vbsim::hw {

struct HwReport {
  const HwCounters& counters;
  const HwConfig& config;
  const ReplayStats& replay;      ///< per-kind avoidance counters
  const nlohmann::json& memory;   ///< Accelerator::memory_stats()
  const SystemCRun& systemc;
};

/// cycles, rays_per_cycle, rays_per_s, utilisation, stalls, memory, avoidance, latency, systemc.
nlohmann::json hw_stats_json(const HwReport& r);
/// A few lines for the terminal.
std::string hw_summary_table(const HwReport& r);

}  // namespace vbsim::hw
