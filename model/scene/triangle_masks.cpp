#include "scene/triangle_masks.h"

#include <algorithm>

#include <fmt/format.h>

namespace vbsim {

void apply_triangle_masks(Scene& scene, const std::vector<TriangleMaskRange>& ranges) {
  scene.triangle_masks.clear();
  const uint64_t n = scene.triangles.size();
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const TriangleMaskRange& r = ranges[i];
    if (uint64_t{r.first} + r.count > n)
      throw SceneError(fmt::format("trace header field 'triangle_masks': entry {} covers triangles {} to {}, but "
                                   "the scene {} holds {} (0 to {})",
                                   i, r.first, uint64_t{r.first} + r.count - 1, scene.source, n, n - 1));
    if (r.mask == kAllMaskBits) continue;
    if (scene.triangle_masks.empty()) scene.triangle_masks.assign(n, kAllMaskBits);
    std::fill_n(scene.triangle_masks.begin() + r.first, r.count, r.mask);
  }
}

std::vector<TriangleMaskRange> triangle_mask_ranges(const std::vector<uint32_t>& masks) {
  std::vector<TriangleMaskRange> out;
  for (std::size_t k = 0; k < masks.size();) {
    std::size_t end = k + 1;
    while (end < masks.size() && masks[end] == masks[k]) ++end;
    if (masks[k] != kAllMaskBits)
      out.push_back({static_cast<uint32_t>(k), static_cast<uint32_t>(end - k), masks[k]});
    k = end;
  }
  return out;
}

Scene load_header_scene(const TraceHeader& header, WorkProgress* progress) {
  Scene scene = load_scene(header.scene_path, header.transform, progress);
  if (header.triangle_masks) apply_triangle_masks(scene, *header.triangle_masks);
  return scene;
}

}  // namespace vbsim
