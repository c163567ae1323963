// RaySource: the patent's ray-emission interface (FIG. 12) in front of the
// dispatcher, with its ray-emission buffer.
//
// Buffer. The source reads trace rays in order into a buffer that looks ahead
// at most `source.window` rays beyond the oldest unfinished one (so it holds at
// most window + 1 rays, those in flight included; window 0: one ray at a time),
// and only as far as it must: until it has a ray ready to emit. Each ray goes
// through the datapath's emission step as it enters (FunctionalReplayer::emit:
// the origin, emission-time methods, the parent sign bit when the trace lacks
// it; in trace order, so parents are emitted before their children).
//
// Dependencies (`source.dependencies`, default on). A ray whose `parent` is one
// of the `parent_window` rays before it in the trace (ReplayOptions::
// parent_window, the same window the functional replay finds parent rays in)
// is ready `shader.latency_cycles` after that parent's result reached the
// result sink (the shader that emits it has seen the hit), whatever the trace
// order and the emission window: the source keeps the finish cycle and id of
// each of those rays (24 bytes a ray, and an id table of 16 bytes a slot at a
// load of at most 1/2 once ids stop running in trace order; both grow as rays
// arrive), so a parent far behind the buffer is still waited for. A ray
// without a parent is ready when it enters. A child whose parent is not among
// those rays (absent from the trace, later in it, or further back) is an error
// naming the child's line; with `source.missing_parents` "independent" it is
// ready on entry instead, counted (`parents_not_found`, the first one's line
// kept for a warning), and a parent that turns up after its child is then an
// error naming the parent's line. A ray id that repeats one of those rays' ids
// is an error. Off: every ray ready at once, as a trace of unrelated queries.
//
// Emission. `source.rays_per_cycle` lanes each take the ready ray earliest in
// trace order (a waiting child does not hold back the ready rays behind it) and
// are busy (occupied) for its emission cycles:
//   single-ray call:  issue_interval
//   bundle call of n: bundle_cycles + n x issue_interval   (`source.bundles`:
//                     consecutive ready rays of one parent with the same origin,
//                     at most bundle_max; the patent's "emit a bundle of rays")
//   + sign_bit_cycles per ray whose sign bit the source computes
//   + emission_op_cycles per emission-time method operation acting on a ray,
//     or, with an emission unit (emission_width W > 0), ceil(n / W) for a ray's
//     n operations: the unit accepts them in that many cycles.
// With shader cores (hw.shader.cores > 0) the method's emission-time arithmetic
// runs there instead (hw/source/shader_core_pool.h), between a ray's
// dependencies resolving and its reaching a lane (state Shading), and the lane
// pays only its issue interval and the sign bit.
// The unit is pipelined: its depth (emission_depth) delays the rays that went
// through it, after their lane is free again, and never occupies the lane. A
// lane's rays leave in the order it emitted them (its pipe). An emitted ray
// goes to the dispatcher; while every slot is busy its lane holds it and takes
// no new ray (the oldest held lane gets the next free slot).
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/observe/stat_provider.h"
#include "hw/source/id_position_map.h"
#include "hw/source/ray_feed.h"
#include "hw/source/ray_source_if.h"
#include "hw/source/ready_queue.h"
#include "hw/source/shader_core_pool.h"
#include "replay/functional_replayer.h"

namespace vbsim::hw {

/// What the source counted beyond SourceCounters.
struct EmissionCounters {
  uint64_t children_waited = 0;          ///< rays that entered the buffer before their parent's result
  uint64_t dependency_wait_cycles = 0;   ///< summed over rays: cycles from entering the buffer to ready
  uint64_t parents_not_found = 0;        ///< child rays whose parent the source could not find (replayed as independent)
  uint64_t lane_idle_dependency_cycles = 0;  ///< lane-cycles idle while buffered rays waited for parents
  uint64_t lane_idle_window_cycles = 0;  ///< lane-cycles idle with the buffer's window full of unfinished rays
  uint64_t lane_idle_shader_cycles = 0;  ///< lane-cycles idle while a closed-loop shader had no ray yet
  uint64_t bundles = 0, bundled_rays = 0;  ///< bundle calls and the rays they emitted
};

class RaySource final : public sc_core::sc_module, public RaySourceIf, public StatProvider {
 public:
  /// `replayer` outlives the source.
  RaySource(sc_core::sc_module_name name, const HwConfig& config, FunctionalReplayer& replayer);

