// ScenarioTraceBuilder: what the failure-case scenarios share. It holds a
// scene, shoots camera rays at it with the float three-half-plane tester (no
// self-intersection method, as a renderer's first hit would be found), turns
// each hit into a spawn point computed as a renderer computes it (float32 ray
// equation or float32 barycentric interpolation, setting `hitpoint`), and
// emits children from it with the parent data filled (parent id, parent_prim,
// parent_t, parent_uv, sign), so that every offset method can be applied at
// replay and the oracle finds the intended origin from the parent ray.
// Rays are recorded in emission order: a parent always precedes its children.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "datapath/dvec3.h"
#include "gen/scenario.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim {

/// How a renderer computes a hit point from its tester's answer.
enum class HitPointRule { Ray, Barycentric };

/// Reads the setting `hitpoint` (`ray` or `barycentric`); `fallback` when unset.
HitPointRule read_hit_point_rule(const ScenarioSettings& s, HitPointRule fallback);
const char* hit_point_rule_name(HitPointRule r);

/// Where a camera ray met the scene, as a renderer would spawn from it.
struct SpawnPoint {
  int64_t parent_id = -1;  ///< the camera ray's id
  int32_t prim = -1;       ///< triangle hit; -1: the camera ray missed
  float t = 0, u = 0, v = 0;
  Vec3f p;                 ///< the renderer's hit point (rule of the builder)
  Vec3f incoming;          ///< the camera ray's direction
  bool hit() const { return prim >= 0; }
};

class ScenarioTraceBuilder {
 public:
  ScenarioTraceBuilder(std::vector<Triangle> triangles, HitPointRule rule);
  const Scene& scene() const { return scene_; }

  /// Records a camera ray from `o` with direction `d` and returns its first hit.
  SpawnPoint shoot(Vec3f o, Vec3f d);
  /// Records a child of `s` leaving from s.p along `d` with interval (0, tmax).
  void child(const SpawnPoint& s, RayKind kind, Vec3f d,
             float tmax = std::numeric_limits<float>::infinity());

  size_t ray_count() const { return rays_.size(); }
  /// The case: the builder's triangles and rays (the builder is left empty).
  ScenarioCase take_case(std::string name, std::string description);

 private:
  Scene scene_;
  Bvh bvh_;
  HitPointRule rule_;
  std::vector<TraceRay> rays_;
};

/// Unit geometric normal of `tri` in double precision (from its float vertices).
DVec3 unit_normal(const Triangle& tri);
/// A unit vector perpendicular to the unit vector `n`.
DVec3 any_perpendicular(DVec3 n);
/// `count` values from lo to hi, equally spaced on a log scale (lo when count is 1).
std::vector<double> log_spaced(double lo, double hi, int64_t count);

/// The items of a comma-list setting (an empty item is an error naming the key).
std::vector<std::string> setting_list(const ScenarioSettings& s, const char* key, const std::string& fallback);

/// Throws naming `--set key` unless lo <= v <= hi.
void require_setting_range(const char* key, double v, double lo, double hi);

}  // namespace vbsim
