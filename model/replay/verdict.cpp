#include "replay/verdict.h"

#include "exact/certified_filter.h"

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
  return tr.kind != RayKind::Shadow && answer >= 0 && tr.expect_prim >= 0 && answer != tr.expect_prim;
}

namespace {

/// Where triangle `tri` meets the intended ray: decided by the certified filter
/// when it can (an interval holding the exact t), in rationals otherwise.
struct Crossing {
  bool hit = false;
  bool exact = false;      ///< t_exact holds the value; else [lo, hi] encloses it
  double lo = 0, hi = 0;
  mpq_class t_exact;
};

Crossing cross(const FilterRay& fr, const ExactRay& ray, const Triangle& tri) {
  Crossing c;
  if (fr.usable) {
    const FilterVerdict v = filter_triangle(fr, tri, c.lo, c.hi);
    if (v == FilterVerdict::Miss) return c;
    if (v == FilterVerdict::Hit) {
      c.hit = true;
      return c;
    }
  }
  ExactHit h = exact_intersect(ray, tri);
  c.hit = h.hit;
  c.exact = true;
  c.t_exact = std::move(h.t);
  return c;
}

/// -1, 0, +1 as a's t is below, equal to or above b's (both hit).
int compare_t(Crossing& a, Crossing& b, const ExactRay& ray, const Triangle& ta, const Triangle& tb) {
  if (!a.exact && !b.exact) {
    if (a.hi < b.lo) return -1;
    if (a.lo > b.hi) return 1;
  }
  if (!a.exact) a.t_exact = exact_intersect(ray, ta).t, a.exact = true;
  if (!b.exact) b.t_exact = exact_intersect(ray, tb).t, b.exact = true;
  return cmp(a.t_exact, b.t_exact) < 0 ? -1 : (a.t_exact == b.t_exact ? 0 : 1);
}

}  // namespace

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
  if (expected < 0) return wrong_hit();  // any hit where the exact answer is a miss
  const FilterRay fr = make_filter_ray(*intended);
  const Triangle& ta = scene.triangles[answer];
  const Triangle& te = scene.triangles[expected];
  Crossing got = cross(fr, *intended, ta);
  if (!got.hit) return wrong_hit();  // a triangle the intended ray does not meet
  Crossing want = cross(fr, *intended, te);
  if (!want.hit) return Verdict::Unscored;  // the expectation contradicts the exact test
  const int order = compare_t(got, want, *intended, ta, te);
  if (order == 0) return Verdict::Correct;  // tied with the exact answer
  return order < 0 ? wrong_hit() : Verdict::Missed;
}

}  // namespace vbsim