  /// The trace to emit, and how to name a ray's line in an error (both before the simulation starts).
  void set_feed(RayFeed feed) override;
  /// A closed-loop feed (RayShader::next_ray): Later leaves the lanes idle
  /// until a ray finishes, when the source asks again.
  void set_shader_feed(ShaderFeed feed) override { feed_ = std::move(feed); }
  void set_locator(RayLocator locate) { locate_ = std::move(locate); }
  /// Sampled simulation (hw/sampling/sampled_feed.h): the feed leaves out the
  /// fast-forwarded rays, so a child whose parent is not among the rays read
  /// had it fast-forwarded: it is ready when it enters (its parent counts as
  /// finished then), counted in parents_fast_forwarded(), never an error.
  void set_parents_fast_forwarded(bool on) { parents_fast_forwarded_on_ = on; }
  uint64_t parents_fast_forwarded() const { return parents_fast_forwarded_; }

  // ---- the scheduler's side ----
  /// Events of the source: two per lane (its occupancy's end, its pipe's next
  /// ray leaving the emission unit's depth), one per buffer place.
  uint32_t event_ids() const override { return places_event_base_ + capacity_; }
  void start(SourceHost& host, uint64_t at) override;
  void on_event(uint32_t id, uint64_t at) override;
  /// The ray at trace position `index` finished at `at`.
  void on_finish(uint64_t index, uint64_t at) override;
  /// A slot became free at `at`: held rays go first, then idle lanes start.
  void on_slot_free(uint64_t at) override;
  /// The trace has ended and every ray read has finished.
  bool all_done() const override { return ended_ && base_ == next_; }
  uint64_t rays_read() const override { return next_; }
  bool holding() const { return !held_.empty(); }
  /// Where the first child whose parent was not found is (missing_parents
  /// "independent"; empty when none was): its line and what was missing.
  const std::string& first_parent_not_found() const { return first_not_found_; }
  /// Rays in the buffer not yet emitted, for a report of a stuck run.
  std::string buffer_report() const override;

  const SourceCounters& counters() const { return counters_; }
  const EmissionCounters& emission() const { return emission_; }
  /// The shader cores running the method's emission-time arithmetic, or null (hw.shader.cores 0).
  const ShaderCorePool* shader_cores() const { return pool_.get(); }
  const char* unit_kind() const override { return "RaySource"; }
  nlohmann::json parameters() const override;

