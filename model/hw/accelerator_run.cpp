// Accelerator: the SystemC process that keeps the accelerator's time (one
// SC_METHOD driving the scheduler a quantum at a time, and the approximately
// timed memory's hand-over), completion, and the checks after a run.
#include "hw/accelerator.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace vbsim::hw {

void Accelerator::start_of_simulation() {
  if (l2_) l2_->set_target_name(memory_target_name());
  memory_l1s_.clear();
  if (l2_) {  // the memory's work in time order (hw/memory/memory_clock.h)
    if (!at_) l2_->set_memory_clock(&memory_clock_);
    if (config_.memory.l2_lookups_in_time_order)
      for (RayTestCore& c : cores_)
        if (L1Cache* l1 = c.l1()) {
          l1->set_memory_clock(&memory_clock_);
          memory_l1s_.push_back(l1);
        }
  }
  engine_ = make_cycle_engine(engine_parts());
  clock_.start_now();
  activations_ = 0;
  last_progress_ = std::chrono::steady_clock::now();
  kick_.notify(sc_core::SC_ZERO_TIME);
}

void Accelerator::activate() {
  try {
    if (activations_ == 0) engine_->start();  // the source's first emission at cycle 0
    const uint64_t now = clock_.now();
    const bool at_wait = at_busy();
    // Approximately timed, requests outstanding: a cycle is handled only once
    // every other process of this time step has run (their responses are in).
    if (at_wait && sc_core::sc_pending_activity_at_current_time()) {
      next_trigger(sc_core::SC_ZERO_TIME);
      return;
    }
    ++activations_;
    if (stop_ && stop_->load(std::memory_order_relaxed)) engine_->stop();
    limit_ = now + config_.quantum_cycles;
    if (at_ && !l2_->broken_promise().empty()) throw std::runtime_error(l2_->broken_promise());
    if (at_wait) {
      l2_->apply_responses(now);
      l2_->release_due(now);
      const uint64_t last = l2_->run_ahead_limit(now);
      if (last != kPendingCycle) limit_ = std::min(limit_, last + 1);
    }
    engine_->advance(limit_);
    if (l2_) l2_->handled_up_to(engine_->last_handled());
    if (progress_ && (activations_ & 255) == 0) {
      const auto t = std::chrono::steady_clock::now();
      if (t - last_progress_ > std::chrono::milliseconds(250)) {
        last_progress_ = t;
        progress_(*engine_);
      }
    }
    if (completion_due() && sink_->counters().last_cycle <= now) complete_run();
    if (!schedule_next(now) && !completed_ && stop_at_completion_) sc_core::sc_stop();  // ended early
  } catch (...) {
    error_ = std::current_exception();
    if (engine_) engine_->stop();
    if (stop_at_completion_) sc_core::sc_stop();
  }
}

void Accelerator::complete_run() {
  // schedule_next lands SystemC time on the last ray's cycle; a later one would misplace the event.
  if (clock_.now() != sink_->counters().last_cycle)
    throw std::logic_error(fmt::format("{}: completion at cycle {}, after the last ray's finish at cycle {}", name(),
                                       clock_.now(), sink_->counters().last_cycle));
  completed_ = true;
  if (completion_callback_) completion_callback_(sink_->counters().last_cycle);
  completion_.notify();  // immediate: waiters run in this evaluation phase, before sc_stop() takes effect
  if (stop_at_completion_) sc_core::sc_stop();
}

bool Accelerator::schedule_next(uint64_t now) {
  const bool at_wait = at_busy();
  if (engine_->stopped()) return false;
  if (!at_wait) {
    if (!engine_->finished()) {
      const uint64_t next = std::max(now + config_.quantum_cycles, engine_->next_event_cycle());
      next_trigger(clock_.period() * static_cast<double>(next - now));
    } else if (sink_->counters().last_cycle > now) {
      next_trigger(clock_.period() * static_cast<double>(sink_->counters().last_cycle - now));  // land on the last cycle
    } else if (at_ && engine_->waiting_for_memory() != 0) {
      next_trigger(kick_);  // a response will come
    } else {
      return false;
    }
    return true;
  }
  uint64_t next = std::min(l2_->next_send_cycle(), l2_->next_response_cycle());
  if (!engine_->finished()) next = std::min(next, engine_->next_event_cycle());
  if (next == kPendingCycle) {
    next_trigger(kick_);  // only the target's responses are left to wait for
    return true;
  }
  next = std::max(next, now + 1);
  next_trigger(clock_.period() * static_cast<double>(next - now), kick_);
  return true;
}

std::string Accelerator::memory_target_name() const {
  if (dram_) return dram_->name();
  const auto* target = dynamic_cast<const sc_core::sc_object*>(memory_socket_->get_interface());
  return target ? std::string(target->name())
                : fmt::format("the memory target bound to {}", memory_socket_->name());
}

void Accelerator::check() const {
  if (error_) std::rethrow_exception(error_);
  if (l2_ && !l2_->broken_promise().empty()) throw std::runtime_error(l2_->broken_promise());
  if (!engine_) throw std::runtime_error(std::string(name()) + ": the simulation did not start");
  if (engine_->stopped()) return;
  const uint64_t fed = engine_->rays_fed(), done = sink_->counters().rays;
  if (!engine_->complete() || fed != done) {
    std::string what = fmt::format(
        "{}: the run stopped making progress at cycle {}: {} of {} rays read finished, {} in slots, {} waiting for "
        "memory\n",
        name(), clock_.now(), done, fed, engine_->rays_in_flight(), engine_->waiting_for_memory());
    if (l2_) what += "  memory: " + l2_->outstanding_report() + "\n";
    what += engine_->slot_report(16);
    throw std::runtime_error(what);
  }
}

}  // namespace vbsim::hw
