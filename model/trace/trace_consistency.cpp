#include "trace/trace_consistency.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "datapath/hit_point.h"

namespace vbsim {

namespace {

std::string vec_text(Vec3f v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

float max_abs(Vec3f v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

/// Largest per-axis difference of two points.
float distance_inf(Vec3f a, Vec3f b) { return max_abs(a - b); }

void add(std::vector<TraceFinding>& out, TraceCheck check, const char* field, std::string message) {
  out.push_back({check, field, std::move(message)});
}

}  // namespace

const char* trace_check_name(TraceCheck check) {
  switch (check) {
    case TraceCheck::ChildBeforeParent: return "child_before_parent";
    case TraceCheck::IdOrder: return "id_order";
    case TraceCheck::ParentData: return "parent_data";
    case TraceCheck::Sign: return "sign";
    case TraceCheck::MissingExpect: return "missing_expect";
  }
  return "unknown";
}

bool trace_check_is_error(TraceCheck check) { return check == TraceCheck::ChildBeforeParent; }

TraceConsistencyChecker::TraceConsistencyChecker(const Options& options)
    : opt_(options), order_(options.window) {}

void TraceConsistencyChecker::check(const TraceRay& ray, int64_t position, const char* position_word,
                                    std::vector<TraceFinding>& out) {
  if (any_ray_ && ray.id <= last_id_)
    add(out, TraceCheck::IdOrder, "id",
        fmt::format("ids out of order: {} follows {} (allowed, but parents are then checked only "
                    "within the last {} rays)", ray.id, last_id_, window()));
  const ParentOrderCheck::Step step = order_.add(ray.id, ray.parent, position);
  if (step.problem)
    add(out, TraceCheck::ChildBeforeParent,
        step.problem.kind == ParentOrderProblem::Kind::ParentArrived ? "id" : "parent",
        step.problem.message(position_word));
  const bool own_order_problem =
      step.problem && step.problem.kind != ParentOrderProblem::Kind::ParentArrived;
  if (ray.parent >= 0 && !own_order_problem) {
    const RecentRay* parent = step.parent_slot >= 0 ? &recent_[static_cast<std::size_t>(step.parent_slot)] : nullptr;
    if (!parent) ++parents_not_checked_;
    check_parent_data(ray, parent, out);
  }
  if (step.slot == recent_.size()) recent_.emplace_back();  // filling: slots come in order 0, 1, 2, ...
  recent_[step.slot] = {ray.o, ray.d, ray.tmin, ray.tmax, ray.kind};
  check_sign(ray, out);
  if (!ray.has_expect)
    add(out, TraceCheck::MissingExpect, "expect",
        "missing: the ray cannot be scored; run `vbsim oracle TRACE -o OUT` to fill in the exact answers");
  last_id_ = ray.id;
  any_ray_ = true;
}

void TraceConsistencyChecker::check_parent_data(const TraceRay& ray, const RecentRay* parent,
                                                std::vector<TraceFinding>& out) const {
  const TraceCheckTolerances& tol = opt_.tolerances;
  if (ray.parent_prim < 0) {
    add(out, TraceCheck::ParentData, "parent_prim",
        fmt::format("missing for a ray with parent {}: the ray is replayed as a camera ray", ray.parent));
    return;
  }
  if (parent) {
    if (parent->kind == RayKind::Shadow)
      add(out, TraceCheck::ParentData, "parent",
          fmt::format("parent {} is a shadow ray, which reports no hit to spawn from", ray.parent));
    if (ray.has_parent_t) {
      if (!(ray.parent_t >= parent->tmin && ray.parent_t <= parent->tmax))
        add(out, TraceCheck::ParentData, "parent_t",
            fmt::format("{} is outside parent {}'s interval [{}, {}]", ray.parent_t, ray.parent,
                        parent->tmin, parent->tmax));
      const Vec3f p = hit_point_ray(parent->o, parent->d, ray.parent_t);
      const float scale = std::max({max_abs(p), max_abs(parent->o), max_abs(ray.parent_t * parent->d), max_abs(ray.o)});
      const float dist = distance_inf(ray.o, p);
      if (dist > tol.point * scale)
        add(out, TraceCheck::ParentData, "o",
            fmt::format("origin {} is {} from parent {}'s hit point {} at parent_t {} (tolerance {})",
                        vec_text(ray.o), dist, ray.parent, vec_text(p), ray.parent_t, tol.point * scale));
    }
  }
  if (!opt_.triangles || ray.parent_prim >= static_cast<int64_t>(opt_.triangles->size())) return;
  const Triangle& tri = (*opt_.triangles)[static_cast<std::size_t>(ray.parent_prim)];
  const float tri_scale = std::max({max_abs(tri.v0), max_abs(tri.v1), max_abs(tri.v2)});
  if (ray.has_parent_uv) {
    const float u = ray.parent_u, v = ray.parent_v;
    if (u < -tol.barycentric || v < -tol.barycentric || u + v > 1.0f + tol.barycentric)
      add(out, TraceCheck::ParentData, "parent_uv",
          fmt::format("[{}, {}] lies outside triangle {} (u, v >= 0 and u + v <= 1)", u, v, ray.parent_prim));
    const Vec3f b = hit_point_barycentric(tri, u, v);
    const float scale = std::max(tri_scale, max_abs(ray.o));
    const float dist = distance_inf(ray.o, b);
    if (dist > tol.point * scale)
      add(out, TraceCheck::ParentData, "parent_uv",
          fmt::format("the point at [{}, {}] on triangle {}, {}, is {} from the origin {} (tolerance {})",
                      u, v, ray.parent_prim, vec_text(b), dist, vec_text(ray.o), tol.point * scale));
  } else if (parent && ray.has_parent_t) {
    // No barycentrics: at least the parent ray must reach the triangle's plane at parent_t.
    const Vec3f p = hit_point_ray(parent->o, parent->d, ray.parent_t);
    const Vec3f n = geometric_normal(tri);
    const float len = length(n);
    if (len > 0.0f && std::isfinite(len)) {
      const float off_plane = std::fabs(dot(p - tri.v0, n)) / len;
      const float scale = std::max({tri_scale, max_abs(p), max_abs(parent->o)});
      if (off_plane > tol.point * scale)
        add(out, TraceCheck::ParentData, "parent_t",
            fmt::format("parent {}'s ray at parent_t {} is {} off the plane of parent_prim {} (tolerance {})",
                        ray.parent, ray.parent_t, off_plane, ray.parent_prim, tol.point * scale));
    }
  }
}

void TraceConsistencyChecker::check_sign(const TraceRay& ray, std::vector<TraceFinding>& out) const {
  if (ray.sign < 0 || ray.parent_prim < 0 || !opt_.triangles ||
      ray.parent_prim >= static_cast<int64_t>(opt_.triangles->size()))
    return;
  const Triangle& tri = (*opt_.triangles)[static_cast<std::size_t>(ray.parent_prim)];
  // In double: the edges of float32 vertices and their products carry (almost)
  // no rounding, so only a dot product near the bound is left undecided.
  const double e1[3] = {double(tri.v1.x) - tri.v0.x, double(tri.v1.y) - tri.v0.y, double(tri.v1.z) - tri.v0.z};
  const double e2[3] = {double(tri.v2.x) - tri.v0.x, double(tri.v2.y) - tri.v0.y, double(tri.v2.z) - tri.v0.z};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double d[3] = {ray.d.x, ray.d.y, ray.d.z};
  const double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
  const auto norm = [](const double* a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); };
  const double bound = opt_.tolerances.sign * norm(d) * norm(e1) * norm(e2);
  if (!(std::fabs(dn) > bound)) return;
  const int expected = dn < 0.0 ? 1 : 0;
  if (ray.sign != expected)
    add(out, TraceCheck::Sign, "sign",
        fmt::format("{} contradicts the geometric normal of parent_prim {}: dot(d, Ng) = {:.6g} {} 0, "
                    "so the sign bit is {}", static_cast<int>(ray.sign), ray.parent_prim, dn,
                    dn < 0.0 ? "<" : ">", expected));
}

}  // namespace vbsim
