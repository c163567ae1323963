#include "capture/parent_linker.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "datapath/hit_point.h"

namespace vbsim::capture {

namespace {

struct Vec3d {
  double x, y, z;
};
Vec3d to_d(Vec3f v) { return {v.x, v.y, v.z}; }
double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d sub(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d scale(double s, Vec3d a) { return {s * a.x, s * a.y, s * a.z}; }
double max_abs(Vec3d a) { return std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}); }
Vec3d unit(Vec3d a) {
  const double len = std::sqrt(dot(a, a));
  return len > 0.0 ? scale(1.0 / len, a) : Vec3d{0, 0, 0};
}

/// Ng = (v1 - v0) x (v2 - v0) in double, normalised (zero for a degenerate triangle).
Vec3d unit_normal(const Triangle& t) {
  const Vec3d e1 = sub(to_d(t.v1), to_d(t.v0)), e2 = sub(to_d(t.v2), to_d(t.v0));
  return unit({e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x});
}

/// Distance from x to the next float32 up, for x >= 0 (the smallest normal spacing below FLT_MIN).
double ulp_of(double x) {
  const float f = std::max(static_cast<float>(x), 1.17549435e-38f);
  return static_cast<double>(std::nextafter(f, INFINITY)) - f;
}

Vec3f org_of(const RawRay& r) { return {r.org[0], r.org[1], r.org[2]}; }
Vec3f dir_of(const RawRay& r) { return {r.dir[0], r.dir[1], r.dir[2]}; }

bool is_hit(const RawRay& r) {
  return r.op == static_cast<uint16_t>(RawOp::Intersect) && r.geom != kInvalidId;  // triangle_hit maps instances
}

}  // namespace

void LinkCounts::add(const LinkCounts& o) {
  at_hit_point += o.at_hit_point;
  rejected_primitive += o.rejected_primitive;
  normal_offset += o.normal_offset;
  unlinked_intersect += o.unlinked_intersect;
  unlinked_occluded += o.unlinked_occluded;
  max_offset = std::max(max_offset, o.max_offset);
  for (int k = 0; k < kRayKindCount; ++k) by_kind[k] += o.by_kind[k];
}

ParentLinker::Candidate ParentLinker::candidate(std::size_t index, const RawRay& hit, int64_t triangle,
                                                const Triangle& tri) const {
  Candidate c;
  c.index = index;
  c.triangle = triangle;
  c.point = hit_point_ray(org_of(hit), dir_of(hit), hit.hit_t);  // as the application computes it
  const Vec3d n = unit_normal(tri);
  c.normal[0] = n.x, c.normal[1] = n.y, c.normal[2] = n.z;
  c.size = std::max(max_abs(to_d(c.point)), max_abs(to_d(hit.hit_t * dir_of(hit))));
  c.scale = std::max({c.size, max_abs(to_d(tri.v0)), max_abs(to_d(tri.v1)), max_abs(to_d(tri.v2))});
  return c;
}

bool ParentLinker::matches(const Candidate& c, const RawRay& child, RayLink& out) const {
  const Vec3d disp = sub(to_d(org_of(child)), to_d(c.point));
  const double d = max_abs(disp);
  const double tol = rules_.ulps * ulp_of(std::max(c.scale, max_abs(to_d(org_of(child)))));
  if (d <= tol) {
    out.tier = LinkTier::AtHitPoint;
    out.offset = 0.0;
    return true;
  }
  if (d > tol + rules_.normal_offset * c.size) return false;  // too far whichever way it points
  const Vec3d n{c.normal[0], c.normal[1], c.normal[2]};
  const double along = dot(disp, n);
  const Vec3d across = sub(disp, scale(along, n));
  if (max_abs(across) > tol || std::fabs(along) > rules_.normal_offset * c.size) return false;
  out.tier = LinkTier::NormalOffset;
  out.offset = c.size > 0.0 ? std::fabs(along) / c.size : 0.0;
  return true;
}

bool ParentLinker::matches_rejected(const Candidate& c, const RawRay& hit, const RawRay& child) const {
  if (!filters_rejected_hit(child, hit)) return false;
  const double d = max_abs(sub(to_d(org_of(child)), to_d(c.point)));
  return d <= rules_.rejected_ulps * ulp_of(std::max(c.scale, max_abs(to_d(org_of(child)))));
}

