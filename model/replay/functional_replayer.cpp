#include "replay/functional_replayer.h"

#include "datapath/closest_hit.h"
#include "datapath/testers.h"
#include "exact/oracle.h"

#include <stdexcept>

#include <fmt/format.h>

namespace vbsim {

RayOutcome conclude_ray(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected,
                        const Scene& scene, bool score_incomplete, KindStats& ks) {
  RayOutcome out;
  out.hit = hit;
  out.rejected = rejected;
  out.reversed = er.reversed;
  // A reversed shadow ray is blocked by anything but the parent's own triangle.
  out.answer = out.hit.prim;
  if (er.reversed && out.hit.prim == tr.parent_prim) out.answer = -1;

  ++ks.rays;
  ks.children += tr.parent_prim >= 0;
  ks.hits += out.answer >= 0;
  ks.emission_fallbacks += er.emission_fallback;
  ks.offset_fallbacks += er.offset_fallback;
  const bool excluded = tr.incomplete != 0 && !score_incomplete;
  ks.incomplete_excluded += excluded;
  ks.incomplete_scored += tr.incomplete != 0 && !excluded && tr.has_expect;
  if (tr.has_expect && !excluded) {
    out.scored = true;
    if (verdict_needs_exact(tr, out.answer)) {  // rational numbers only when needed
      const ExactRay intended = intended_ray(tr, scene, er.parent ? &*er.parent : nullptr);
      out.verdict = judge(tr, out.answer, scene, &intended);
    } else {
      out.verdict = judge(tr, out.answer, scene, nullptr);
    }
  }
  ++ks.verdicts[static_cast<int>(out.verdict)];
  return out;
}

namespace {

/// The renderer's own answer of `tr` as a hit (ReplayOptions::reference_answers).
Hit reference_hit(const TraceRay& tr, const Scene& scene) {
  if (!tr.has_reference)
    throw std::runtime_error(fmt::format(
        "ray {} carries no reference answer (the renderer's own, as a capture's trace holds): the renderer row "
        "needs one on every ray", tr.id));
  Hit hit;
  if (tr.reference_prim >= 0) {
    hit.prim = tr.reference_prim;
    hit.t = tr.has_reference_t ? tr.reference_t : 0.0f;
  } else if (tr.reference_prim == kReferenceOccluded && !scene.triangles.empty()) {
    hit.prim = 0;  // occluded by an unnamed triangle: judged by visibility (a wrong one as false_hit)
  }
  return hit;
}

}  // namespace

RayOutcome replay_one_ray(const TraceRay& tr, const Scene& scene, const Bvh& bvh,
                          const ReplayOptions& opt, const CandidateFilter& filter,
                          const ParentRay* parent, KindStats& ks) {
  const EmittedRay er = emit_ray(tr, scene, opt, parent);
  if (opt.reference_answers) {
    RayOutcome out = conclude_ray(tr, er, reference_hit(tr, scene), 0, scene, opt.score_incomplete, ks);
    if (tr.reference_prim == kReferenceOccluded && out.verdict == Verdict::SelfHit) {
      --ks.verdicts[static_cast<int>(Verdict::SelfHit)];
      ++ks.verdicts[static_cast<int>(Verdict::FalseHit)];
      out.verdict = Verdict::FalseHit;
    }
    return out;
  }
  const bool any_hit = search_stops_at_any_hit(opt, tr, er);
  const uint64_t rejected_before = ks.candidates.rejected;
  Hit hit;
  switch (opt.tester) {
    case TesterKind::ThreeHalfPlane:
      hit = closest_hit<ThreeHalfPlaneTester>(bvh, er.ray, filter, ks.candidates, ks.traversal, any_hit);
      break;
    case TesterKind::MollerTrumbore:
      hit = closest_hit<MollerTrumboreTester>(bvh, er.ray, filter, ks.candidates, ks.traversal, any_hit);
      break;
    case TesterKind::PbrtWatertight:
      hit = closest_hit<PbrtWatertightTester>(bvh, er.ray, filter, ks.candidates, ks.traversal, any_hit);
      break;
  }
  return conclude_ray(tr, er, hit, ks.candidates.rejected - rejected_before, scene, opt.score_incomplete, ks);
}

FunctionalReplayer::FunctionalReplayer(const Scene& scene, const Bvh& bvh, const ReplayOptions& options)
    : scene_(scene),
      bvh_(bvh),
      opt_(options),
      filter_(options.method, scene.mask_table()),
      parents_(options.parent_window) {
  check_traversal_depth(bvh);
}

RayOutcome FunctionalReplayer::replay(const TraceRay& tr) {
  KindStats& ks = stats_.by_kind[static_cast<int>(tr.kind)];
  const ParentRay* parent = track_parents_ ? parents_.lookup(tr.parent) : nullptr;
  const RayOutcome out = replay_one_ray(tr, scene_, bvh_, opt_, filter_, parent, ks);
  if (track_parents_) parents_.add(tr.id, tr.o, tr.d);
  return out;
}

EmittedRay FunctionalReplayer::emit(const TraceRay& tr) {
  const EmittedRay er = emit_ray(tr, scene_, opt_, track_parents_ ? parents_.lookup(tr.parent) : nullptr);
  if (track_parents_) parents_.add(tr.id, tr.o, tr.d);
  return er;
}

RayOutcome FunctionalReplayer::conclude(const TraceRay& tr, const EmittedRay& er, const Hit& hit,
                                        uint64_t rejected) {
  return conclude_ray(tr, er, hit, rejected, scene_, opt_.score_incomplete, stats_.by_kind[static_cast<int>(tr.kind)]);
}

}  // namespace vbsim