 private:
  enum class State : uint8_t { Waiting, Shading, Ready, Emitting, Held, InFlight, Finished };
  static constexpr uint32_t kNone = ~uint32_t{0};
  static constexpr uint64_t kUnfinished = ~uint64_t{0};
  /// A ray in the buffer: from the oldest unfinished one to the last read.
  /// Small, so that the ring stays in the host's caches; the ray record itself
  /// is staged (below) only until it is dispatched.
  struct Entry {
    uint64_t index = 0;  ///< its trace position
    uint64_t entered = 0;
    uint64_t parent = 0;  ///< waiting: its parent's trace position
    /// Ring places: the first child waiting for this unfinished ray; the next
    /// child of the same parent (waiting for it, or in one group made ready
    /// together by the event at the group's first place).
    uint32_t first_child = kNone, next_sibling = kNone;
    uint32_t staged = kNone;  ///< its record in staged_ until dispatched
    State state = State::Finished;
  };
  /// Where a child's parent is, as far as the source knows.
  enum class ParentAt : uint8_t { Found, NotBefore, TooFar };
  enum class Idle : uint8_t { None, Dependency, Window, Shader, End };
  /// The rays of one call of the emission API (more than one: a bundle).
  struct Emission {
    uint64_t first = 0;  ///< trace position of its first ray
    uint32_t count = 0;  ///< rays it emits
    uint32_t sent = 0;   ///< of which dispatched
    uint64_t done = 0;   ///< the cycle its rays leave the emission path (after the unit's depth)
  };
  /// A lane: busy (`emitting`) for its current call's occupancy; its calls in
  /// the order they started, until their rays are dispatched (`pipe`, a ring
  /// of `pipe_capacity_`: the head is the oldest; `holding`: the head is done
  /// and waits for a free slot).
  struct Lane {
    bool emitting = false;
    bool holding = false;
    bool out_pending = false;  ///< an event for the pipe's head is scheduled
    uint32_t head = 0, size = 0;
    Idle idle = Idle::End;
    uint64_t idle_since = 0, held_since = 0;
  };

  uint32_t place_of(uint64_t pos) const { return static_cast<uint32_t>(pos & (capacity_ - 1)); }
  Entry& at_pos(uint64_t pos) { return ring_[place_of(pos)]; }
  const Entry& at_pos(uint64_t pos) const { return ring_[place_of(pos)]; }
  SourceRay& record(const Entry& e) { return staged_[e.staged]; }
  /// Reads the next trace ray into the buffer if the window allows; false when it does not or the trace ended.
  bool read_one(uint64_t now);
  /// Reads until a ray is ready or nothing more can be read.
  void fill_until_ready(uint64_t now);
  void enter(uint64_t pos, uint64_t now);
  void make_ready(uint64_t pos, uint64_t cycle);
  /// The trace position of the ray `id` among the parent_window_ rays before
  /// `pos` (the one entering), into `found`.
  ParentAt find_parent(int64_t id, uint64_t pos, uint64_t& found) const;
  /// Records that the ray `id` is at `pos` (the next position read); throws
  /// when `id` repeats an id of the rays the history holds.
  void note_position(int64_t id, uint64_t pos);
  /// A child at `pos` whose parent is not where it must be: an error naming
  /// its line, or (missing_parents "independent") counted.
  void parent_not_found(const TraceRay& tr, uint64_t pos, ParentAt where);
  /// The ray at `pos` waits for its parent at `parent_pos` (unfinished, or
  /// finished less than the shading latency ago): ready with the parent's other
  /// children when its result has been shaded.
  void wait_for_parent(uint64_t pos, uint64_t parent_pos);
  /// A position's finish cycle (kUnfinished until then) and, while its children
  /// wait for the shader, the ring place of their group's first child.
  struct Finish {
    uint64_t cycle = kUnfinished;
    int64_t id = 0;  ///< the ray's id (the id table's entries leave the history by it)
    uint32_t group = kNone;
    RayKind kind = RayKind::Primary;  ///< the ray's kind: the shading latency of its children
  };
  Finish& finish_at(uint64_t pos) { return finish_[pos & (history_capacity_ - 1)]; }
  [[noreturn]] void fail(uint64_t pos, const std::string& field, const std::string& what) const;
  void try_start(uint32_t lane, uint64_t now);
  void go_idle(uint32_t lane, uint64_t now);
  /// Adds the lane's idle time since it went idle (or was last counted) to its reason's counter.
  void account_idle(Lane& lane, uint64_t now);
  void start_idle_lanes(uint64_t now);
  Emission& pipe_at(uint32_t lane, uint32_t k) {
    return pipe_[lane * pipe_capacity_ + ((lanes_[lane].head + k) & (pipe_capacity_ - 1))];
  }
  /// Sends the rays of the lane's oldest call to free slots; true when all went.
  bool send(uint32_t lane, uint64_t now);
  /// Dispatches the lane's calls whose rays are done by `now`, in order, until
  /// one must wait for a slot (the lane then holds it); schedules the next
  /// one's event.
  void drain(uint32_t lane, uint64_t now);
  /// One ray's emission cycles, the lane's occupancy (counted: sign bits,
  /// emission operations); `through_unit` is set when its operations went
  /// through the emission unit (its depth then delays the ray).
  uint64_t emission_cycles(const TraceRay& tr, bool& through_unit);

