#include "hw/memory/l2_cache.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "hw/memory/cache_level_stats.h"
#include "hw/memory/l2_cache_inline.h"

namespace vbsim::hw {

L2Cache::L2Cache(sc_core::sc_module_name name, const CacheConfig& config, const CycleClock& clock, TlmStyle style,
                 uint32_t lookahead_cycles)
    : sc_core::sc_module(name), target("target"), fill_out("fill_out"), socket("socket"), level_(config),
      config_(config), clock_(clock), style_(style), lookahead_(lookahead_cycles < 1 ? 1 : lookahead_cycles),
      line_shift_(log2_of(config.line_bytes)), data_(config.line_bytes) {
  target.bind(*this);
  socket.bind(*this);
  prepare(lt_payload_, 0);
  declare_stat("dram_requests", "transactions", "TLM-2.0 read transactions sent through the socket", dram_requests_);
  declare_stat("late_responses", "transactions",
               "approximately timed responses sooner than the lookahead promises (the run stops with an error)",
               late_responses_);
  declare_stats(cache_level_statistics(level_, "DRAM", misses_sent_late_));
}

L2Cache::~L2Cache() {
  // Every payload this cache made: the pool's, and those still out at a memory
  // target when the run stopped (a target that never answered, an error).
  for (const auto& [trans, sent] : in_flight_send_cycle_) pool_.push_back(trans);
  for (tlm::tlm_generic_payload* p : pool_) {
    p->set_mm(nullptr);
    delete p;
  }
}

nlohmann::json L2Cache::parameters() const {
  return {{"size_bytes", config_.size_bytes},
          {"ways", config_.ways},
          {"line_bytes", config_.line_bytes},
          {"hit_latency", config_.hit_latency},
          {"mshrs", config_.mshrs},
          {"merge_misses", config_.merge_misses},
          {"tlm", tlm_style_name(style_)},
          {"at_lookahead_cycles", lookahead_}};
}

void L2Cache::set_tracing(TimelineRecorder* timeline, VcdRecorder* vcd) {
  track_ = timeline ? timeline->track(name(), "dram requests") : TimelineRecorder::kNoTrack;
  timeline_ = track_ == TimelineRecorder::kNoTrack ? nullptr : timeline;
  vcd_misses_ = vcd ? vcd->signal(name(), "misses_in_flight") : VcdRecorder::kNoSignal;
  vcd_ = vcd_misses_ == VcdRecorder::kNoSignal ? nullptr : vcd;
}

void L2Cache::prepare(tlm::tlm_generic_payload& trans, uint64_t line) const {
  trans.set_command(tlm::TLM_READ_COMMAND);
  trans.set_address(line << line_shift_);
  trans.set_data_ptr(const_cast<unsigned char*>(data_.data()));
  trans.set_data_length(config_.line_bytes);
  trans.set_streaming_width(config_.line_bytes);
  trans.set_byte_enable_ptr(nullptr);
  trans.set_dmi_allowed(false);
  trans.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
}

uint64_t L2Cache::dram_read(uint64_t line, uint64_t send) {
  ++dram_requests_;
  // Loosely timed without a memory clock (a bare memory rig): at once, in call order.
  if (style_ == TlmStyle::LooselyTimed && !memory_clock_) return transport_lt(line, send);
  sends_.push(send, line);
  ++outstanding_;
  if (style_ == TlmStyle::LooselyTimed) memory_clock_->request(send);
  else if (on_request_) on_request_(send);
  return kPendingCycle;
}

void L2Cache::release_lt(uint64_t now) {
  uint64_t cycle, line;
  while (sends_.pop_due(now, cycle, line)) {
    const uint64_t fill = transport_lt(line, cycle);
    responses_.push(fill, line);  // applied at its cycle, as a response would be
    memory_clock_->request(fill);
  }
}

uint64_t L2Cache::transport_lt(uint64_t line, uint64_t send) {
  lt_payload_.set_address(line << line_shift_);
  lt_payload_.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time delay = clock_.delay_to(send);
  socket->b_transport(lt_payload_, delay);
  if (lt_payload_.is_response_error())
    throw std::runtime_error(fmt::format("{}: the memory target answered the read of 0x{:x} with {}", name(),
                                         line << line_shift_, lt_payload_.get_response_string()));
  const uint64_t ready = std::max(clock_.cycle_after(delay), send + 1);  // a line takes at least a cycle
  dram_read_done(send, ready);
  return ready;
}

// ---- approximately timed ----

void L2Cache::wait_for(uint64_t line, uint32_t core, uint64_t t) { waiting_.add(line, core, t); }

void L2Cache::defer_miss(uint64_t line, uint32_t core, uint64_t t) {
  deferred_.push_back({line, t});
  wait_for(line, core, t);
}

uint64_t L2Cache::run_ahead_limit(uint64_t now) const {
  uint64_t earliest = kPendingCycle;
  for (const auto& [trans, sent] : in_flight_send_cycle_) earliest = std::min(earliest, sent);
  earliest = std::min(earliest, sends_.earliest());
  if (earliest == kPendingCycle) return kPendingCycle;
  // A response comes at least lookahead_ cycles after its request.
  return std::max(now, earliest + lookahead_ - 1);
}

void L2Cache::release_due(uint64_t now) {
  uint64_t cycle, line;
  while (!request_in_progress_ && sends_.pop_due(now, cycle, line)) {
    tlm::tlm_generic_payload* trans;
    if (pool_.empty()) {
      trans = new tlm::tlm_generic_payload();
      trans->set_mm(this);
    } else {
      trans = pool_.back();
      pool_.pop_back();
    }
    prepare(*trans, line);
    trans->acquire();
    in_flight_send_cycle_[trans] = now;
    if (timeline_) timeline_->add(track_, "dram request", now, now + 1, -1);
    tlm::tlm_phase phase = tlm::BEGIN_REQ;
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    const tlm::tlm_sync_enum status = socket->nb_transport_fw(*trans, phase, delay);
    if (status == tlm::TLM_COMPLETED) {
      arrived(*trans, delay);
    } else if (status == tlm::TLM_UPDATED && phase == tlm::BEGIN_RESP) {
      tlm::tlm_phase end = tlm::END_RESP;
      sc_core::sc_time zero = sc_core::SC_ZERO_TIME;
      socket->nb_transport_fw(*trans, end, zero);
      arrived(*trans, delay);
    } else if (!(status == tlm::TLM_UPDATED && phase == tlm::END_REQ)) {
      request_in_progress_ = trans;  // accepted: the next request waits for its END_REQ
    }
  }
}

tlm::tlm_sync_enum L2Cache::nb_transport_bw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                            sc_core::sc_time& delay) {
  if (phase == tlm::END_REQ) {
    if (request_in_progress_ == &trans) request_in_progress_ = nullptr;
    if (on_response_) on_response_();  // the next request may go
    return tlm::TLM_ACCEPTED;
  }
  if (phase == tlm::BEGIN_RESP) {
    if (request_in_progress_ == &trans) request_in_progress_ = nullptr;  // BEGIN_RESP implies END_REQ
    arrived(trans, delay);
    return tlm::TLM_COMPLETED;
  }
  throw std::runtime_error(fmt::format("{}: unexpected phase {} from the memory target", name(), phase.get_name()));
}

