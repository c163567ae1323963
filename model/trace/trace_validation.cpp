#include "trace/trace_validation.h"

#include <cmath>

#include <fmt/format.h>

#include "trace/incomplete_reasons.h"

namespace vbsim {

namespace {

bool fail(TraceFieldProblem& problem, const char* field, std::string message) {
  problem.field = field;
  problem.message = std::move(message);
  return false;
}

std::string vec_text(Vec3f v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

/// parent_prim / expect.prim: -1 (none) or a triangle index of the scene.
bool check_prim(int32_t prim, int32_t triangle_count, const char* field,
                TraceFieldProblem& problem) {
  if (prim < -1) return fail(problem, field, fmt::format("{} is below -1", prim));
  if (triangle_count >= 0 && prim >= triangle_count)
    return fail(problem, field,
                fmt::format("triangle {} is out of range: the scene has {} triangles (0..{})",
                            prim, triangle_count, triangle_count - 1));
  return true;
}

}  // namespace

bool check_trace_ray(const TraceRay& ray, int32_t triangle_count, TraceFieldProblem& problem) {
  if (ray.id < 0) return fail(problem, "id", fmt::format("{} is negative", ray.id));
  if (ray.parent < -1)
    return fail(problem, "parent", fmt::format("{} is below -1 (-1 means no parent)", ray.parent));
  if (static_cast<int>(ray.kind) >= kRayKindCount)
    return fail(problem, "kind", fmt::format("unknown kind {}", static_cast<int>(ray.kind)));
  if (ray.parent >= 0 && ray.kind == RayKind::Primary)
    return fail(problem, "kind",
                fmt::format("primary (the default), but the ray has parent {}: a camera ray has no parent; give "
                            "the child's kind (reflect, refract, diffuse or shadow)", ray.parent));
  if (!is_finite(ray.o))
    return fail(problem, "o", fmt::format("origin {} is not finite", vec_text(ray.o)));
  if (!is_finite(ray.d))
    return fail(problem, "d", fmt::format("direction {} is not finite", vec_text(ray.d)));
  if (ray.d.x == 0.0f && ray.d.y == 0.0f && ray.d.z == 0.0f)
    return fail(problem, "d", "direction is zero");
  if (!std::isfinite(ray.tmin)) return fail(problem, "tmin", fmt::format("{} is not finite", ray.tmin));
  if (ray.tmin < 0.0f) return fail(problem, "tmin", fmt::format("{} is negative", ray.tmin));
  if (std::isnan(ray.tmax)) return fail(problem, "tmax", "is NaN");
  if (ray.tmax < ray.tmin)
    return fail(problem, "tmax", fmt::format("{} is below tmin {}", ray.tmax, ray.tmin));
  if (!check_prim(ray.parent_prim, triangle_count, "parent_prim", problem)) return false;
  if (ray.has_parent_t && !std::isfinite(ray.parent_t))
    return fail(problem, "parent_t", fmt::format("{} is not finite", ray.parent_t));
  if (ray.has_parent_uv && !(std::isfinite(ray.parent_u) && std::isfinite(ray.parent_v)))
    return fail(problem, "parent_uv",
                fmt::format("[{}, {}] is not finite", ray.parent_u, ray.parent_v));
  if (ray.has_parent_ns && !is_finite(ray.parent_ns))
    return fail(problem, "parent_ns", fmt::format("{} is not finite", vec_text(ray.parent_ns)));
  if (ray.sign != -1 && ray.sign != 0 && ray.sign != 1)
    return fail(problem, "sign", fmt::format("must be 0 or 1, got {}", static_cast<int>(ray.sign)));
  if (ray.has_expect_t && !ray.has_expect)
    return fail(problem, "expect.t", "given without an expect answer");
  if (ray.has_expect) {
    if (!check_prim(ray.expect_prim, triangle_count, "expect.prim", problem)) return false;
    if (ray.has_expect_t) {
      if (ray.expect_prim == -1)
        return fail(problem, "expect.t", "a miss (prim -1) has no hit distance; use null or omit t");
      if (!std::isfinite(ray.expect_t))
        return fail(problem, "expect.t", fmt::format("{} is not finite", ray.expect_t));
    }
  }
  if (ray.has_reference_t && !ray.has_reference)
    return fail(problem, "reference.t", "given without a reference answer");
  if (ray.has_reference) {
    if (ray.reference_prim < kReferenceOccluded)
      return fail(problem, "reference.prim", fmt::format("{} is below -1", ray.reference_prim));
    if (ray.reference_prim >= 0 && !check_prim(ray.reference_prim, triangle_count, "reference.prim", problem))
      return false;
    if (ray.has_reference_t && (ray.reference_prim < 0 || !std::isfinite(ray.reference_t)))
      return fail(problem, "reference.t", "a hit distance needs a hit (prim >= 0) and must be finite");
  }
  if (ray.incomplete & ~kIncompleteKnownBits)
    return fail(problem, "incomplete",
                fmt::format("unknown reason bits 0x{:x}", ray.incomplete & ~kIncompleteKnownBits));
  return true;
}

bool TraceRayValidator::check(const TraceRay& ray, TraceFieldProblem& problem) {
  if (!check_trace_ray(ray, triangle_count_, problem)) return false;
  switch (ids_.insert(ray.id)) {
    case TraceIdSet::Membership::Yes:
      return fail(problem, "id", fmt::format("duplicate id {}", ray.id));
    case TraceIdSet::Membership::Unknown:
      ++ids_not_checked_;
      break;
    case TraceIdSet::Membership::No:
      break;
  }
  return true;
}

}  // namespace vbsim
