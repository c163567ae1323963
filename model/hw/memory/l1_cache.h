// L1Cache: one core's private cache as a SystemC module. The core reads the BVH
// through it (MemoryReadIf at `target`); its misses go on to the shared L2
// through `next` (LineReadIf). docs/memory-model.md has the timing rules: a read
// is split into the lines it spans, each looked up at the read's cycle, and the
// read's data are ready with its last line; a miss takes the MSHR that frees
// first, allocates its line at once and holds the MSHR until the fill.
//
// A miss that must wait for an MSHR (every MSHR busy until a known later cycle)
// is looked up in the L2 at the cycle it leaves, not when it is found: it
// takes the MSHR and allocates its line at once (fill not known), asks the
// memory clock (hw/memory/memory_clock.h) for that cycle, and the accelerator's memory
// step then sends it (send_due), so that the shared L2 sees every core's
// lookups in time order: memory.l2_lookups_in_time_order. Otherwise (the
// default, faster) it is looked up at once, stamped with that cycle (its wait
// is in mshr_stall_cycles): the L2 takes it before lookups stamped earlier.
//
// Ports (memory.l1.ports, 0: unlimited): a read waits until a port takes it
// (UnitPipelines: `ports` pipelines, each taking a read every `port_cycles`
// cycles); its lookups are made at that cycle, and the wait is in
// port_wait_cycles.
//
// A miss's fill may not be known when it is sent (kPendingCycle: an L2 miss
// whose request has not reached the memory target yet): the read is then
// answered kPendingCycle and the core gets the cycle through `done`
// (ReadDoneIf) once the L2 calls line_filled(). Requests waiting for such a
// line, and misses waiting for an MSHR whose fill is unknown, are held here
// until then (out of line).
#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <unordered_map>
#include <vector>

#include <systemc>

#include "hw/memory/cache_level.h"
#include "hw/memory/line_waiters.h"
#include "hw/memory/memory_clock.h"
#include "hw/memory/memory_config.h"
#include "hw/memory/memory_interfaces.h"
#include "hw/observe/stat_provider.h"
#include "hw/observe/vcd_recorder.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

class L2Cache;

class L1Cache final : public sc_core::sc_module, public MemoryReadIf, public LineFillIf, public StatProvider {
 public:
  sc_core::sc_export<MemoryReadIf> target;    ///< the core's reads
  sc_core::sc_port<LineReadIf> next;          ///< misses, to the L2
  sc_core::sc_export<LineFillIf> fill_target; ///< the L2's answers to misses answered kPendingCycle
  sc_core::sc_port<ReadDoneIf> done;          ///< answers to the core's reads answered kPendingCycle

  /// The L1 of core `core`, whose slots are the accelerator-wide ids
  /// [first_slot, first_slot + slots). `config` is valid (check_memory_config).
  L1Cache(sc_core::sc_module_name name, const CacheConfig& config, uint32_t core, uint32_t first_slot,
          uint32_t slots);

  /// Misses go to `l2` by direct calls (the built-in L2, which `next` is bound
  /// to): the ways of both levels known at compile time for the presets' shapes.
  void connect_fast(L2Cache* l2);

  uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) override {
    return read_direct(addr, bytes, now, slot);
  }
  /// read() without the virtual call (the scheduler's direct path; one call,
  /// the line loop and both levels' lookups inlined into it).
  uint64_t read_direct(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) {
    event_now_ = now;
    return read_at(addr, bytes, __builtin_expect(ports_ != nullptr, 0) ? ports_->issue(now, now) : now, slot);
  }
  void line_filled(uint64_t line, uint64_t fill) override;

  /// Asks `clock` for the cycles its MSHR-waiting misses leave (null: none).
  void set_memory_clock(MemoryClock* clock) { clock_ = clock; }
  /// Sends the misses that leave at or before `now` to the L2.
  void send_due(uint64_t now);

  /// Asks the host's caches for the tag sets a read of `addr` looks up first
  /// (its first line in this L1 and in the L2); changes nothing.
  void prefetch(uint64_t addr) const {
    const uint64_t line = addr >> line_shift_;
    level_.tags().prefetch(line);
    if (l2_tags_) l2_tags_->prefetch(line);
  }

  /// Functional warming (sampled simulation, hw/sampling/): every line of a
  /// read of `bytes` at `addr` is warmed in this L1 (CacheLevel::warm) and,
  /// when it was absent and the built-in L2 is connected (connect_fast), in
  /// the L2, as the read's misses would reach it. No time, no counter.
  void warm(uint64_t addr, uint32_t bytes);

  const char* unit_kind() const override { return "L1Cache"; }
  nlohmann::json parameters() const override;
  LevelCounters counters() const { return level_.counters(); }
  uint64_t reads() const { return reads_; }
  uint64_t bytes() const { return bytes_; }
  /// The cycle of the first read and the latest ready cycle of any read (0 without reads).
  uint64_t first_read_cycle() const { return first_now_; }
  uint64_t last_ready_cycle() const { return last_ready_; }
  /// Summed over its misses whose data have come: cycles from the miss's
  /// leaving for the L2 to its data (the miss latency less any MSHR wait; the
  /// L1's lookup included, as the L2 is asked a hit latency after the miss left).
  uint64_t miss_service_cycles() const { return miss_fill_sum_ - miss_start_sum_; }
  /// Its misses whose data have come.
  uint64_t misses_filled() const { return misses_filled_; }
  /// Its misses in flight are recorded (VCD).
  void set_tracing(VcdRecorder* vcd);

 private:
  enum class Shape { Any, L1x4L2x8, L1x4L2x16 };
  /// The read a port took at cycle `now` (>= the cycle being handled).
  uint64_t read_at(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot);
  template <uint32_t L1Ways, uint32_t L2Ways>
  uint64_t read_shaped(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot);
  template <uint32_t L1Ways, uint32_t L2Ways>
  uint64_t read_line(uint64_t line, uint64_t now, uint32_t slot);
  template <uint32_t L2Ways>
  uint64_t next_level(uint64_t line, uint64_t t);
  /// next_level() of the L2's shape (the misses sent late).
  uint64_t next_level_any(uint64_t line, uint64_t t);

  // The pending path (approximately timed memory only).
  void wait_for(uint64_t line, uint32_t slot, uint64_t t);
  void defer_miss(uint64_t line, uint32_t slot, uint64_t t);
  /// A miss found at `t` that leaves at `start` (> t): allocated and holding
  /// its MSHR now, sent by send_due; kPendingCycle (out of line: the rare path).
  /// `allocated`: the line is there already (a miss of a line in flight, merging off).
  __attribute__((noinline, cold)) uint64_t defer_until(uint64_t line, uint32_t slot, uint64_t t, uint64_t start,
                                                       bool allocated);
  /// The miss of `line`, holding its MSHR, leaves for the L2 at `start` (send_due).
  void send_at(uint64_t line, uint64_t start);
  uint64_t pend_read(uint32_t slot, uint32_t lines, uint64_t ready);
  void answer(uint32_t slot, uint64_t ready);
  void send_deferred();
  void trace_miss(uint64_t start, uint64_t fill);
  // Miss latency: each miss's leaving cycle and fill cycle summed (a miss's
  // fill may come later than its leaving is known).
  void miss_sent(uint64_t start) { miss_start_sum_ += start; }
  void miss_filled(uint64_t fill) {
    miss_fill_sum_ += fill;
    ++misses_filled_;
  }
  uint64_t miss_start_sum_ = 0, miss_fill_sum_ = 0, misses_filled_ = 0;

  CacheLevel level_;
  CacheConfig config_;
  uint32_t core_, first_slot_, line_shift_;
  Shape shape_ = Shape::Any;
  L2Cache* l2_ = nullptr;  // the built-in L2 when connect_fast() was called
  const LruCache* l2_tags_ = nullptr;  // its tag array (for prefetch)
  uint64_t reads_ = 0, bytes_ = 0, first_now_ = 0, last_ready_ = 0;
  uint64_t misses_sent_late_ = 0;  ///< misses that waited for an MSHR whose fill was unknown
  uint64_t event_now_ = 0;         // the cycle being handled (a read's lookups may be later: ports)
  UnitCounters port_counters_;     // reads taken by a port and their waits
  std::unique_ptr<UnitPipelines> ports_;  // null: no port limit

  struct PendingRead {
    uint32_t lines = 0;  ///< lines still unknown
    uint64_t ready = 0;  ///< the latest known line's ready cycle
  };
  struct DeferredMiss {
    uint64_t line, t;
  };
  LineWaiters waiting_;  // slots waiting for pending lines
  std::vector<PendingRead> pending_;                           // by slot - first_slot_
  std::deque<DeferredMiss> deferred_;
  struct TimedMiss {
    uint64_t cycle, order, line;
    bool operator>(const TimedMiss& o) const { return cycle != o.cycle ? cycle > o.cycle : order > o.order; }
  };
  std::vector<TimedMiss> timed_;  // a min-heap by (leaving cycle, order found)
  uint64_t timed_order_ = 0;
  MemoryClock* clock_ = nullptr;
  // Tracing (VCD of the misses in flight; null: none).
  VcdRecorder* vcd_ = nullptr;
  uint32_t vcd_misses_ = VcdRecorder::kNoSignal;
};

}  // namespace vbsim::hw
