#include "replay/verdict.h"

namespace vbsim {

const char* verdict_name(Verdict v) {
  static constexpr const char* names[kVerdictCount] = {"correct", "self_hit", "false_hit",
                                                       "missed", "unscored"};
  return names[static_cast<int>(v)];
}

bool is_self_hit_prim(const TraceRay& tr, int32_t prim, const Scene& scene) {
  if (tr.parent_prim < 0) return false;
  if (prim == tr.parent_prim) return true;
  return shares_vertex(scene.triangles[prim], scene.triangles[tr.parent_prim]);
}

bool verdict_needs_exact(const TraceRay& tr, int32_t answer) {
  return tr.kind != RayKind::Shadow && answer >= 0 && answer != tr.expect_prim;
}

Verdict judge(const TraceRay& tr, int32_t answer, const Scene& scene, const ExactRay* intended) {
  const int32_t expected = tr.expect_prim;
  const auto wrong_hit = [&] {
    return is_self_hit_prim(tr, answer, scene) ? Verdict::SelfHit : Verdict::FalseHit;
  };
  if (tr.kind == RayKind::Shadow) {
    const bool occluded = answer >= 0, should = expected >= 0;
    if (occluded == should) return Verdict::Correct;
    return occluded ? wrong_hit() : Verdict::Missed;
  }
  if (answer == expected) return Verdict::Correct;
  if (answer < 0) return Verdict::Missed;
  const ExactHit got = exact_intersect(*intended, scene.triangles[answer]);
  if (!got.hit || expected < 0) return wrong_hit();
  const ExactHit want = exact_intersect(*intended, scene.triangles[expected]);
  if (!want.hit) return Verdict::Unscored;  // the expectation contradicts the exact test
  if (got.t == want.t) return Verdict::Correct;  // tied with the exact answer
  return got.t < want.t ? wrong_hit() : Verdict::Missed;
}

}  // namespace vbsim
