// Triangle masks: the per-triangle ray-mask bits a trace header declares
// (`triangle_masks`, docs/trace-format.md), set on a loaded scene. A ray sees a
// triangle only when their masks share a bit, as Embree decides with ray masks
// (rtcSetGeometryMask); the candidate filter and the exact oracle apply it.
#pragma once
#include <vector>

#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

/// Gives `scene` the masks of `ranges` (triangles outside every range keep all
/// bits). Throws SceneError naming the header field, the entry and the scene
/// file when a range reaches past the scene's last triangle.
void apply_triangle_masks(Scene& scene, const std::vector<TriangleMaskRange>& ranges);

/// The ranges that give triangle k the mask at masks[k]: one per run of equal
/// masks other than all bits, ascending (the inverse of apply_triangle_masks).
std::vector<TriangleMaskRange> triangle_mask_ranges(const std::vector<uint32_t>& masks);

/// The scene a trace header names, with its transform and triangle masks
/// applied (what every command that replays, scores or checks a trace loads).
Scene load_header_scene(const TraceHeader& header, WorkProgress* progress = nullptr);

}  // namespace vbsim
