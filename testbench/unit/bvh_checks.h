// Checks of a built Bvh shared by the BVH builders' tests: every structural
// promise of bvh.h and bvh_builder.cpp (check_structure), and closest hits
// through the tree against a brute-force double-precision search and against
// Embree's own intersector (cross_check).
#pragma once
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "scene/bvh.h"
#include "scene/embree_reference.h"
#include "scene/scene.h"

namespace vbsim::test {

inline const std::string kBunnyPath = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj";

// Random triangles of assorted sizes in the unit cube.
inline Scene random_soup(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-1.0f, 1.0f);
  std::vector<Triangle> tris;
  for (int i = 0; i < count; ++i) {
    const float size = (i % 10 == 0) ? 0.5f : 0.05f;
    const Vec3f c{unit(rng), unit(rng), unit(rng)};
    auto corner = [&] { return c + size * Vec3f{offset(rng), offset(rng), offset(rng)}; };
    const Vec3f a = corner(), b = corner(), d = corner();
    tris.push_back({a, b, d});
  }
  return make_scene(std::move(tris));
}

inline bool contains(const Bounds3f& b, Vec3f p) {
  for (int a = 0; a < 3; ++a)
    if (!(b.lo[a] <= p[a] && p[a] <= b.hi[a])) return false;
  return true;
}

inline bool contains(const Bounds3f& outer, const Bounds3f& inner) {
  for (int a = 0; a < 3; ++a)
    if (!(outer.lo[a] <= inner.lo[a] && inner.hi[a] <= outer.hi[a])) return false;
  return true;
}

inline bool same_box(const Bounds3f& a, const Bounds3f& b) { return a.lo == b.lo && a.hi == b.hi; }

// Where a walk of the tree is: the next node index pre-order must give and the
// next triangle leaf order must give.
struct WalkState {
  uint32_t next_node = 0;
  uint32_t next_tri = 0;
};

// Checks every structural promise of bvh.h and bvh_builder.cpp for the subtree
// `ref` whose box (its parent's child slot, or root_bounds) is `box`; returns
// the recounted depth (levels, leaf included) of the subtree.
inline int check_subtree(const Bvh& bvh, BvhRef ref, const Bounds3f& box, WalkState& walk, std::vector<int>& seen,
                  int max_leaf) {
  if (ref.is_leaf()) {
    CHECK(ref.count <= static_cast<uint32_t>(max_leaf));
    CHECK(ref.index == walk.next_tri);  // triangles are stored in leaf order
    REQUIRE(ref.index + ref.count <= bvh.tris.size());
    Bounds3f exact;
    for (uint32_t i = ref.index; i < ref.index + ref.count; ++i) {
      const BvhTriangle& t = bvh.tris[i];
      REQUIRE(t.prim < seen.size());
      ++seen[t.prim];
      CHECK((contains(box, t.tri.v0) && contains(box, t.tri.v1) && contains(box, t.tri.v2)));
      exact.extend(t.tri.v0);
      exact.extend(t.tri.v1);
      exact.extend(t.tri.v2);
    }
    CHECK(same_box(box, exact));  // tight: exactly the leaf's vertices' bounds
    walk.next_tri += ref.count;
    return 1;
  }
  // Pre-order: a node right after its parent, or after its elder sibling's subtree.
  CHECK(ref.index == walk.next_node);
  REQUIRE(ref.index < bvh.nodes.size());
  ++walk.next_node;
  const BvhNode& n = bvh.nodes[ref.index];
  CHECK(n.axis <= 2);
  const Bounds3f first = n.child_bounds(0), second = n.child_bounds(1);
  CHECK(contains(box, first));
  CHECK(contains(box, second));
  // Tight: the slot's box is exactly the union of the node's two child boxes.
  for (int a = 0; a < 3; ++a) {
    CHECK(box.lo[a] == std::min(first.lo[a], second.lo[a]));
    CHECK(box.hi[a] == std::max(first.hi[a], second.hi[a]));
  }
  const int axis = static_cast<int>(n.axis);
  const double c_first = double(first.lo[axis]) + first.hi[axis];
  const double c_second = double(second.lo[axis]) + second.hi[axis];
  CHECK(c_first <= c_second);  // child 0 on the low side of the split axis
  const int depth_first = check_subtree(bvh, n.child(0), first, walk, seen, max_leaf);
  const int depth_second = check_subtree(bvh, n.child(1), second, walk, seen, max_leaf);
  return 1 + std::max(depth_first, depth_second);
}

