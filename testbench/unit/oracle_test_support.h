// Test support for the exact oracle: an independent rational ray/triangle test
// (Cramer's rule on barycentrics, not the edge functions the oracle uses), a
// brute-force closest hit over all triangles, and a small median-split BVH
// builder that produces the documented layout by hand.
#pragma once
#include <algorithm>
#include <numeric>
#include <vector>

#include "exact/exact_geometry.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::test {

inline mpq_class det3(const ExactVec3& a, const ExactVec3& b, const ExactVec3& c) {
  return a.x * (b.y * c.z - b.z * c.y) + a.y * (b.z * c.x - b.x * c.z) + a.z * (b.x * c.y - b.y * c.x);
}

inline ExactVec3 sub(const ExactVec3& a, const ExactVec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

/// Reference hit: solve o + t d = v0 + u (v1 - v0) + v (v2 - v0) by Cramer's
/// rule; hit when the system is regular, u, v >= 0, u + v <= 1 and 0 < t < tmax.
inline ExactHit reference_intersect(const ExactRay& ray, const Triangle& tri) {
  const ExactVec3 v0 = to_exact(tri.v0);
  const ExactVec3 e1 = sub(to_exact(tri.v1), v0), e2 = sub(to_exact(tri.v2), v0);
  const ExactVec3 s = sub(ray.o, v0);
  const ExactVec3 nd{-ray.d.x, -ray.d.y, -ray.d.z};
  ExactHit h;
  const mpq_class m = det3(e1, e2, nd);
  if (m == 0) return h;
  const mpq_class u = det3(s, e2, nd) / m;
  if (u < 0) return h;
  const mpq_class v = det3(e1, s, nd) / m;
  if (v < 0 || u + v > 1) return h;
  const mpq_class t = det3(e1, e2, s) / m;
  if (t <= 0 || (ray.has_tmax && t >= ray.tmax)) return h;
  h.hit = true;
  h.t = t;
  return h;
}

struct ReferenceClosest {
  std::vector<int32_t> ties;  ///< ascending; empty on a miss
  mpq_class t;
};

inline ReferenceClosest reference_closest(const Scene& scene, const ExactRay& ray) {
  ReferenceClosest out;
  for (int32_t p = 0; p < scene.size(); ++p) {
    const ExactHit h = reference_intersect(ray, scene.triangles[static_cast<size_t>(p)]);
    if (!h.hit) continue;
    if (out.ties.empty() || h.t < out.t) {
      out.ties.assign(1, p);
      out.t = h.t;
    } else if (h.t == out.t) {
      out.ties.push_back(p);
    }
  }
  return out;
}

/// Median split on the longest axis of the centroid bounds, `leaf_size` triangles per leaf.
class MedianBvhBuilder {
 public:
  MedianBvhBuilder(const Scene& scene, int leaf_size) : scene_(scene), leaf_size_(leaf_size) {}

  Bvh build() {
    Bvh bvh;
    std::vector<uint32_t> prims(scene_.triangles.size());
    std::iota(prims.begin(), prims.end(), 0u);
    if (prims.empty()) return bvh;
    bvh.root_bounds = bounds(prims, 0, prims.size());
    bvh.root = subtree(bvh, prims, 0, prims.size(), 1);
    return bvh;
  }

 private:
  Vec3f centroid(uint32_t p) const {
    const Triangle& t = scene_.triangles[p];
    return (1.0f / 3.0f) * (t.v0 + t.v1 + t.v2);
  }

  Bounds3f bounds(const std::vector<uint32_t>& prims, size_t begin, size_t end) const {
    Bounds3f box;
    for (size_t i = begin; i < end; ++i) {
      const Triangle& t = scene_.triangles[prims[i]];
      box.extend(t.v0);
      box.extend(t.v1);
      box.extend(t.v2);
    }
    return box;
  }

  // Appends the subtree of prims[begin, end) (nodes in pre-order) and returns its reference.
  BvhRef subtree(Bvh& bvh, std::vector<uint32_t>& prims, size_t begin, size_t end, int depth) {
    bvh.depth = std::max(bvh.depth, depth);
    if (end - begin <= static_cast<size_t>(leaf_size_)) {
      const BvhRef leaf{static_cast<uint32_t>(bvh.tris.size()), static_cast<uint32_t>(end - begin)};
      for (size_t i = begin; i < end; ++i) bvh.tris.push_back({scene_.triangles[prims[i]], prims[i]});
      return leaf;
    }
    const uint32_t index = static_cast<uint32_t>(bvh.nodes.size());
    bvh.nodes.push_back({});
    Bounds3f cbox;
    for (size_t i = begin; i < end; ++i) cbox.extend(centroid(prims[i]));
    const Vec3f ext = cbox.hi - cbox.lo;
    const int axis = max_dimension(ext);
    const size_t mid = (begin + end) / 2;
    std::nth_element(prims.begin() + begin, prims.begin() + mid, prims.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centroid(a)[axis] < centroid(b)[axis]; });
    const BvhRef low = subtree(bvh, prims, begin, mid, depth + 1);
    const BvhRef high = subtree(bvh, prims, mid, end, depth + 1);
    BvhNode& n = bvh.nodes[index];
    n.set_child(0, bounds(prims, begin, mid), low);
    n.set_child(1, bounds(prims, mid, end), high);
    n.axis = static_cast<uint32_t>(axis);
    return {index, 0};
  }

  const Scene& scene_;
  int leaf_size_;
};

/// A valid BVH of one leaf holding every triangle.
inline Bvh single_leaf_bvh(const Scene& scene) { return MedianBvhBuilder(scene, 65535).build(); }

}  // namespace vbsim::test
