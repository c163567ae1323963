// Verdict of one answer against the exact answer, as the trace spec defines it.
// Exact: whenever the answer is not the expected triangle, the answered and the
// expected triangles are intersected with the intended ray in rational arithmetic,
// so ties and "nearer / farther" are decided without rounding.
#pragma once
#include <cstdint>

#include "exact/exact_geometry.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

enum class Verdict : uint8_t { Correct = 0, SelfHit = 1, FalseHit = 2, Missed = 3, Unscored = 4 };
constexpr int kVerdictCount = 5;
const char* verdict_name(Verdict v);  ///< "correct", "self_hit", ...

/// True when judging `answer_prim` needs the exact intended ray: a non-shadow
/// ray that hit something other than the expected triangle.
bool verdict_needs_exact(const TraceRay& tr, int32_t answer_prim);

/// Verdict for a ray whose method answered `answer_prim` (-1: miss; for shadow
/// rays: any triangle >= 0 means "occluded"). Precondition: tr.has_expect, and
/// `intended` (the ray's intended ray) is not null when verdict_needs_exact().
/// Unscored when `expect` names a triangle the intended ray does not meet (an
/// inconsistent trace).
Verdict judge(const TraceRay& tr, int32_t answer_prim, const Scene& scene,
              const ExactRay* intended);

/// True when a wrong nearer hit on `prim` counts as a self hit: prim is the
/// parent triangle or shares a vertex position with it.
bool is_self_hit_prim(const TraceRay& tr, int32_t prim, const Scene& scene);

}  // namespace vbsim