inline void check_structure(const Scene& scene, const Bvh& bvh, int max_leaf) {
  REQUIRE(bvh.tris.size() == scene.triangles.size());
  // The root is node 0 unless the whole tree is one leaf (then there are no nodes).
  CHECK(bvh.root.is_leaf() == bvh.nodes.empty());
  if (!bvh.root.is_leaf()) CHECK(bvh.root.index == 0);
  std::vector<int> seen(scene.triangles.size(), 0);
  WalkState walk;
  const int depth = check_subtree(bvh, bvh.root, bvh.root_bounds, walk, seen, max_leaf);
  CHECK(depth == bvh.depth);
  CHECK(walk.next_tri == bvh.tris.size());
  CHECK(walk.next_node == bvh.nodes.size());  // every node reached once, none spare
  CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<long>(seen.size()));
  for (const BvhTriangle& t : bvh.tris) {
    const Triangle& s = scene.triangles[t.prim];
    CHECK((t.tri.v0 == s.v0 && t.tri.v1 == s.v1 && t.tri.v2 == s.v2));
  }
  CHECK(bvh.root_bounds.lo == scene.bounds.lo);
  CHECK(bvh.root_bounds.hi == scene.bounds.hi);
  // Storage promises of the hardware layout.
  CHECK(reinterpret_cast<uintptr_t>(bvh.nodes.data()) % 64 == 0);
}

// ---- Brute-force reference in double -------------------------------------

struct DoubleRay {
  double o[3], d[3];
  double tnear, tfar;
};

// Plain Moller-Trumbore in double without range checks: the ray's plane hit t
// and barycentrics (u, v) of triangle `tri`; false for a ray parallel to it.
inline bool plane_hit(const Triangle& tri, const DoubleRay& r, double& t, double& u, double& v) {
  const double v0[3] = {tri.v0.x, tri.v0.y, tri.v0.z};
  double e1[3], e2[3], s[3];
  for (int a = 0; a < 3; ++a) {
    e1[a] = double(tri.v1[a]) - v0[a];
    e2[a] = double(tri.v2[a]) - v0[a];
    s[a] = r.o[a] - v0[a];
  }
  const double p[3] = {r.d[1] * e2[2] - r.d[2] * e2[1], r.d[2] * e2[0] - r.d[0] * e2[2],
                       r.d[0] * e2[1] - r.d[1] * e2[0]};
  const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (det == 0.0) return false;
  const double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
  v = (r.d[0] * q[0] + r.d[1] * q[1] + r.d[2] * q[2]) / det;
  t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
  return true;
}

constexpr double kMargin = 1e-4;  // conditioning margin (barycentric and relative t)

// Closest hit over a set of candidate triangles, with a flag telling whether
// the answer is well conditioned (robust to float rounding).
struct Closest {
  int32_t prim = -1;
  double t = std::numeric_limits<double>::infinity(), u = 0, v = 0;
  bool well_conditioned = true;
};

template <class Candidates>
inline Closest closest_hit(const DoubleRay& r, const Candidates& candidates) {
  Closest best;
  double second = std::numeric_limits<double>::infinity();
  double nearest_doubtful = std::numeric_limits<double>::infinity();  // near an edge or an end
  for (const auto& [tri, prim] : candidates) {
    double t, u, v;
    if (!plane_hit(tri, r, t, u, v)) continue;
    const double min_bary = std::min({1.0 - u - v, u, v});
    const bool near_end = std::fabs(t - r.tnear) <= kMargin * std::fabs(t) ||
                          (std::isfinite(r.tfar) && std::fabs(t - r.tfar) <= kMargin * r.tfar);
    const bool in_range = t > r.tnear && t < r.tfar;
    if (min_bary > kMargin && in_range && !near_end) {
      if (t < best.t) {
        second = best.t;
        best.prim = static_cast<int32_t>(prim), best.t = t, best.u = u, best.v = v;
      } else {
        second = std::min(second, t);
      }
    } else if (min_bary >= -kMargin && t > r.tnear - kMargin * std::fabs(t) &&
               t < r.tfar * (1 + kMargin)) {
      nearest_doubtful = std::min(nearest_doubtful, t);
    }
  }
  if (best.prim < 0)
    best.well_conditioned = std::isinf(nearest_doubtful);
  else
    best.well_conditioned = second > best.t * (1 + kMargin) && nearest_doubtful > best.t * (1 + kMargin);
  return best;
}

