// Engine (hw/scheduler/engine.h): fast-forwarding for sampled simulation
// (hw/sampling/sampled_feed.h). A fast-forwarded ray goes through the same
// datapath as a slot's (FunctionalReplayer::emit, a BvhStepper with the
// slots' settings and the built-in units' answers, conclude), so its hit,
// verdict and functional statistics are those of a detailed run; it takes no
// simulated time and no unit, and its reads (nodes, leaves) only warm the tags
// of the caches of the core it would have run on (round-robin over the cores:
// L1 and, for lines absent there, L2; or the object caches). The source reads
// ahead of the rays in flight, so the reads are kept and applied when the
// detailed ray after them is dispatched: the rays before them have started
// (and mostly fetched what they need) by then, as in a full run. Stack refills
// read the slot's spill area, which is not warmed. Nothing here runs in an
// unsampled run.
#pragma once
#include "hw/sampling/sampled_feed.h"
#include "hw/scheduler/engine.h"

namespace vbsim::hw::engine_detail {
namespace {

template <class Tester, class Memory>
void Engine<Tester, Memory>::warm_read(uint32_t core, uint64_t addr, uint32_t bytes) {
  if (L1Cache* l1 = fast_forward_->l1[core]) return l1->warm(addr, bytes);
  if (ObjectCaches* o = fast_forward_->objects[core]) o->warm(addr);
}

template <class Tester, class Memory>
void Engine<Tester, Memory>::apply_warm(uint64_t index) {
  FastForward& ff = *fast_forward_;
  while (ff.applied_runs < ff.runs.size() && ff.runs[ff.applied_runs].first <= index) {
    for (; ff.applied_reads < ff.runs[ff.applied_runs].second; ++ff.applied_reads) {
      const typename FastForward::Read& r = ff.reads[ff.applied_reads];
      warm_read(r.core, r.addr, r.bytes);
    }
    ++ff.applied_runs;
  }
  if (ff.applied_runs == ff.runs.size()) {  // every run applied: the buffers start again (their capacity stays)
    ff.reads.clear();
    ff.runs.clear();
    ff.applied_runs = ff.applied_reads = 0;
    warm_pending_ = false;
  }
}

template <class Tester, class Memory>
void Engine<Tester, Memory>::fast_forward(SampledFeed& feed) {
  if (!fast_forward_) {
    fast_forward_ = std::make_unique<FastForward>(bvh_, replayer_.filter(), static_cast<int>(cfg_.stack_depth));
    fast_forward_->stepper.set_root_box_test(cfg_.root_box_test);
    fast_forward_->stepper.set_pop_culling(cfg_.pop_culling);
    for (const CoreBinding& c : cores_) {
      fast_forward_->l1.push_back(c.core->l1());
      fast_forward_->objects.push_back(dynamic_cast<ObjectCaches*>(c.memory));
    }
  }
  FastForward& ff = *fast_forward_;
  BvhStepper<Tester>& st = ff.stepper;
  const bool warm = feed.warm();
  const uint32_t cores = static_cast<uint32_t>(cores_.size());
  TraceRay tr;
  while (feed.next_fast_forward(tr)) {
    const EmittedRay er = replayer_.emit(tr);
    KindStats& ks = replayer_.stats().by_kind[static_cast<int>(tr.kind)];
    const uint32_t core = ff.next_core;
    ff.next_core = core + 1 == cores ? 0 : core + 1;
    StepRequest r = st.begin(er.ray, replayer_.any_hit(tr, er), ks.candidates, ks.traversal);
    for (bool searching = true; searching;) {
      switch (r.kind) {
        case StepRequest::Node:
          if (warm) ff.reads.push_back({map_.node(r.index), map_.node_bytes, core});
          r = st.node_step();
          break;
        case StepRequest::Leaf:
          if (warm) ff.reads.push_back({map_.triangle(r.index), r.count * BvhAddressMap::kTriangleBytes, core});
          for (uint32_t i = 0; i < r.count; ++i)
            if (st.triangle_step(r.index + i).stop) break;
          r = st.leaf_done();
          break;
        case StepRequest::Refill: r = st.refilled(); break;
        case StepRequest::Done: searching = false; break;
      }
    }
    const RayOutcome out = replayer_.conclude(tr, er, st.hit(), st.rejected());
    feed.fast_forwarded(tr, out, last_handled_);
  }
  // The reads wait for the dispatch of the detailed ray after them: the one
  // the source is reading now, at its next position.
  if (warm && ff.reads.size() > (ff.runs.empty() ? 0 : ff.runs.back().second)) {
    ff.runs.emplace_back(source_.rays_read(), ff.reads.size());
    warm_pending_ = true;
  }
}

}  // namespace
}  // namespace vbsim::hw::engine_detail
