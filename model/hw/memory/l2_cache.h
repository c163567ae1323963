// L2Cache: the shared second-level cache as a SystemC module. Every core's L1
// sends its misses here (LineReadIf at `target`); the L2's own misses leave
// through a TLM-2.0 initiator socket to the DRAM target (`socket`, a
// tlm_generic_payload read of one line at the line's byte address).
//
// Loosely timed (memory.tlm "lt", the default): each miss is one b_transport
// call whose delay annotation says when the request leaves the L2 (ahead of
// SystemC time by up to the scheduler's quantum) and, on return, when its line
// arrives. The call is made when the scheduler reaches the cycle the request
// leaves, not when the miss is found: misses are found up to an L1 and L2 round
// ahead of that cycle and out of its order, and a target that books a shared
// resource (the built-in DRAM channel) in call order would then serve a later
// request first. So a target sees its requests in time order, each annotated
// with its own cycle. The line is pending (kPendingCycle) until the arrival
// cycle the call returned, as with the approximately timed protocol: the L2
// asks the memory clock (hw/memory/memory_clock.h) for each request's cycle and each
// arrival's, and the accelerator's memory step at such a cycle applies the
// arrivals due (apply_responses) and, after the L1s' work, sends the requests
// due (release_lt), as the approximately timed path does before each cycle it
// handles; both styles then give the same cycles.
//
// Approximately timed ("at"): each miss is queued and sent with nb_transport_fw
// (BEGIN_REQ) when SystemC time reaches the cycle it leaves the L2, one request
// at a time (the base protocol's request exclusion: the next waits for END_REQ);
// its line is pending (kPendingCycle) until the target's BEGIN_RESP, which may
// come whenever the target decides (its latency may depend on its state, as a
// DRAM controller's does). The scheduler asks for due sends and arrived
// responses each cycle it handles (release_due, apply_responses) and never
// handles a cycle beyond run_ahead_limit(). A response is taken at the cycle it
// arrives (its time rounded up to a clock edge), at least one cycle after its
// request, and never before the cycle the scheduler last handled (counted as a
// late response when that moved it).
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <systemc>
#include <tlm>

#include "hw/cycle_clock.h"
#include "hw/memory/cache_level.h"
#include "hw/memory/line_waiters.h"
#include "hw/memory/memory_clock.h"
#include "hw/memory/memory_config.h"
#include "hw/memory/memory_interfaces.h"
#include "hw/memory/timed_queue.h"
#include "hw/observe/stat_provider.h"
#include "hw/observe/timeline_recorder.h"
#include "hw/observe/vcd_recorder.h"

