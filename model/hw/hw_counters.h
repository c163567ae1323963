// HwCounters: what the cycle engine counted in one run (cycles, unit
// operations, waits by cause, stack overflow, per-ray latency); hw/observe/hw_stats.h
// turns them into the `hw` section of the stats JSON and the human table.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "datapath/ray.h"
#include "hw/observe/latency_distribution.h"

namespace vbsim::hw {

struct UnitCounters {
  uint64_t ops = 0;          ///< operations issued (all cores)
  uint64_t wait_cycles = 0;  ///< cycles operations waited for a free pipeline ("pipeline full")
  /// Issue cycles held by operations of their own interval (UnitPipelines'
  /// three-argument issue: the controller); 0 for units whose every operation
  /// holds the configured interval (then: ops x issue_interval).
  uint64_t busy_cycles = 0;
  /// Chip-wide totals: a core's unit of this kind is a replacement, whose
  /// pipelines are its own (its utilisation is not known).
  bool replaced = false;
};

/// SystemC's view of one run.
struct SystemCRun {
  double start_ps = 0, end_ps = 0;  ///< SystemC time at the run's start and end
  uint64_t cycles = 0;              ///< (end - start) / period, as SystemC measured it
  uint64_t activations = 0;         ///< activations of the scheduler process
  double period_ps = 0;
};

/// What one ray-test core counted (its units and L1 count their own).
struct CoreCounters {
  uint64_t rays = 0;                ///< rays finished on this core
  uint64_t slot_cycles = 0;         ///< sum over its rays of cycles in a slot (dispatch to result)
  uint64_t node_fetches = 0, leaf_fetches = 0, refill_reads = 0;
  uint64_t memory_wait_cycles = 0;  ///< node and leaf fetches: cycles from request to data
  uint64_t refill_wait_cycles = 0;  ///< stack refill reads: cycles from request to data
  uint64_t spills = 0;              ///< stack entries pushed past the on-chip depth
  std::array<uint64_t, kRayKindCount> avoidance_ops_by_kind{};  ///< suspects sent to its avoidance unit
  /// Operations of the units that replacements took the place of, counted by
  /// the scheduler from their answers (issue - ready: the wait); a built-in
  /// unit counts its own.
  enum { kBox, kTriangle, kAvoidance };
  std::array<UnitCounters, 3> replaced_units{};
  UnitCounters controller;  ///< steps its traversal controllers took, and their waits (hw.controller)
};

/// What the ray source counted.
struct SourceCounters {
  uint64_t rays = 0;                ///< rays emitted
  uint64_t busy_cycles = 0;         ///< cycles spent emitting (interval, sign bits, emission ops)
  uint64_t sign_bits_computed = 0;  ///< rays whose sign bit the source computed
  uint64_t emission_ops = 0;        ///< emission-time method operations charged
  uint64_t emission_unit_ops = 0;   ///< arithmetic operations through the emission unit (0 without one)
  uint64_t no_free_slot_cycles = 0; ///< cycles a ready ray waited because no slot was free
};

/// What the result sink counted.
struct SinkCounters {
  uint64_t rays = 0;         ///< rays finished
  uint64_t last_cycle = 0;   ///< cycle the last ray finished
  uint64_t latency_sum = 0;  ///< sum of dispatch-to-result latencies
  uint64_t latency_min = 0, latency_max = 0;
  std::vector<uint64_t> latency_histogram;  ///< rays per latency bucket (the last one open-ended)
  std::array<LatencyDistribution, kRayKindCount> latency_by_kind;  ///< exact latencies by ray kind
};

/// The chip-wide totals of one run, summed from the modules' counters.
struct HwCounters {
  uint64_t cycles = 0;            ///< cycle at which the last ray finished
  uint64_t rays = 0;              ///< rays finished
  UnitCounters box, triangle, avoidance;
  UnitCounters box_low;     ///< the low-precision box pool (none: 0)
  UnitCounters controller;  ///< the cores' traversal controllers (none: 0)
  std::array<uint64_t, kRayKindCount> avoidance_ops_by_kind{};  ///< suspects sent to the avoidance unit
  uint64_t node_fetches = 0, leaf_fetches = 0, refill_reads = 0;
  uint64_t memory_wait_cycles = 0;  ///< node and leaf fetches: cycles from request to data
  uint64_t refill_wait_cycles = 0;  ///< stack refill reads: cycles from request to data
  uint64_t spills = 0;              ///< stack entries pushed past the on-chip depth
  uint64_t no_free_slot_cycles = 0; ///< cycles the source held a ready ray because no slot was free
  uint64_t source_busy_cycles = 0;  ///< cycles the source spent emitting (interval, sign bits, emission ops)
  bool source_replaced = false;     ///< a replacement source: the source's counts above are not known
  uint64_t sign_bits_computed = 0;  ///< rays whose sign bit the source computed
  uint64_t emission_ops = 0;        ///< emission-time method operations charged
  uint64_t emission_unit_ops = 0;   ///< arithmetic operations through the emission unit (0 without one)
  uint64_t slot_cycles = 0;         ///< sum over rays of cycles in a slot (dispatch to result)
  std::vector<uint64_t> latency_histogram;  ///< rays per latency bucket (the last one open-ended)
  uint64_t latency_min = 0, latency_max = 0;
};

}  // namespace vbsim::hw