  SourceConfig config_;
  uint32_t unit_ops_[2][2] = {};  ///< emission-unit operations by [has a parent surface][shadow]
  ShaderConfig shader_;  ///< the shading latency, by the kind of the parent ray
  FunctionalReplayer& replayer_;
  ShaderFeed feed_;
  RayLocator locate_;
  SourceHost* host_ = nullptr;
  uint32_t lanes_count_, window_, capacity_;  // capacity: a power of two above the window
  std::vector<Entry> ring_;  // position p at place_of(p); grown as positions arrive, up to capacity_
  /// The history: the Finish of each of the last history_capacity_ positions
  /// read, a power of two above parent_window_ + window_ + 1 (a waiting
  /// child's parent is kept while the child is in the buffer); grown as
  /// positions arrive.
  uint64_t parent_window_, history_capacity_;
  std::vector<Finish> finish_;
  bool parents_fast_forwarded_on_ = false;
  uint64_t parents_fast_forwarded_ = 0;
  bool independent_missing_ = false;  ///< missing_parents "independent"
  std::string first_not_found_;
  std::vector<SourceRay> staged_;     // records of rays read and not yet dispatched
  std::vector<uint32_t> free_staged_;  // places of staged_ free for reuse (the last freed first: warm)
  std::vector<Lane> lanes_;
  /// Calls a lane may have started and not yet dispatched (a power of two):
  /// one a cycle at the most through the unit's depth, one being emitted, one
  /// held; a lane whose pipe is full takes no new ray.
  uint32_t pipe_capacity_;
  std::vector<Emission> pipe_;  ///< the lanes' pipes, pipe_capacity_ each
  uint32_t places_event_base_;  ///< the first buffer place's event id (after the lanes' two each)
  uint64_t base_ = 0;  ///< the oldest unfinished position
  uint64_t next_ = 0;  ///< the next position to read
  bool ended_ = false;
  bool later_ = false;  ///< the feed's last answer was Later: ask again when a ray finishes
  uint64_t waiting_count_ = 0;  ///< buffered rays waiting for a parent
  /// Ids in trace order as first_id_, first_id_ + 1, ... (the usual trace): a ray's
  /// position is its id less first_id_. From the first id off that sequence on,
  /// position_of_ (made then) maps id -> position for the last parent_window_ + 1 positions.
  bool ids_dense_ = true;
  int64_t first_id_ = 0;
  std::unique_ptr<IdPositionMap> position_of_;
  struct Unresolved {
    uint64_t pos;  ///< the child's trace position
    int64_t id;    ///< and id
  };
  std::unordered_map<int64_t, Unresolved> unresolved_;  ///< parent id not found (missing_parents "independent") -> its child
  ReadyQueue ready_;  ///< ready positions, smallest first
  std::deque<uint32_t> held_;  ///< lanes holding an emitted ray for want of a slot, oldest first
  SourceCounters counters_;
  EmissionCounters emission_;
  std::unique_ptr<ShaderCorePool> pool_;  ///< hw.shader.cores > 0: the method's arithmetic runs there
  uint64_t shading_ = 0;      ///< buffered rays on the shader cores
  /// With shader cores and a method that runs arithmetic there: rays read
  /// ahead, ready or shading (fill_until_ready); 0 otherwise.
  uint64_t shade_ahead_ = 0;
};

}  // namespace vbsim::hw
