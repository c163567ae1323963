// SampledFeed: the trace as a sampled cycle-level replay gives it to the
// accelerator (SamplePlan says which rays), and the measurement of its units.
//
// The accelerator's ray source reads only the rays simulated in detail (a
// measured unit's and its warm-up's), through next_detailed(). The rays in
// between are fast-forwarded on the way: next_detailed() hands the scheduler
// to CycleEngine::fast_forward once per run of them, which takes each with
// next_fast_forward(), runs it through the functional datapath (emission,
// the same BvhStepper search, conclusion: hits, verdicts and functional
// statistics exact for every ray) and warms the caches' tags with the reads
// its traversal makes, and reports it with fast_forwarded(). Such a ray takes
// no simulated time: the ray source treats a fast-forwarded parent as finished
// when its child enters (RaySource::set_parents_fast_forwarded).
//
// The head and tail strata (SamplePlan) are measured as units of their own,
// whole. Measurement: with C(k) the cycle of the k-th finish among the
// detailed rays (C(0) = 0; finishes counted in completion order, as SMARTS
// counts committed instructions), a measured unit whose first ray is the d-th
// detailed ray and which holds x rays takes C(d + x) - C(d) cycles. With
// interval 1 the units tile the run and their cycles sum to the run's. A unit
// after which the trace goes on with fast-forwarded rays only ends in the
// detailed simulation's drain and is left out (MeasuredUnit::drained).
// L1 and L2 hits and accesses are read at the same two instants.
//
// Results reach the user's sink with their trace positions, detailed rays
// (through detailed_done) and fast-forwarded ones alike.
#pragma once
#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "hw/sampling/sample_plan.h"
#include "hw/sampling/sampling_config.h"
#include "hw/source/ray_feed.h"

namespace vbsim::hw {

class Accelerator;

/// Cache counters at one instant (built-in L1s summed, built-in L2).
struct CacheSnapshot {
  uint64_t l1_hits = 0, l1_accesses = 0, l2_hits = 0, l2_accesses = 0;
};

/// One measured unit: a body unit, or the head or the tail stratum measured whole.
struct MeasuredUnit {
  enum class Stratum { Head, Body, Tail };
  Stratum stratum = Stratum::Body;
  uint64_t trace_start = 0;   ///< its first ray's trace position
  uint64_t detailed_start = 0;  ///< its first ray's index among the detailed rays (d)
  uint64_t rays = 0;          ///< x
  uint64_t start_cycle = 0, end_cycle = 0;  ///< C(d), C(d + x)
  CacheSnapshot start, end;
  bool started = false, ended = false;
  /// The detailed rays end with this unit while the trace goes on: its end
  /// instant is the detailed simulation's drain, which a full run does not
  /// have there, so it is left out of the estimates.
  bool drained = false;
};

class SampledFeed final {
 public:
  /// `inner` gives the trace's rays in order; `sink` (may be empty) receives
  /// every ray's result with its trace position.
  SampledFeed(const SamplingConfig& config, RayFeed inner, RayResultSink sink);

  /// The accelerator whose scheduler fast-forwards and whose caches are read (before the run).
  void attach(Accelerator& accelerator) { acc_ = &accelerator; }

  // ---- the accelerator's side ----
  /// The next ray to simulate in detail (the ray source's feed); false at the trace's end.
  bool next_detailed(TraceRay& out);
  /// A detailed ray finished (the accelerator's result callback; index: its detailed position).
  void detailed_done(const TraceRay& tr, const RayOutcome& out, uint64_t cycle, uint64_t index);

  // ---- the scheduler's side (CycleEngine::fast_forward) ----
  /// The next ray to fast-forward; false when the next ray is detailed or the trace has ended.
  bool next_fast_forward(TraceRay& out);
  /// The ray next_fast_forward gave last has this result.
  void fast_forwarded(const TraceRay& tr, const RayOutcome& out, uint64_t cycle) {
    ++fast_forwarded_;
    if (sink_) sink_(tr, out, cycle, taken_pos_);
  }
  bool warm() const { return config_.warm; }

  // ---- after the run ----
  const SamplingConfig& config() const { return config_; }
  const std::vector<MeasuredUnit>& units() const { return units_; }
  uint64_t rays() const { return pos_; }  ///< rays read from the trace
  uint64_t detailed() const { return detailed_; }
  uint64_t fast_forwarded() const { return fast_forwarded_; }
  /// Why measuring ended: "trace ended" or "error target reached at trace position N".
  const std::string& stop_reason() const { return stop_reason_; }
  /// The head or tail stratum's measurement (null: none, or not complete).
  const MeasuredUnit* stratum(MeasuredUnit::Stratum which) const;
  const SamplePlan& plan() const { return plan_; }
  /// The measured body units completed so far (both instants known), but a drained one.
  std::vector<const MeasuredUnit*> complete_units() const;

 private:
  /// Reads the next trace ray into the stash (if it is empty); false at the end.
  bool peek();
  /// Whether `pos` is simulated in detail; decides the stopping rule when a
  /// new measured unit's rays would begin there. Called once per position.
  bool decide_detailed(uint64_t pos);
  /// The unit starting at `pos` begins (its first ray is being fed).
  void begin_unit(uint64_t pos, MeasuredUnit::Stratum stratum, uint64_t rays);
  /// The cycles' relative half-width over the units complete so far has reached the target.
  bool error_reached() const;
  CacheSnapshot snapshot() const;
  /// Records the instants whose finish count has been reached, at `cycle`.
  void cross(uint64_t cycle);

  SamplingConfig config_;
  SamplePlan plan_;
  RayFeed inner_;
  RayResultSink sink_;
  Accelerator* acc_ = nullptr;
  TraceRay stash_;
  bool stashed_ = false, stash_detailed_ = false, ended_ = false, active_ = true;
  uint64_t planned_start_ = ~uint64_t{0};  ///< the measured unit whose rays are being fed (its start)
  uint64_t stash_pos_ = 0, taken_pos_ = 0;
  uint64_t pos_ = 0;  ///< rays read from the trace
  uint64_t detailed_ = 0, fast_forwarded_ = 0, finished_ = 0, last_finish_cycle_ = 0;
  uint64_t current_unit_start_ = ~uint64_t{0};  ///< trace start of the unit being fed (measured)
  /// The detailed stretches: (first detailed index, its trace position), one
  /// per run of consecutive detailed rays (no per-ray storage).
  std::vector<std::pair<uint64_t, uint64_t>> stretches_;
  /// The trace position of the detailed ray at detailed index `index`.
  uint64_t trace_position(uint64_t index) const;
  std::vector<MeasuredUnit> units_;
  /// Instants not reached yet, in finish-count order: (count, unit, end?).
  struct Instant {
    uint64_t count;
    size_t unit;
    bool end;
  };
  std::deque<Instant> pending_;
  std::string stop_reason_ = "trace ended";
};

}  // namespace vbsim::hw
