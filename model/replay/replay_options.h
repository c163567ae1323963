// ReplayOptions: the effective configuration of one replay (echoed into stats).
#pragma once
#include <string>

#include "datapath/self_intersection_method.h"
#include "datapath/testers.h"
#include "scene/bvh.h"
#include "trace/parent_ray_store.h"

namespace vbsim {

/// Where a child's origin comes from before any method acts (trace spec):
/// the trace's `o` as given, the parent ray's o + parent_t d, or the
/// barycentric point at parent_uv on parent_prim.
enum class HitPointMode { Given, Ray, Barycentric };
const char* hit_point_mode_name(HitPointMode m);
bool parse_hit_point_mode(const std::string& s, HitPointMode& out);

struct ReplayOptions {
  SelfIntersectionMethod method;
  TesterKind tester = TesterKind::ThreeHalfPlane;
  HitPointMode hit_point = HitPointMode::Given;
  bool any_hit_for_shadow = true;  ///< shadow rays stop at the first accepted hit
  /// The tree the trace's scene is built into (replay and render). Closest
  /// hits do not depend on it (docs/hw-model.md, "The BVH"); the work does.
  BvhBuildOptions bvh;
  /// Rays kept for children to look their parent up in (ParentRayStore): a
  /// resource limit, not part of the echoed configuration; a parent further
  /// back is an error, never a silently different answer.
  int64_t parent_window = ParentRayStore::kDefaultWindow;
  /// Score rays marked `incomplete` (their renderer's answer involved what the
  /// trace does not hold); by default they are replayed but left unscored.
  bool score_incomplete = false;
  /// Judge each ray's `reference` answer (the capturing renderer's own, e.g.
  /// Cycles' primitive-ID exclusion on Embree) instead of searching: the
  /// `renderer` row of `vbsim score`. A ray without one is an error. An
  /// occlusion query's wrong "occluded" counts as false_hit: Embree does not
  /// say which triangle occluded it.
  bool reference_answers = false;
};

}  // namespace vbsim
