// Ray emission: turns one trace ray into the ray record the accelerator tests,
// as the patent's ray-emission API would: the origin (given, or recomputed from
// the parent's data), the emission-time methods (shading position, offsets,
// tmin, reverse shadow) and the parent sign bit (computed when the trace omits it).
#pragma once
#include <cstdint>
#include <optional>

#include "datapath/ray.h"
#include "replay/replay_options.h"
#include "scene/scene.h"
#include "trace/parent_ray_store.h"
#include "trace/trace_record.h"

namespace vbsim {

struct EmittedRay {
  Ray ray;
  bool reversed = false;        ///< reverse-shadow: traced from the light back
  bool emission_fallback = false;  ///< a step needed parent data the ray lacks and was skipped
  /// The parent ray emission was given (absent: not in the trace before this
  /// ray); the verdict's intended origin uses it again after the search.
  std::optional<ParentRay> parent;
  /// An offset or shading position could not follow its reference's float
  /// arithmetic (a degenerate normal; origin_offsets.h): it took the double
  /// normal or left the origin as it was.
  bool offset_fallback = false;
};

/// Parent sign bit of the trace spec: the given `sign`, else dot(d, Ng(parent_prim)) < 0
/// (0 for a camera ray). Precondition: parent_prim is in range.
uint8_t parent_sign_bit(const TraceRay& tr, const Scene& scene);

/// The ray the accelerator receives for `tr` under `opt`. `parent`: the ray
/// `tr.parent` when the trace gave it before `tr`, else null.
EmittedRay emit_ray(const TraceRay& tr, const Scene& scene, const ReplayOptions& opt,
                    const ParentRay* parent);

}  // namespace vbsim