namespace vbsim::hw {

class L2Cache final : public sc_core::sc_module,
                      public LineReadIf,
                      public StatProvider,
                      public tlm::tlm_bw_transport_if<>,
                      public tlm::tlm_mm_interface {
 public:
  sc_core::sc_export<LineReadIf> target;     ///< bound by every core's L1
  sc_core::sc_port<LineFillIf, 0> fill_out;  ///< every core's L1, in core order (pending answers)
  tlm::tlm_initiator_socket<> socket;         ///< misses, to the DRAM target

  /// `config` is valid (check_memory_config); `clock` outlives the cache.
  L2Cache(sc_core::sc_module_name name, const CacheConfig& config, const CycleClock& clock, TlmStyle style,
          uint32_t lookahead_cycles);
  ~L2Cache() override;

  uint64_t read_line(uint64_t line, uint64_t t, uint32_t core) override { return read_line_inline<0>(line, t, core); }
  /// read_line() with the associativity known at compile time (`Ways`, 0: any):
  /// inlined into the built-in L1's reads. Defined in l2_cache_inline.h.
  template <uint32_t Ways>
  uint64_t read_line_inline(uint64_t line, uint64_t t, uint32_t core);

  const LruCache& tags() const { return level_.tags(); }
  /// Functional warming of `line` (CacheLevel::warm; sampled simulation only).
  bool warm_line(uint64_t line) { return level_.warm(line); }
  uint32_t ways() const { return config_.ways; }

  // ---- loosely timed, in time order ----
  /// Asks `clock` for the cycles of its requests and arrivals (null: each
  /// request is sent when its miss is found, in call order: a bare memory rig).
  void set_memory_clock(MemoryClock* clock) { memory_clock_ = clock; }
  /// Sends (b_transport) the queued requests due at or before `now` in time
  /// order; their lines arrive (apply_responses) at the cycles the target gave.
  void release_lt(uint64_t now);

  // ---- approximately timed: what the scheduler asks each cycle it handles ----
  /// Requests queued or in flight.
  bool busy() const { return outstanding_ != 0; }
  /// Sends the queued requests due at or before `now` (SystemC time is at `now`).
  void release_due(uint64_t now);
  /// Resolves the responses that arrived for cycles at or before `now` (either style).
  void apply_responses(uint64_t now);
  /// The cycle of the next queued send, else kPendingCycle.
  uint64_t next_send_cycle() const { return sends_.earliest(); }
  /// The cycle of the earliest response that arrived but is not applied, else kPendingCycle.
  uint64_t next_response_cycle() const { return responses_.earliest(); }
  /// The last cycle the scheduler may handle now that SystemC time is at
  /// `now`: `now` itself, or further when the target promises a lookahead.
  uint64_t run_ahead_limit(uint64_t now) const;
  /// Called when a response (or an END_REQ) arrives, so the scheduler wakes up.
  void set_response_callback(std::function<void()> cb) { on_response_ = std::move(cb); }
  /// Called with its send cycle when a request is queued, so the scheduler
  /// stops short of where its response could fall (run_ahead_limit).
  void set_request_callback(std::function<void(uint64_t)> cb) { on_request_ = std::move(cb); }
  uint32_t lookahead_cycles() const { return lookahead_; }
  /// The scheduler last handled cycle `c` (responses before it are late).
  void handled_up_to(uint64_t c) { handled_ = c; }
  /// The memory target's name, for errors (set once it is bound).
  void set_target_name(std::string name) { target_name_ = std::move(name); }
  /// Empty, or what the target did to break its lookahead promise (the first
  /// response that came for a cycle already handled): the run's figures are then wrong.
  const std::string& broken_promise() const { return broken_promise_; }
  /// A line state for a report of a stuck run: requests in flight and queued.
  std::string outstanding_report() const;

  const char* unit_kind() const override { return "L2Cache"; }
  nlohmann::json parameters() const override;
  LevelCounters counters() const { return level_.counters(); }
  uint64_t dram_requests() const { return dram_requests_; }
  /// Records its DRAM reads (timeline) and misses in flight (VCD); either may be null.
  void set_tracing(TimelineRecorder* timeline, VcdRecorder* vcd = nullptr);
  /// Summed over its DRAM reads whose data have come: cycles from the read's
  /// sending to its data (the miss latency less the lookup and any MSHR wait).
  uint64_t dram_read_cycles() const { return dram_fill_sum_ - dram_send_sum_; }
  /// DRAM reads whose data have come.
  uint64_t dram_reads_filled() const { return dram_reads_filled_; }

  // tlm_bw_transport_if, tlm_mm_interface
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override;
  void invalidate_direct_mem_ptr(sc_dt::uint64, sc_dt::uint64) override {}
  void free(tlm::tlm_generic_payload* trans) override;

 private:
  /// The cycle line `line`, leaving the L2 at `send`, arrives (LT), or kPendingCycle (AT: queued).
  uint64_t dram_read(uint64_t line, uint64_t send);
  /// One b_transport of line `line` leaving at `send`: the cycle it arrives.
  uint64_t transport_lt(uint64_t line, uint64_t send);
  void wait_for(uint64_t line, uint32_t core, uint64_t t);
  void defer_miss(uint64_t line, uint32_t core, uint64_t t);
  void resolve(uint64_t line, uint64_t fill);

  void send_deferred();
  void arrived(tlm::tlm_generic_payload& trans, const sc_core::sc_time& delay);
  void prepare(tlm::tlm_generic_payload& trans, uint64_t line) const;

  CacheLevel level_;
  CacheConfig config_;
  const CycleClock& clock_;
  TlmStyle style_;
  uint32_t lookahead_, line_shift_;
  uint64_t dram_requests_ = 0, late_responses_ = 0, misses_sent_late_ = 0;
  tlm::tlm_generic_payload lt_payload_;
  std::vector<unsigned char> data_;  // the payload's data buffer (contents not modelled)

  // Approximately timed state.
  struct DeferredMiss {
    uint64_t line, t;
  };
  TimedQueue<uint64_t> sends_;      // lines to send, by the cycle they leave (then the order found)
  TimedQueue<uint64_t> responses_;  // lines arrived, by their cycle (then the order they came)
  std::map<tlm::tlm_generic_payload*, uint64_t> in_flight_send_cycle_;  // sent, no response yet
  LineWaiters waiting_;                                                  // cores' L1s waiting for pending lines
  std::deque<DeferredMiss> deferred_;
  std::vector<tlm::tlm_generic_payload*> pool_;
  tlm::tlm_generic_payload* request_in_progress_ = nullptr;  // BEGIN_REQ sent, END_REQ not yet seen
  uint64_t outstanding_ = 0, handled_ = 0;
  std::function<void()> on_response_;
  std::function<void(uint64_t)> on_request_;
  MemoryClock* memory_clock_ = nullptr;
  /// A DRAM read sent at `send` has its data at `fill` (miss latency, tracing).
  void dram_read_done(uint64_t send, uint64_t fill) {
    dram_send_sum_ += send;
    dram_fill_sum_ += fill;
    ++dram_reads_filled_;
    if (timeline_) timeline_->add(track_, "dram read", send, fill, -1);
    if (vcd_) {
      vcd_->add(vcd_misses_, send, +1);
      vcd_->add(vcd_misses_, fill, -1);
    }
  }
  uint64_t dram_send_sum_ = 0, dram_fill_sum_ = 0, dram_reads_filled_ = 0;
  VcdRecorder* vcd_ = nullptr;
  uint32_t vcd_misses_ = VcdRecorder::kNoSignal;
  TimelineRecorder* timeline_ = nullptr;
  uint32_t track_ = TimelineRecorder::kNoTrack;
  std::string target_name_ = "the memory target";
  std::string broken_promise_;
};

}  // namespace vbsim::hw
