// Oracle: the exact answer of the trace spec for each ray (intended origin,
// open lower end, ties), computed with rational arithmetic where floating point
// cannot decide. Traversal of the BVH is conservative: no candidate is skipped.
#pragma once
#include <unordered_map>
#include <vector>

#include "exact/exact_geometry.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/parent_ray_store.h"
#include "trace/trace_record.h"

namespace vbsim {

struct OracleAnswer {
  int32_t prim = -1;     ///< -1: miss
  double t = 0.0;        ///< exact t rounded to nearest double (valid when prim >= 0)
  mpq_class t_exact;     ///< exact t (valid when prim >= 0)
};


/// Intended ray of a trace ray (spec "The exact answer", step 1 and 2).
/// `parent`: the ray `ray.parent` when the trace gave it before `ray`, else
/// null (then parent_uv, then the projection of o is used).
ExactRay intended_ray(const TraceRay& ray, const Scene& scene, const ParentRay* parent);

class Oracle {
 public:
  /// Checks that `bvh` covers `scene` (every triangle in exactly one leaf, boxes
  /// nested and enclosing their triangles); throws std::invalid_argument if not.
  Oracle(const Scene& scene, const Bvh& bvh);
  /// Closest exact hit of the intended ray; for ties, the smallest prim id.
  OracleAnswer answer(const ExactRay& ray) const;
  /// Every triangle at the exact smallest t (ascending ids); empty on a miss.
  std::vector<int32_t> closest_ties(const ExactRay& ray) const;

 private:
  const Scene& scene_;
  const Bvh& bvh_;
};

}  // namespace vbsim
