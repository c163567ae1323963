// Oracle: closest exact hit by a conservative BVH traversal. Every triangle the
// traversal reaches is decided by the certified filter, or in rationals where
// the filter is not certain; among the certain hits, only those whose t interval
// reaches below the best upper bound can be (or tie with) the closest, and only
// those get an exact t.
#include "exact/oracle.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "exact/certified_filter.h"
#include "exact/exact_plane.h"
#include "exact/rational_rounding.h"

namespace vbsim {

namespace {

struct Candidate {
  int32_t prim;
  double t_lo, t_hi;  // enclosure of the exact t
  int32_t exact;      // index of its exact t in Workspace::exact_t, -1 when not computed
};

// Per-thread buffers reused from ray to ray.
struct Workspace {
  std::vector<Candidate> candidates;
  std::vector<mpq_class> exact_t;
  size_t exact_used = 0;
  std::vector<std::pair<BvhRef, double>> stack;  // subtree, lower bound of its entry t

  mpq_class& next_exact() {
    if (exact_used == exact_t.size()) exact_t.emplace_back();
    return exact_t[exact_used++];
  }
};
thread_local Workspace workspace;

bool box_contains(const Bounds3f& b, Vec3f p) {
  for (int a = 0; a < 3; ++a)
    if (!(b.lo[a] <= p[a] && p[a] <= b.hi[a])) return false;
  return true;
}


[[noreturn]] void bad_bvh(const std::string& where, const std::string& what) {
  throw std::invalid_argument("Oracle: BVH " + where + ": " + what);
}

std::string node_name(uint32_t node) { return "node " + std::to_string(node); }

// The traversal skips a subtree only when its box misses the ray, so it is
// exact only if each triangle sits in one leaf inside every box above it: the
// root's box and each child slot's box on its way down. (A child's box need
// not lie inside its parent's: a low-precision box rounded outward may not,
// scene/bvh_precision.h; each triangle is checked against the intersection of
// the boxes above it.)
void check_coverage(const Scene& scene, const Bvh& bvh) {
  if (scene.size() == 0) return;  // every answer is a miss; the BVH is not read
  if (bvh.tris.empty()) throw std::invalid_argument("Oracle: empty BVH for a non-empty scene");
  std::vector<uint8_t> node_seen(bvh.nodes.size(), 0), prim_seen(scene.triangles.size(), 0);
  struct Pending {
    BvhRef ref;
    Bounds3f box;  // the intersection of the boxes the traversal tests before entering `ref`
    int64_t parent;  // the node whose child `ref` is (-1: the root), and which child: for messages
    int child;
    std::string where() const {
      return parent < 0 ? "root" : node_name(static_cast<uint32_t>(parent)) + " child " + std::to_string(child);
    }
  };
  std::vector<Pending> todo{{bvh.root, bvh.root_bounds, -1, 0}};
  while (!todo.empty()) {
    const Pending p = todo.back();
    todo.pop_back();
    if (!p.ref.is_leaf()) {
      const uint32_t i = p.ref.index;
      if (i >= bvh.nodes.size()) bad_bvh(p.where(), "node index " + std::to_string(i) + " out of range");
      if (node_seen[i]++) bad_bvh(node_name(i), "reached twice");
      const BvhNode& n = bvh.nodes[i];
      for (int c = 0; c < 2; ++c) {
        const Bounds3f b = n.child_bounds(c);
        Bounds3f inside;  // what a ray must have met of both boxes to reach the child
        for (int a = 0; a < 3; ++a) {
          inside.lo[a] = std::max(p.box.lo[a], b.lo[a]);
          inside.hi[a] = std::min(p.box.hi[a], b.hi[a]);
        }
        todo.push_back({n.child(c), inside, static_cast<int64_t>(i), c});
      }
      continue;
    }
    if (size_t(p.ref.index) + p.ref.count > bvh.tris.size()) bad_bvh(p.where(), "triangle range out of range");
    for (uint32_t j = p.ref.index; j < p.ref.index + p.ref.count; ++j) {
      const uint32_t prim = bvh.tris[j].prim;
      if (prim >= scene.triangles.size()) bad_bvh(p.where(), "prim " + std::to_string(prim) + " out of range");
      if (prim_seen[prim]++) bad_bvh(p.where(), "prim " + std::to_string(prim) + " in two leaves");
      const Triangle& t = scene.triangles[prim];
      if (!box_contains(p.box, t.v0) || !box_contains(p.box, t.v1) || !box_contains(p.box, t.v2))
        bad_bvh(p.where(), "box, or a box above it, does not enclose prim " + std::to_string(prim));
    }
  }
  for (size_t p = 0; p < prim_seen.size(); ++p)
    if (!prim_seen[p]) throw std::invalid_argument("Oracle: BVH misses prim " + std::to_string(p));
}

// The filter's slab test on a box.
bool filter_bounds(const FilterRay& fr, const Bounds3f& b, double t_limit, double& t_near) {
  const float lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  return filter_box(fr, lo, hi, t_limit, t_near);
}

// Records an exact hit t (already in ws.exact_t[slot]) as a candidate.
void add_exact(Workspace& ws, int32_t prim, double& best_hi) {
  const int32_t slot = static_cast<int32_t>(ws.exact_used - 1);
  const mpq_class& t = ws.exact_t[static_cast<size_t>(slot)];
  const double lo = round_down_double(t), hi = round_up_double(t);
  if (lo > best_hi) return;
  ws.candidates.push_back({prim, lo, hi, slot});
  best_hi = std::min(best_hi, hi);
}

void test_triangle(const ExactRay& ray, const FilterRay& fr, const Triangle& tri, int32_t prim,
                   Workspace& ws, double& best_hi) {
  double lo = 0, hi = 0;
  switch (filter_triangle(fr, tri, lo, hi)) {
    case FilterVerdict::Miss:
      return;
    case FilterVerdict::Hit:
      if (lo > best_hi) return;
      ws.candidates.push_back({prim, lo, hi, -1});
      best_hi = std::min(best_hi, hi);
      return;
    case FilterVerdict::PlaneOnly:
      if (exact_plane_crossing(ray, tri, ws.next_exact())) add_exact(ws, prim, best_hi);
      else --ws.exact_used;
      return;
    case FilterVerdict::Unknown: {
      ExactHit h = exact_intersect(ray, tri);
      if (!h.hit) return;
      ws.next_exact().swap(h.t);
      add_exact(ws, prim, best_hi);
      return;
    }
  }
}

/// Whether the ray's mask lets it see triangle `prim` (the trace's ray masks).
bool sees(const Scene& scene, const ExactRay& ray, int32_t prim) {
  const uint32_t tri = scene.triangle_masks.empty() ? 0xffffffffu : scene.triangle_masks[static_cast<size_t>(prim)];
  return (tri & ray.mask) != 0;
}

void traverse(const ExactRay& ray, const FilterRay& fr, const Scene& scene, const Bvh& bvh,
              Workspace& ws, double& best_hi) {
  double tn = 0;
  if (!filter_bounds(fr, bvh.root_bounds, best_hi, tn)) return;
  ws.stack.clear();
  ws.stack.push_back({bvh.root, tn});
  while (!ws.stack.empty()) {
    const auto [ref, entry] = ws.stack.back();
    ws.stack.pop_back();
    if (entry > best_hi) continue;
    if (ref.is_leaf()) {
      for (uint32_t j = ref.index; j < ref.index + ref.count; ++j) {
        const int32_t prim = static_cast<int32_t>(bvh.tris[j].prim);
        if (!sees(scene, ray, prim)) continue;
        test_triangle(ray, fr, scene.triangles[static_cast<size_t>(prim)], prim, ws, best_hi);
      }
      continue;
    }
    const BvhNode& n = bvh.nodes[ref.index];
    double near[2];
    bool hit[2];
    for (int k = 0; k < 2; ++k) hit[k] = filter_bounds(fr, n.child_bounds(k), best_hi, near[k]);
    const int first = hit[0] && hit[1] ? (near[1] < near[0] ? 1 : 0) : (hit[0] ? 0 : 1);
    if (hit[1 - first]) ws.stack.push_back({n.child(1 - first), near[1 - first]});
    if (hit[first]) ws.stack.push_back({n.child(first), near[first]});
  }
}

// Every triangle at the smallest exact t, ascending, into `ties`, and that t.
// False on a miss.
bool find_closest(const Scene& scene, const Bvh& bvh, const ExactRay& ray,
                  std::vector<int32_t>& ties, mpq_class& t_min) {
  ties.clear();
  if (scene.size() == 0) return false;
  Workspace& ws = workspace;
  ws.candidates.clear();
  ws.exact_used = 0;
  const FilterRay fr = make_filter_ray(ray);
  double best_hi = fr.tmax_hi;
  if (fr.usable) {
    traverse(ray, fr, scene, bvh, ws, best_hi);
  } else {  // the filter has no proven bound for this ray: every triangle in rationals
    for (int32_t p = 0; p < scene.size(); ++p) {
      if (!sees(scene, ray, p)) continue;
      ExactHit h = exact_intersect(ray, scene.triangles[static_cast<size_t>(p)]);
      if (!h.hit) continue;
      ws.next_exact().swap(h.t);
      add_exact(ws, p, best_hi);
    }
  }
  // Only candidates that can reach down to best_hi can be, or tie with, the closest.
  int32_t best = -1;  // index into ws.exact_t (which may grow, so no pointers)
  for (Candidate& c : ws.candidates) {
    if (c.t_lo > best_hi) continue;
    if (c.exact < 0) {
      if (!exact_plane_crossing(ray, scene.triangles[static_cast<size_t>(c.prim)], ws.next_exact()))
        throw std::logic_error("Oracle: filter certified a hit on prim " + std::to_string(c.prim) +
                               " that the exact test rejects");
      c.exact = static_cast<int32_t>(ws.exact_used - 1);
    }
    const int order = best < 0 ? -1 : cmp(ws.exact_t[size_t(c.exact)], ws.exact_t[size_t(best)]);
    if (order < 0) {
      best = c.exact;
      ties.assign(1, c.prim);
    } else if (order == 0) {
      ties.push_back(c.prim);
    }
  }
  if (best < 0) return false;
  t_min = ws.exact_t[size_t(best)];
  std::sort(ties.begin(), ties.end());
  return true;
}

}  // namespace

Oracle::Oracle(const Scene& scene, const Bvh& bvh) : scene_(scene), bvh_(bvh) {
  check_coverage(scene, bvh);
}

OracleAnswer Oracle::answer(const ExactRay& ray) const {
  thread_local std::vector<int32_t> ties;
  OracleAnswer out;
  if (!find_closest(scene_, bvh_, ray, ties, out.t_exact)) return out;
  out.prim = ties.front();
  out.t = round_to_nearest_double(out.t_exact);
  return out;
}

std::vector<int32_t> Oracle::closest_ties(const ExactRay& ray) const {
  std::vector<int32_t> ties;
  mpq_class t;
  find_closest(scene_, bvh_, ray, ties, t);
  return ties;
}

}  // namespace vbsim
