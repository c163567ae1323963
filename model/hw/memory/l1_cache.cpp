#include "hw/memory/l1_cache.h"

#include <algorithm>

#include "hw/memory/cache_level_stats.h"
#include "hw/memory/l2_cache_inline.h"

namespace vbsim::hw {

L1Cache::L1Cache(sc_core::sc_module_name name, const CacheConfig& config, uint32_t core, uint32_t first_slot,
                 uint32_t slots)
    : sc_core::sc_module(name), target("target"), next("next"), fill_target("fill_target"), done("done"),
      level_(config), config_(config), core_(core), first_slot_(first_slot), line_shift_(log2_of(config.line_bytes)),
      pending_(slots) {
  target.bind(*this);
  fill_target.bind(*this);
  declare_stat("reads", "reads", "reads by the core (a node, a leaf's triangles, a stack refill)", reads_);
  declare_stat("bytes", "bytes", "bytes the core read", bytes_);
  declare_stats(cache_level_statistics(level_, "the L2", misses_sent_late_));
  if (config.ports != 0) {
    ports_ = std::make_unique<UnitPipelines>(UnitConfig{config.ports, 1, config.port_cycles}, port_counters_,
                                             std::string(this->name()) + " ports");
    declare_stat("port_wait_cycles", "cycles", "cycles reads waited for a free port", port_counters_.wait_cycles);
  }
}

void L1Cache::connect_fast(L2Cache* l2) {
  l2_ = l2;
  l2_tags_ = l2 ? &l2->tags() : nullptr;
  shape_ = !l2 || config_.ways != 4 ? Shape::Any
           : l2->ways() == 8        ? Shape::L1x4L2x8
           : l2->ways() == 16       ? Shape::L1x4L2x16
                                    : Shape::Any;
}

nlohmann::json L1Cache::parameters() const {
  return {{"core", core_},
          {"size_bytes", config_.size_bytes},
          {"ways", config_.ways},
          {"line_bytes", config_.line_bytes},
          {"hit_latency", config_.hit_latency},
          {"mshrs", config_.mshrs},
          {"merge_misses", config_.merge_misses},
          {"ports", config_.ports},
          {"port_cycles", config_.port_cycles}};
}

void L1Cache::warm(uint64_t addr, uint32_t bytes) {
  const uint64_t first = addr >> line_shift_, last = (addr + (bytes ? bytes : 1) - 1) >> line_shift_;
  for (uint64_t line = first; line <= last; ++line)
    if (!level_.warm(line) && l2_) l2_->warm_line(line);
}

uint64_t L1Cache::read_at(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) {
  switch (shape_) {  // the presets' associativities: loops unrolled, no switch per lookup
    case Shape::L1x4L2x8: return read_shaped<4, 8>(addr, bytes, now, slot);
    case Shape::L1x4L2x16: return read_shaped<4, 16>(addr, bytes, now, slot);
    default: return read_shaped<0, 0>(addr, bytes, now, slot);
  }
}

template <uint32_t L2Ways>
__attribute__((always_inline)) inline uint64_t L1Cache::next_level(uint64_t line, uint64_t t) {
  return l2_ ? l2_->read_line_inline<L2Ways>(line, t, core_) : next->read_line(line, t, core_);
}

uint64_t L1Cache::next_level_any(uint64_t line, uint64_t t) {
  switch (shape_) {
    case Shape::L1x4L2x8: return next_level<8>(line, t);
    case Shape::L1x4L2x16: return next_level<16>(line, t);
    default: return next_level<0>(line, t);
  }
}

// Inlined into both of read_shaped()'s calls (the first line's, the loop's).
template <uint32_t L1Ways, uint32_t L2Ways>
__attribute__((always_inline)) inline uint64_t L1Cache::read_line(uint64_t line, uint64_t now, uint32_t slot) {
  const CacheLevel::Access a = level_.access<L1Ways>(line, now);
  if (a.outcome != CacheLevel::Outcome::Miss) {
    if (__builtin_expect(a.ready == kPendingCycle, 0)) wait_for(line, slot, now);  // merge with a pending miss
    return a.ready;
  }
  if (__builtin_expect(a.start == kPendingCycle, 0)) {  // every MSHR waits for a fill not known yet
    level_.uncount_pending_wait(now);
    if (!a.allocated) level_.install<L1Ways>(line, kPendingCycle, now);
    defer_miss(line, slot, now);
    return kPendingCycle;
  }
  // Waits for an MSHR (start > now): with l2_lookups_in_time_order looked up in
  // the L2 when it leaves; else now, stamped with that cycle (its wait is in
  // mshr_stall_cycles). The clock first: one predictable test on the usual path.
  if (__builtin_expect(clock_ != nullptr, 0) && a.start != event_now_)
    return defer_until(line, slot, now, a.start, a.allocated);
  const uint64_t fill = next_level<L2Ways>(line, a.start + level_.hit_latency());
  if (__builtin_expect(a.allocated, 0)) level_.hold_mshr(fill);  // merging off: the line is there, in flight
  else level_.fill<L1Ways>(line, fill, a.start);
  miss_sent(a.start);
  if (fill != kPendingCycle) miss_filled(fill);
  if (__builtin_expect(vcd_ != nullptr, 0)) trace_miss(a.start, fill);
  if (__builtin_expect(fill == kPendingCycle, 0)) wait_for(line, slot, now);
  return fill;
}

template <uint32_t L1Ways, uint32_t L2Ways>
uint64_t L1Cache::read_shaped(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) {
  const uint64_t first = addr >> line_shift_;
  const uint64_t last = (addr + (bytes ? bytes - 1 : 0)) >> line_shift_;
  uint64_t ready = read_line<L1Ways, L2Ways>(first, now, slot);  // a node read: its only line
  uint32_t unknown = 0;
  if (__builtin_expect(ready == kPendingCycle, 0)) ready = 0, unknown = 1;
  for (uint64_t line = first + 1; line <= last; ++line) {
    const uint64_t r = read_line<L1Ways, L2Ways>(line, now, slot);
    if (__builtin_expect(r == kPendingCycle, 0)) ++unknown;
    else if (r > ready) ready = r;
  }
  if (reads_ == 0) first_now_ = now;
  ++reads_;
  bytes_ += bytes;
  if (__builtin_expect(unknown != 0, 0)) return pend_read(slot, unknown, ready);
  if (ready > last_ready_) last_ready_ = ready;
  return ready;
}

void L1Cache::set_tracing(VcdRecorder* vcd) {
  vcd_misses_ = vcd ? vcd->signal(name(), "misses_in_flight") : VcdRecorder::kNoSignal;
  vcd_ = vcd_misses_ == VcdRecorder::kNoSignal ? nullptr : vcd;
}

void L1Cache::trace_miss(uint64_t start, uint64_t fill) {
  vcd_->add(vcd_misses_, start, +1);
  if (fill != kPendingCycle) vcd_->add(vcd_misses_, fill, -1);  // else when line_filled() tells the fill
}

// ---- the pending path: an approximately timed memory behind the L2 ----

void L1Cache::wait_for(uint64_t line, uint32_t slot, uint64_t t) { waiting_.add(line, slot, t); }

void L1Cache::defer_miss(uint64_t line, uint32_t slot, uint64_t t) {
  deferred_.push_back({line, t});
  wait_for(line, slot, t);
}

uint64_t L1Cache::defer_until(uint64_t line, uint32_t slot, uint64_t t, uint64_t start, bool allocated) {
  if (!allocated) level_.install<0>(line, kPendingCycle, t);
  level_.hold_mshr(kPendingCycle);
  send_at(line, start);
  wait_for(line, slot, t);
  return kPendingCycle;
}

void L1Cache::send_at(uint64_t line, uint64_t start) {
  timed_.push_back({start, timed_order_++, line});
  std::push_heap(timed_.begin(), timed_.end(), std::greater<>());
  clock_->request(start);
}

void L1Cache::send_due(uint64_t now) {
  while (!timed_.empty() && timed_.front().cycle <= now) {
    const TimedMiss m = timed_.front();
    std::pop_heap(timed_.begin(), timed_.end(), std::greater<>());
    timed_.pop_back();
    if (vcd_) vcd_->add(vcd_misses_, m.cycle, +1);
    miss_sent(m.cycle);
    const uint64_t t = m.cycle + level_.hit_latency();
    const uint64_t fill = next_level_any(m.line, t);
    if (fill != kPendingCycle) line_filled(m.line, fill);  // answers its waiters (and sends deferred misses)
  }
}

uint64_t L1Cache::pend_read(uint32_t slot, uint32_t lines, uint64_t ready) {
  PendingRead& p = pending_[slot - first_slot_];
  p.lines = lines;
  p.ready = ready;
  return kPendingCycle;
}

void L1Cache::answer(uint32_t slot, uint64_t ready) {
  PendingRead& p = pending_[slot - first_slot_];
  if (ready > p.ready) p.ready = ready;
  if (p.lines == 0 || --p.lines != 0) return;
  if (p.ready > last_ready_) last_ready_ = p.ready;
  done->read_done(slot, p.ready);
}

void L1Cache::line_filled(uint64_t line, uint64_t fill) {
  level_.resolve(line, fill);
  miss_filled(fill);
  if (vcd_) vcd_->add(vcd_misses_, fill, -1);  // the miss's +1 went in when it was sent
  waiting_.fill(line, fill, level_, [this](uint32_t slot, uint64_t ready) { answer(slot, ready); });
  send_deferred();
}

void L1Cache::send_deferred() {
  while (!deferred_.empty() && level_.mshr_free_cycle() != kPendingCycle) {
    const DeferredMiss d = deferred_.front();
    deferred_.pop_front();
    const uint64_t free = level_.mshr_free_cycle();
    const uint64_t start = std::max(free, d.t);
    level_.count_mshr_wait(start - d.t);
    ++misses_sent_late_;
    level_.hold_mshr(kPendingCycle);
    if (clock_) {  // looked up in the L2 when it leaves, as every miss that waited for an MSHR
      send_at(d.line, start);
      continue;
    }
    if (vcd_) vcd_->add(vcd_misses_, start, +1);
    miss_sent(start);
    const uint64_t fill = next_level_any(d.line, start + level_.hit_latency());
    if (fill != kPendingCycle) line_filled(d.line, fill);  // answers its waiters (and sends further deferred misses)
  }
}

}  // namespace vbsim::hw