struct Candidate {
  Triangle tri;
  uint32_t prim;
};

// Slab test in double against float bounds, t in [tnear, tfar].
inline bool enters(const Bounds3f& b, const DoubleRay& r) {
  double t0 = r.tnear, t1 = r.tfar;
  for (int a = 0; a < 3; ++a) {
    if (r.d[a] == 0.0) {
      if (r.o[a] < b.lo[a] || r.o[a] > b.hi[a]) return false;
      continue;
    }
    double near = (b.lo[a] - r.o[a]) / r.d[a], far = (b.hi[a] - r.o[a]) / r.d[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 <= t1;
}

// Simple recursive traversal: every triangle in every leaf the ray enters;
// `box` is the box of subtree `ref`.
inline void gather(const Bvh& bvh, BvhRef ref, const Bounds3f& box, const DoubleRay& r, std::vector<Candidate>& out) {
  if (!enters(box, r)) return;
  if (ref.is_leaf()) {
    for (uint32_t i = ref.index; i < ref.index + ref.count; ++i) out.push_back({bvh.tris[i].tri, bvh.tris[i].prim});
    return;
  }
  const BvhNode& n = bvh.nodes[ref.index];
  for (int c = 0; c < 2; ++c) gather(bvh, n.child(c), n.child_bounds(c), r, out);
}

// Random rays from a sphere around the scene toward random points in its box;
// every other ray ends near its target point (finite tfar).
inline std::vector<DoubleRay> random_rays(const Scene& scene, uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  const Vec3f lo = scene.bounds.lo, hi = scene.bounds.hi;
  const double radius = 2.0 * length(hi - lo);
  std::vector<DoubleRay> rays;
  for (int i = 0; i < count; ++i) {
    double dir[3], norm2;
    do {
      for (double& x : dir) x = sym(rng);
      norm2 = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
    } while (norm2 > 1.0 || norm2 < 1e-6);
    DoubleRay r;
    for (int a = 0; a < 3; ++a) {
      const double centre = 0.5 * (double(lo[a]) + hi[a]);
      const double target = lo[a] + unit(rng) * (double(hi[a]) - lo[a]);
      // Float32 origin and direction, as a trace carries them.
      r.o[a] = static_cast<float>(centre + radius * dir[a] / std::sqrt(norm2));
      r.d[a] = static_cast<float>(target - r.o[a]);
    }
    r.tnear = 0.0;
    r.tfar = (i % 2 == 0) ? std::numeric_limits<double>::infinity() : static_cast<float>(0.5 + unit(rng));
    rays.push_back(r);
  }
  return rays;
}

// Returns how many rays were well conditioned (and therefore compared).
inline int cross_check(const Scene& scene, const Bvh& bvh, const EmbreeReference& embree, uint32_t seed, int count,
                int& hits) {
  std::vector<Candidate> all;
  for (size_t k = 0; k < scene.triangles.size(); ++k) all.push_back({scene.triangles[k], uint32_t(k)});
  std::vector<Candidate> gathered;
  int compared = 0;
  hits = 0;
  for (const DoubleRay& r : random_rays(scene, seed, count)) {
    const Closest brute = closest_hit(r, all);
    if (!brute.well_conditioned) continue;
    ++compared;
    hits += brute.prim >= 0;

    gathered.clear();
    gather(bvh, bvh.root, bvh.root_bounds, r, gathered);
    const Closest through_bvh = closest_hit(r, gathered);
    CHECK(through_bvh.prim == brute.prim);

    int32_t prim = -1;
    float t = 0, u = 0, v = 0;
    const Vec3f o{float(r.o[0]), float(r.o[1]), float(r.o[2])};
    const Vec3f d{float(r.d[0]), float(r.d[1]), float(r.d[2])};
    const bool hit = embree.intersect(o, d, float(r.tnear), float(r.tfar), prim, t, u, v);
    CHECK(hit == (brute.prim >= 0));
    CHECK(prim == brute.prim);
    if (hit && prim == brute.prim) {
      CHECK(t == Approx(brute.t).epsilon(1e-5));
      CHECK(u == Approx(brute.u).margin(1e-4));
      CHECK(v == Approx(brute.v).margin(1e-4));
    }
  }
  return compared;
}

}  // namespace vbsim::test
