#include "hw/source/ray_source.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "datapath/method_costs.h"

namespace vbsim::hw {

namespace {

/// Emission-time method operations acting on `tr` (each costs emission_op_cycles).
uint32_t emission_ops(const SelfIntersectionMethod& m, const TraceRay& tr) {
  const bool child = tr.parent_prim >= 0, shadow = tr.kind == RayKind::Shadow;
  uint32_t ops = m.tmin;
  if (child) ops += m.offset_normal + m.offset_direction + m.offset_adaptive + m.offset_errbound;
  if (shadow && child) ops += m.shading_position || m.shading_position_always;
  if (shadow) ops += m.reverse_shadow;
  return ops;
}

bool same_origin(const Vec3f& a, const Vec3f& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The smallest power of two above `n` (at least 2): places are then a mask, not a division.
uint64_t power_of_two_above(uint64_t n) {
  uint64_t c = 2;
  while (c <= n) c *= 2;
  return c;
}

}  // namespace

RaySource::RaySource(sc_core::sc_module_name name, const HwConfig& config, FunctionalReplayer& replayer)
    : sc_core::sc_module(name), config_(config.source), shader_(config.shader), replayer_(replayer),
      lanes_count_(std::max<uint32_t>(1, config.source.rays_per_cycle)),
      window_(config.source.window), capacity_(static_cast<uint32_t>(power_of_two_above(window_))),
      parent_window_(static_cast<uint64_t>(std::max<int64_t>(1, replayer.options().parent_window))),
      history_capacity_(power_of_two_above(parent_window_ + window_ + 1)),
      independent_missing_(config.source.missing_parents == MissingParents::Independent), lanes_(lanes_count_),
      pipe_capacity_(static_cast<uint32_t>(power_of_two_above(uint64_t{config.source.emission_depth} + 2))),
      pipe_(size_t{lanes_count_} * pipe_capacity_), places_event_base_(2 * lanes_count_), ready_(window_ + 1) {
  ring_.reserve(std::min<uint32_t>(capacity_, 4096));
  // The emission unit's operations per kind of ray; the sign bit keeps its own
  // sign_bit_cycles, so the validity bit's dot product is not the unit's.
  SelfIntersectionMethod arithmetic = replayer.options().method;
  arithmetic.validity_bit = false;
  for (const bool child : {false, true})
    for (const bool shadow : {false, true})
      unit_ops_[child][shadow] = static_cast<uint32_t>(emission_ops_for(arithmetic, child, shadow).total());
  finish_.reserve(std::min<uint64_t>(history_capacity_, uint64_t{1} << 20));  // address space only until rays arrive
  if (shader_.cores > 0) {
    pool_ = std::make_unique<ShaderCorePool>(shader_);
    uint32_t most = 0;  // the most operations a ray of this method runs there
    for (const auto& by_kind : unit_ops_) most = std::max({most, by_kind[0], by_kind[1]});
    const uint64_t latency = (most + shader_.ops_per_lane_cycle - 1) / shader_.ops_per_lane_cycle + shader_.pipeline_latency;
    if (most > 0) shade_ahead_ = lanes_count_ * (1 + latency / std::max<uint32_t>(1, config_.issue_interval));
  }
  const SourceCounters& c = counters_;
  const EmissionCounters& e = emission_;
  declare_stat("rays", "rays", "rays read from the trace and emitted", c.rays);
  declare_stat("busy_cycles", "lane-cycles",
               "cycles the lanes spent emitting (issue interval, sign bits, emission operations, bundle calls)",
               c.busy_cycles);
  declare_stat("sign_bits_computed", "rays", "child rays whose parent sign bit the source computed",
               c.sign_bits_computed);
  declare_stat("emission_ops", "operations", "emission-time method operations (offsets, tmin, ...)",
               c.emission_ops);
  declare_stat("emission_unit_ops", "operations", "arithmetic operations through the emission unit (none without one)",
               c.emission_unit_ops);
  declare_stat("no_free_slot_cycles", "lane-cycles", "cycles emitted rays waited because every slot was busy",
               c.no_free_slot_cycles);
  declare_stat("children_waited", "rays", "rays that entered the buffer before their parent's result",
               e.children_waited);
  declare_stat("dependency_wait_cycles", "ray-cycles",
               "cycles from entering the buffer to ready, summed over the rays that waited for a parent",
               e.dependency_wait_cycles);
  declare_stat("parents_not_found", "rays",
               "child rays whose parent is not among the parent window's rays before them, replayed as "
               "independent (missing_parents \"independent\")",
               e.parents_not_found);
  declare_stat("lane_idle_dependency_cycles", "lane-cycles",
               "cycles a lane had nothing ready while buffered rays waited for their parents",
               e.lane_idle_dependency_cycles);
  declare_stat("lane_idle_window_cycles", "lane-cycles",
               "cycles a lane had nothing ready because the window was full of unfinished rays",
               e.lane_idle_window_cycles);
  declare_stat("lane_idle_shader_cycles", "lane-cycles",
               "cycles a lane had nothing ready because a closed-loop shader had no ray until a result arrived, "
               "or rays were still on the shader cores (hw.shader.cores)",
               e.lane_idle_shader_cycles);
  declare_stat("bundles", "calls", "bundle calls of the emission API", e.bundles);
  declare_stat("bundled_rays", "rays", "rays emitted by bundle calls", e.bundled_rays);
}

nlohmann::json RaySource::parameters() const {
  nlohmann::json j = {{"rays_per_cycle", lanes_count_},
          {"window", window_},
          {"dependencies", config_.dependencies},
          {"parent_window", parent_window_},
          {"missing_parents", missing_parents_name(config_.missing_parents)},
          {"shading_latency_cycles", shader_.latency_cycles},
          {"issue_interval", config_.issue_interval},
          {"sign_bit_cycles", config_.sign_bit_cycles},
          {"emission_op_cycles", config_.emission_op_cycles},
          {"emission_width", config_.emission_width},
          {"emission_depth", config_.emission_depth},
          {"bundles", config_.bundles},
          {"method", replayer_.options().method.name()}};
  if (shader_.any_by_kind()) j["shading_latency_by_kind"] = shader_config_json(shader_)["latency_by_kind"];
  return j;
}

uint64_t RaySource::emission_cycles(const TraceRay& tr, bool& through_unit) {
  uint64_t cost = config_.issue_interval;
  if (tr.sign < 0 && tr.parent_prim >= 0) {
    cost += config_.sign_bit_cycles;
    ++counters_.sign_bits_computed;
  }
  const uint32_t ops = emission_ops(replayer_.options().method, tr);
  counters_.emission_ops += ops;
  if (pool_) return cost;  // the method's arithmetic ran on the shader cores (make_ready)
  if (config_.emission_width == 0) {
    cost += uint64_t{ops} * config_.emission_op_cycles;
    return cost;
  }
  const uint32_t n = unit_ops_[tr.parent_prim >= 0][tr.kind == RayKind::Shadow];
  counters_.emission_unit_ops += n;
  if (n) {
    cost += (n + config_.emission_width - 1) / config_.emission_width;
    through_unit = true;
  }
  return cost;
}

void RaySource::set_feed(RayFeed feed) {
  feed_ = nullptr;  // no feed: the trace has ended
  if (feed)
    feed_ = [trace = std::move(feed)](TraceRay& tr, uint64_t) {
      return trace(tr) ? ShaderAnswer::Ray : ShaderAnswer::Finished;
    };
}

void RaySource::start(SourceHost& host, uint64_t at) {
  host_ = &host;
  for (Lane& l : lanes_) l.idle_since = at;
  start_idle_lanes(at);
}

bool RaySource::read_one(uint64_t now) {
  if (ended_ || next_ > base_ + window_) return false;
  if (ring_.size() < capacity_ && next_ == ring_.size()) ring_.emplace_back();  // grows to its capacity as rays come
  if (finish_.size() < history_capacity_ && next_ == finish_.size()) finish_.emplace_back();
  Entry& e = at_pos(next_);
  if (free_staged_.empty()) {
    free_staged_.push_back(static_cast<uint32_t>(staged_.size()));
    staged_.emplace_back();
  }
  const uint32_t place = free_staged_.back();
  const ShaderAnswer answer = feed_ ? feed_(staged_[place].tr, now) : ShaderAnswer::Finished;
  later_ = answer == ShaderAnswer::Later;
  if (answer != ShaderAnswer::Ray) {
    ended_ = answer == ShaderAnswer::Finished;
    return false;
  }
  free_staged_.pop_back();
  e.staged = place;
  enter(next_, now);
  ++next_;
  return true;
}

void RaySource::fill_until_ready(uint64_t now) {
  if (shade_ahead_ == 0) {  // every ray is ready as it enters, or once its parent's result is shaded
    while (ready_.empty() && read_one(now)) {
    }
    return;
  }
  // With shader cores a ray read now reaches the lanes their latency later:
  // read as far ahead as the lanes take rays in that time (shade_ahead_), and
  // no further, so that the buffer holds what a lane needs, not the window.
  while ((ready_.empty() || ready_.size() + shading_ < shade_ahead_) && read_one(now)) {
  }
}

void RaySource::enter(uint64_t pos, uint64_t now) {
  Entry& e = at_pos(pos);
  SourceRay& ray = record(e);
  const TraceRay& tr = ray.tr;
  ray.index = e.index = pos;
  ray.er = replayer_.emit(tr);  // in trace order: a parent before its children
  e.entered = ray.entered = now;
  e.first_child = e.next_sibling = kNone;
  e.state = State::Ready;
  ++counters_.rays;
  note_position(tr.id, pos);  // the ray leaving the history goes first
  finish_at(pos) = Finish{kUnfinished, tr.id, kNone, tr.kind};
  if (config_.dependencies) {
    if (!unresolved_.empty()) {
      const auto child = unresolved_.find(tr.id);
      if (child != unresolved_.end() && child->second.pos + parent_window_ >= pos)
        fail(pos, "id",
             fmt::format("ray {} is the parent of ray {} (trace position {}), which comes before it: a trace "
                         "replayed with dependencies lists every parent before its children (--deps off replays "
                         "it as independent rays)",
                         tr.id, child->second.id, child->second.pos));
    }
    if (tr.parent >= 0) {
      uint64_t parent_pos = 0;
      const ParentAt where = find_parent(tr.parent, pos, parent_pos);
      if (where != ParentAt::Found) {
        if (__builtin_expect(parents_fast_forwarded_on_, 0)) ++parents_fast_forwarded_;
        else parent_not_found(tr, pos, where);
      } else if (const Finish& p = finish_at(parent_pos);
                 p.cycle == kUnfinished || p.cycle + shader_.latency_for(p.kind) > now) {
        return wait_for_parent(pos, parent_pos);
      }
    }
  }
  make_ready(pos, now);
}

void RaySource::wait_for_parent(uint64_t pos, uint64_t parent_pos) {
  Entry& e = at_pos(pos);
  e.state = State::Waiting;
  e.parent = parent_pos;
  ++waiting_count_;
  ++emission_.children_waited;
  Finish& parent = finish_at(parent_pos);
  if (parent.cycle == kUnfinished) {
    // In the buffer (every position before base_ has finished): ready with the
    // parent's other children once its result has been shaded (on_finish).
    Entry& p = at_pos(parent_pos);
    e.next_sibling = p.first_child;
    p.first_child = place_of(pos);
  } else if (parent.group != kNone) {  // joins the children its parent's event makes ready
    Entry& head = ring_[parent.group];
    e.next_sibling = head.next_sibling;
    head.next_sibling = place_of(pos);
  } else {  // the group's event at its first child's place: it stays while the child waits
    e.next_sibling = kNone;
    parent.group = place_of(pos);
    host_->schedule_source_event(places_event_base_ + parent.group, parent.cycle + shader_.latency_for(parent.kind));
  }
}

void RaySource::fail(uint64_t pos, const std::string& field, const std::string& what) const {
  throw std::runtime_error(locate_ ? locate_(field, what) : fmt::format("trace position {}: {}", pos, what));
}

void RaySource::parent_not_found(const TraceRay& tr, uint64_t pos, ParentAt where) {
  const std::string what =
      where == ParentAt::TooFar
          ? fmt::format("parent {} lies more than {} rays before ray {} (the parent window: --parent-window)",
                        tr.parent, parent_window_, tr.id)
          : fmt::format("parent {} of ray {} is not among the {} rays before it (not in the trace, later in it, or "
                        "further back than --parent-window)",
                        tr.parent, tr.id, parent_window_);
  if (!independent_missing_)
    fail(pos, "parent",
         what + ": a child cannot wait for it; --missing-parents independent replays such rays as independent, "
                "--deps off every ray");
  if (emission_.parents_not_found++ == 0)
    first_not_found_ = locate_ ? locate_("parent", what) : fmt::format("trace position {}: {}", pos, what);
  if (unresolved_.size() > 4 * size_t{window_} + 64)  // forget the children too far behind to matter
    for (auto u = unresolved_.begin(); u != unresolved_.end();)
      u = u->second.pos + parent_window_ < pos ? unresolved_.erase(u) : std::next(u);
  unresolved_.emplace(tr.parent, Unresolved{pos, tr.id});
}

RaySource::ParentAt RaySource::find_parent(int64_t id, uint64_t pos, uint64_t& found) const {
  uint64_t p = 0;
  if (ids_dense_) {
    p = static_cast<uint64_t>(id) - static_cast<uint64_t>(first_id_);  // an id below the first wraps high
    if (p >= pos) return ParentAt::NotBefore;
  } else if (!position_of_->find(id, p) || p >= pos) {
    return ParentAt::NotBefore;  // (or dropped from the table: further back)
  }
  if (pos - p > parent_window_) return ParentAt::TooFar;
  found = p;
  return ParentAt::Found;
}

void RaySource::note_position(int64_t id, uint64_t pos) {
  if (ids_dense_) {
    if (pos == 0) first_id_ = id;
    if (static_cast<uint64_t>(id) - static_cast<uint64_t>(first_id_) == pos) return;
    // The first id off the sequence: the table takes over the rays the history holds.
    ids_dense_ = false;
    position_of_ = std::make_unique<IdPositionMap>(static_cast<uint32_t>(
        std::min<uint64_t>(parent_window_ + 1, uint64_t{1} << 31)));
    for (uint64_t p = pos > parent_window_ ? pos - parent_window_ : 0; p < pos; ++p)
      position_of_->set(finish_at(p).id, p);
  }
  if (pos > parent_window_) {  // the ray parent_window_ + 1 back leaves the history
    const uint64_t old = pos - parent_window_ - 1;
    position_of_->erase(finish_at(old).id, old);
  }
  uint64_t seen = 0;
  if (position_of_->find(id, seen))
    fail(pos, "id",
         fmt::format("duplicate id {}: the ray at trace position {} has it too (a ray id names one ray)", id, seen));
  position_of_->set(id, pos);
}

void RaySource::make_ready(uint64_t pos, uint64_t cycle) {
  Entry& e = at_pos(pos);
  if (e.state == State::Waiting) --waiting_count_;
  SourceRay& ray = record(e);
  ray.ready = cycle;
  emission_.dependency_wait_cycles += cycle - e.entered;
  if (pool_) {  // the method's emission-time arithmetic first, on the shader cores
    const uint32_t n = unit_ops_[ray.tr.parent_prim >= 0][ray.tr.kind == RayKind::Shadow];
    if (n) {
      e.state = State::Shading;
      ++shading_;
      host_->schedule_source_event(places_event_base_ + place_of(pos), pool_->run(cycle, n));
      return;
    }
  }
  e.state = State::Ready;
  ready_.push(pos);
}

void RaySource::on_event(uint32_t id, uint64_t at) {
  if (id < lanes_count_) {  // a lane's occupancy ends: its call's rays leave unless the unit's depth delays them
    lanes_[id].emitting = false;
    drain(id, at);
    if (!lanes_[id].holding) try_start(id, at);
    return;
  }
  if (id < places_event_base_) {  // the pipe's head leaves the emission unit's depth
    const uint32_t lane = id - lanes_count_;
    lanes_[lane].out_pending = false;
    drain(lane, at);
    if (!lanes_[lane].emitting && !lanes_[lane].holding) try_start(lane, at);
    return;
  }
  // The children of one parent, from the first child at this place, are
  // ready: its result has been shaded.
  const uint32_t head = id - places_event_base_;
  if (ring_[head].state == State::Shading) {  // its arithmetic on the shader cores is done
    ring_[head].state = State::Ready;
    --shading_;
    ready_.push(ring_[head].index);
    return start_idle_lanes(at);
  }
  Finish& parent = finish_at(ring_[head].parent);
  if (parent.group == head) parent.group = kNone;
  for (uint32_t c = head; c != kNone;) {
    Entry& child = ring_[c];
    c = child.next_sibling;
    make_ready(child.index, at);
  }
  start_idle_lanes(at);
}

void RaySource::on_finish(uint64_t index, uint64_t at) {
  Entry& e = at_pos(index);
  e.state = State::Finished;
  Finish& f = finish_at(index);
  f.cycle = at;
  if (e.first_child != kNone) {  // its waiting children: one group, its event at the first child's place
    f.group = e.first_child;
    host_->schedule_source_event(places_event_base_ + f.group, at + shader_.latency_for(f.kind));
    e.first_child = kNone;
  }
  const uint64_t old_base = base_;
  while (base_ < next_ && at_pos(base_).state == State::Finished) ++base_;
  // The window moved, or a closed-loop shader may have made rays of the result: idle lanes read further.
  if (base_ != old_base || later_) start_idle_lanes(at);
}

void RaySource::on_slot_free(uint64_t at) {
  while (!held_.empty()) {
    const uint32_t lane_id = held_.front();
    if (!send(lane_id, at)) return;
    held_.pop_front();
    Lane& lane = lanes_[lane_id];
    counters_.no_free_slot_cycles += at - lane.held_since;
    lane.holding = false;
    lane.head = (lane.head + 1) & (pipe_capacity_ - 1);
    --lane.size;
    drain(lane_id, at);  // the calls behind it that are done by now
    if (!lane.emitting && !lane.holding) try_start(lane_id, at);
  }
}

bool RaySource::send(uint32_t lane_id, uint64_t now) {
  Emission& call = pipe_at(lane_id, 0);
  while (call.sent < call.count) {
    Entry& e = at_pos(call.first + call.sent);
    if (!host_->try_dispatch(record(e), now)) return false;
    e.state = State::InFlight;
    free_staged_.push_back(e.staged);  // the slot holds its own copy now
    e.staged = kNone;
    ++call.sent;
  }
  return true;
}

void RaySource::drain(uint32_t lane_id, uint64_t now) {
  Lane& lane = lanes_[lane_id];
  while (lane.size > 0 && !lane.holding) {
    Emission& call = pipe_at(lane_id, 0);
    if (call.done > now) {
      if (!lane.out_pending) {
        lane.out_pending = true;
        host_->schedule_source_event(lanes_count_ + lane_id, call.done);
      }
      return;
    }
    if (call.sent == 0)
      for (uint32_t k = 0; k < call.count; ++k) at_pos(call.first + k).state = State::Held;
    if (!send(lane_id, now)) {
      lane.holding = true;
      lane.held_since = now;
      held_.push_back(lane_id);
      return;
    }
    lane.head = (lane.head + 1) & (pipe_capacity_ - 1);
    --lane.size;
  }
}

void RaySource::start_idle_lanes(uint64_t now) {
  for (uint32_t l = 0; l < lanes_count_; ++l) {
    Lane& lane = lanes_[l];
    if (lane.emitting || lane.holding || lane.size == pipe_capacity_) continue;  // busy, holding, or its pipe full
    try_start(l, now);
    if (!lanes_[l].emitting) return;  // nothing more to emit now
  }
}

void RaySource::try_start(uint32_t lane_id, uint64_t now) {
  Lane& lane = lanes_[lane_id];
  if (lane.size == pipe_capacity_) return;  // its pipe is full: it takes a ray when the head leaves
  fill_until_ready(now);  // reads ahead only as far as the first ready ray
  if (ready_.empty()) return go_idle(lane_id, now);
  account_idle(lane, now);
  lane.idle = Idle::None;
  const uint64_t first = ready_.top();
  ready_.pop();
  const TraceRay& head = record(at_pos(first)).tr;
  bool through_unit = false;
  uint64_t cost = emission_cycles(head, through_unit);
  // Copies: reading further may move the staged records.
  const int64_t head_parent = head.parent;
  const Vec3f head_origin = head.o;
  uint32_t count = 1;
  if (config_.bundles) {
    while (count < config_.bundle_max) {
      if (next_ == first + count) read_one(now);  // the bundle may go on in the rays not read yet
      if (ready_.empty() || ready_.top() != first + count) break;
      const TraceRay& next = record(at_pos(first + count)).tr;
      if (next.parent < 0 || next.parent != head_parent || !same_origin(next.o, head_origin)) break;
      ready_.pop();
      cost += emission_cycles(next, through_unit);
      ++count;
    }
    if (count > 1) {
      cost += config_.bundle_cycles;
      ++emission_.bundles;
      emission_.bundled_rays += count;
    }
  }
  for (uint32_t k = 0; k < count; ++k) {
    Entry& e = at_pos(first + k);
    e.state = State::Emitting;
    record(e).emitted = now;
  }
  counters_.busy_cycles += cost;
  lane.emitting = true;
  // Its rays leave when the lane is free again, or the unit's depth later; never before the calls ahead of it.
  uint64_t done = now + cost + (through_unit ? config_.emission_depth : 0);
  if (lane.size > 0) done = std::max(done, pipe_at(lane_id, lane.size - 1).done);
  pipe_at(lane_id, lane.size) = Emission{first, count, 0, done};
  ++lane.size;
  host_->schedule_source_event(lane_id, now + cost);
}

void RaySource::account_idle(Lane& lane, uint64_t now) {
  if (lane.idle == Idle::Dependency) emission_.lane_idle_dependency_cycles += now - lane.idle_since;
  if (lane.idle == Idle::Window) emission_.lane_idle_window_cycles += now - lane.idle_since;
  if (lane.idle == Idle::Shader) emission_.lane_idle_shader_cycles += now - lane.idle_since;
  lane.idle_since = now;
}

void RaySource::go_idle(uint32_t lane_id, uint64_t now) {
  Lane& lane = lanes_[lane_id];
  account_idle(lane, now);  // a lane idle already: its time so far, under the reason it had
  lane.idle = waiting_count_                 ? Idle::Dependency
              : shading_ > 0                 ? Idle::Shader  // rays on the shader cores
              : ended_                       ? Idle::End
              : next_ > base_ + window_      ? Idle::Window
                                             : Idle::Shader;
  lane.idle_since = now;
}

std::string RaySource::buffer_report() const {
  std::ostringstream out;
  size_t waiting = 0, ready = 0, shading = 0;
  for (uint64_t p = base_; p < next_; ++p) {
    waiting += at_pos(p).state == State::Waiting;
    ready += at_pos(p).state == State::Ready;
    shading += at_pos(p).state == State::Shading;
  }
  out << "  ray source: " << next_ - base_ << " rays in the buffer from trace position " << base_ << " (" << waiting
      << " waiting for a parent, " << shading << " on the shader cores, " << ready << " ready), " << held_.size()
      << " lanes holding a ray, trace "
      << (ended_ ? "ended" : later_ ? "not ended (the shader has no ray until a result arrives)" : "not ended")
      << "\n";
  return out.str();
}

}  // namespace vbsim::hw
