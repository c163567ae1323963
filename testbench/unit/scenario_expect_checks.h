// Independent checks of a generated trace's `expect` fields: a sample of rays
// is re-answered by brute force over every triangle in rational arithmetic
// (Cramer's rule, oracle_test_support.h), on the scene loaded exactly as a
// replay loads it (with the header's transform).
#pragma once
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "exact/expected_answers.h"
#include "oracle_test_support.h"
#include "scene/scene.h"
#include "trace/trace_file.h"

namespace vbsim::test {

/// Checks every `stride`-th ray of `trace`; returns how many were checked.
inline int check_expects_brute_force(const std::string& trace, int stride) {
  auto source = open_trace(trace);
  const TraceHeader& h = source->header();
  const Scene scene = load_scene(h.scene_path, h.transform);
  std::vector<TraceRay> rays;
  TraceRay tr;
  while (source->next(tr)) rays.push_back(tr);
  const ParentRays parents = collect_parent_rays(rays);
  int checked = 0;
  for (size_t i = 0; i < rays.size(); i += static_cast<size_t>(stride)) {
    const TraceRay& r = rays[i];
    REQUIRE(r.has_expect);
    const ReferenceClosest ref = reference_closest(scene, intended_ray(r, scene, find_parent(parents, r.parent)));
    INFO(trace << " ray " << r.id << " expect " << r.expect_prim);
    if (ref.ties.empty()) {
      CHECK(r.expect_prim == -1);
    } else if (r.kind == RayKind::Shadow) {
      CHECK(r.expect_prim >= 0);  // occluded; any occluder will do
    } else {
      CHECK(std::count(ref.ties.begin(), ref.ties.end(), r.expect_prim) == 1);
    }
    ++checked;
  }
  return checked;
}

}  // namespace vbsim::test
