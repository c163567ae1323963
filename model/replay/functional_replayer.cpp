#include "replay/functional_replayer.h"

#include "datapath/closest_hit.h"
#include "datapath/testers.h"
#include "exact/oracle.h"

namespace vbsim {

FunctionalReplayer::FunctionalReplayer(const Scene& scene, const Bvh& bvh, const ReplayOptions& options)
    : scene_(scene), bvh_(bvh), opt_(options), filter_(options.method) {
  check_traversal_depth(bvh);
}

EmittedRay FunctionalReplayer::emit(const TraceRay& tr) {
  const EmittedRay er = emit_ray(tr, scene_, opt_, track_parents_ ? &parents_ : nullptr);
  if (track_parents_) parents_[tr.id] = {tr.o, tr.d};
  return er;
}

RayOutcome FunctionalReplayer::replay(const TraceRay& tr) {
  KindStats& ks = stats_.by_kind[static_cast<int>(tr.kind)];
  const EmittedRay er = emit(tr);
  const bool stop_at_any = any_hit(tr, er);
  const uint64_t rejected_before = ks.candidates.rejected;
  Hit hit;
  switch (opt_.tester) {
    case TesterKind::ThreeHalfPlane:
      hit = closest_hit<ThreeHalfPlaneTester>(bvh_, er.ray, filter_, ks.candidates, ks.traversal, stop_at_any);
      break;
    case TesterKind::MollerTrumbore:
      hit = closest_hit<MollerTrumboreTester>(bvh_, er.ray, filter_, ks.candidates, ks.traversal, stop_at_any);
      break;
  }
  return conclude(tr, er, hit, ks.candidates.rejected - rejected_before);
}

RayOutcome FunctionalReplayer::conclude(const TraceRay& tr, const EmittedRay& er, const Hit& hit,
                                        uint64_t rejected) {
  KindStats& ks = stats_.by_kind[static_cast<int>(tr.kind)];
  RayOutcome out;
  out.hit = hit;
  out.rejected = rejected;
  out.reversed = er.reversed;
  // A reversed shadow ray is blocked by anything but the parent's own triangle.
  out.answer = out.hit.prim;
  if (er.reversed && out.hit.prim == tr.parent_prim) out.answer = -1;

  ++ks.rays;
  ks.hits += out.answer >= 0;
  ks.emission_fallbacks += er.emission_fallback;
  if (tr.has_expect) {
    out.scored = true;
    if (verdict_needs_exact(tr, out.answer)) {  // rational numbers only when needed
      const ExactRay intended = intended_ray(tr, scene_, &parents_);
      out.verdict = judge(tr, out.answer, scene_, &intended);
    } else {
      out.verdict = judge(tr, out.answer, scene_, nullptr);
    }
  }
  ++ks.verdicts[static_cast<int>(out.verdict)];
  return out;
}

}  // namespace vbsim