void L2Cache::arrived(tlm::tlm_generic_payload& trans, const sc_core::sc_time& delay) {
  if (trans.is_response_error())
    throw std::runtime_error(fmt::format("{}: the memory target answered the read of 0x{:x} with {}", name(),
                                         trans.get_address(), trans.get_response_string()));
  const auto it = in_flight_send_cycle_.find(&trans);
  const uint64_t sent = it == in_flight_send_cycle_.end() ? 0 : it->second;
  if (it != in_flight_send_cycle_.end()) in_flight_send_cycle_.erase(it);
  uint64_t cycle = std::max(clock_.cycle_after(delay), sent + 1);
  // The target's promise: no response sooner than lookahead_ cycles after its
  // request (the scheduler may have run that far ahead). Broken, the run's
  // figures may be wrong: it stops with an error naming the target.
  if (cycle < sent + lookahead_ || cycle <= handled_) {
    if (late_responses_++ == 0)
      broken_promise_ = fmt::format(
          "{}: answered the read of 0x{:x} sent at cycle {} for cycle {}, {} cycles after the request (the "
          "accelerator had handled cycle {}), but memory.at_lookahead_cycles = {} promises that no response comes "
          "sooner than that many cycles after its request: set it to at most the target's shortest latency",
          target_name_, trans.get_address(), sent, cycle, cycle - sent, handled_, lookahead_);
    if (cycle <= handled_) cycle = handled_ + 1;
  }
  const uint64_t line = trans.get_address() >> line_shift_;
  responses_.push(cycle, line);
  dram_read_done(sent, cycle);
  trans.release();
  if (on_response_) on_response_();
}

void L2Cache::free(tlm::tlm_generic_payload* trans) {
  trans->reset();
  pool_.push_back(trans);
}

void L2Cache::apply_responses(uint64_t now) {
  uint64_t cycle, line;
  while (responses_.pop_due(now, cycle, line)) {
    --outstanding_;
    resolve(line, cycle);
  }
}

void L2Cache::resolve(uint64_t line, uint64_t fill) {
  level_.resolve(line, fill);
  waiting_.fill(line, fill, level_,
                [this, line](uint32_t core, uint64_t ready) { fill_out[core]->line_filled(line, ready); });
  send_deferred();
}

void L2Cache::send_deferred() {
  while (!deferred_.empty() && level_.mshr_free_cycle() != kPendingCycle) {
    const DeferredMiss d = deferred_.front();
    deferred_.pop_front();
    const uint64_t start = std::max(level_.mshr_free_cycle(), d.t);
    level_.count_mshr_wait(start - d.t);
    ++misses_sent_late_;
    level_.hold_mshr(kPendingCycle);
    const uint64_t fill = dram_read(d.line, start + level_.hit_latency());
    if (fill != kPendingCycle) resolve(d.line, fill);
  }
}

std::string L2Cache::outstanding_report() const {
  std::ostringstream s;
  s << in_flight_send_cycle_.size() << " DRAM requests in flight (sent at cycles";
  for (const auto& [trans, sent] : in_flight_send_cycle_) s << " " << sent;
  s << "), " << sends_.size() << " queued, " << responses_.size() << " responses not applied, "
    << deferred_.size() << " misses waiting for an MSHR";
  return s.str();
}

}  // namespace vbsim::hw