bool ParentLinker::origin_matches(const RawRay& parent, const Triangle& tri, const RawRay& child, RayLink& out) const {
  return matches(candidate(0, parent, -1, tri), child, out);
}

RayKind ParentLinker::infer_kind(const RawRay& parent, const Triangle& tri, const RawRay& child) const {
  if (std::isfinite(child.tfar) && child.tfar < std::numeric_limits<float>::max()) return RayKind::Shadow;
  const Vec3d n = unit_normal(tri);
  const Vec3d din = unit(to_d(dir_of(parent))), dout = unit(to_d(dir_of(child)));
  const double a = dot(din, n), b = dot(dout, n);
  if (a * b > 0.0) return RayKind::Refract;  // continues to the far side of the surface
  const Vec3d mirror = sub(din, scale(2.0 * a, n));
  const Vec3d miss = sub(dout, mirror);
  // |dout - mirror| is 2 sin(angle / 2) between two unit vectors.
  return std::sqrt(dot(miss, miss)) <= 2.0 * std::sin(rules_.mirror_radians / 2.0) ? RayKind::Reflect
                                                                                      : RayKind::Diffuse;
}

std::vector<RayLink> ParentLinker::link(const RawRay* rays, std::size_t n, const std::vector<bool>& eligible,
                                        LinkCounts& counts) const {
  std::vector<RayLink> links(n);
  std::deque<Candidate> recent;  // newest at the back, at most rules_.history
  for (std::size_t i = 0; i < n; ++i) {
    if (!eligible[i]) continue;
    const RawRay& r = rays[i];
    const bool occluded = r.op == static_cast<uint16_t>(RawOp::Occluded);
    RayLink& l = links[i];
    // The newest matching hit; among them, for a ray whose filters rejected one
    // primitive, the newest on that primitive (two coplanar surfaces give two
    // hits at one point: the renderer's exclusion names the one it left).
    // Failing all, a hit on that primitive within rejected_ulps.
    auto adopt = [&](const Candidate& c, LinkTier tier, double offset) {
      l.parent = static_cast<int64_t>(c.index);
      l.tier = tier;
      l.offset = offset;
      l.kind = occluded ? RayKind::Shadow
                        : infer_kind(rays[c.index], scene_.triangles()[static_cast<std::size_t>(c.triangle)], r);
    };
    const bool rejected = (r.flags & kRawFilterRejected) != 0;
    const Candidate* chosen = nullptr;
    RayLink how;
    for (auto it = recent.rbegin(); it != recent.rend(); ++it) {
      RayLink m;
      if (!matches(*it, r, m)) continue;
      const bool named = rejected && filters_rejected_hit(r, rays[it->index]);
      if (!chosen || named) chosen = &*it, how = m;
      if (named || !rejected) break;
    }
    if (chosen) {
      adopt(*chosen, how.tier, how.offset);
    } else if (rejected) {
      for (auto it = recent.rbegin(); it != recent.rend(); ++it)
        if (matches_rejected(*it, rays[it->index], r)) {
          adopt(*it, LinkTier::RejectedPrimitive, 0.0);
          break;
        }
    }
    if (l.parent < 0) {
      l.tier = LinkTier::None;
      l.kind = occluded ? RayKind::Shadow : RayKind::Primary;
      ++(occluded ? counts.unlinked_occluded : counts.unlinked_intersect);
    } else if (l.tier == LinkTier::AtHitPoint) {
      ++counts.at_hit_point;
    } else if (l.tier == LinkTier::RejectedPrimitive) {
      ++counts.rejected_primitive;
    } else {
      ++counts.normal_offset;
      counts.max_offset = std::max(counts.max_offset, l.offset);
    }
    ++counts.by_kind[static_cast<int>(l.kind)];
    if (is_hit(r) && l.kind != RayKind::Shadow) {  // a visibility query spawns nothing
      const int64_t tri = scene_.triangle_hit(r).triangle;
      if (tri >= 0) {
        recent.push_back(candidate(i, r, tri, scene_.triangles()[static_cast<std::size_t>(tri)]));
        if (recent.size() > rules_.history) recent.pop_front();
      }
    }
  }
  return links;
}

}  // namespace vbsim::capture
