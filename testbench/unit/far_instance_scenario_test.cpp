// The `far-instance` scenario: the trace carries the translation, the scene a
// replay loads is the mesh moved in float32, the expectations hold by brute
// force, and at 2^20 fixed offsets and tmin self-hit while the adaptive offset
// of Ray Tracing Gems ch. 6 does not (but skips the mesh instead).
#include <catch2/catch.hpp>

#include "gen/far_instance_scenario.h"
#include "scenario_expect_checks.h"
#include "scenario_test_support.h"
#include "scene/scene_transform.h"

using namespace vbsim;

TEST_CASE("far-instance traces carry the translation and the replayed scene is the moved mesh", "[scenario][far-instance]") {
  const auto g = test::generate_scenario("far-instance", 12, 1, {{"k", "20"}});
  REQUIRE(g.traces.size() == 1);
  auto source = open_trace(g.traces[0]);
  const TraceHeader& h = source->header();
  REQUIRE(h.transform.has_value());
  CHECK(*h.transform == far_translation(20));
  CHECK((*h.transform)[3] == 1048576.0f);
  // Every vertex of the replayed scene is the file's vertex plus 2^20, rounded to float32.
  const Scene moved = load_scene(h.scene_path, h.transform);
  const Scene plain = load_scene(h.scene_path);
  REQUIRE(moved.size() == plain.size());
  for (int32_t i = 0; i < plain.size(); i += 97) {
    const Vec3f p = plain.triangles[i].v1, q = moved.triangles[i].v1;
    CHECK(q.x == static_cast<float>(double(p.x) + 1048576.0));
    CHECK(q.z == static_cast<float>(double(p.z) + 1048576.0));
  }
  CHECK(test::check_expects_brute_force(g.traces[0], 3) == 15);
}

TEST_CASE("far-instance at 2^20: fixed offsets and tmin self-hit, the adaptive offset does not", "[scenario][far-instance]") {
  // 20 camera paths of depth 2 (seed 1) at k = 20, where a float32 coordinate's
  // ulp is 1/8 and the bunny (about 3 units) is resolved to 1/8 of a unit.
  const auto g = test::generate_scenario("far-instance", 20, 1, {{"k", "20"}});
  const test::VerdictCounts normal = test::total_counts(test::replay_traces(g.traces, "offset-normal"));
  const test::VerdictCounts tmin = test::total_counts(test::replay_traces(g.traces, "tmin"));
  const test::VerdictCounts adaptive = test::total_counts(test::replay_traces(g.traces, "offset-adaptive"));
  const test::VerdictCounts vb = test::total_counts(test::replay_traces(g.traces, "validity-bit"));
  INFO("rays " << normal.rays);
  // Hit points rounded by 1/16 on average: a 1e-4 offset or tmin is far too small.
  CHECK(normal.self_hit == 22);  // of 64 rays
  CHECK(tmin.self_hit == 22);
  // 256 ulps of 2^20 is 32 units along the normal: never a self hit, but the
  // origin leaves the whole mesh behind, so every child that should hit the
  // mesh misses it (the chapter's warning about large instance translations).
  CHECK(adaptive.self_hit == 0);
  CHECK(adaptive.missed == 24);
  // The validity bit's exponent epsilon grows with the coordinates (one ulp
  // times 2^5 guard: 4 units). One self hit remains (ray 40, a diffuse child
  // leaving its triangle's front): it meets a neighbour sharing a vertex with
  // its parent from the front, so the bits differ and it is not a suspect;
  // the given origin, rounded to 1/8, lies on the wrong side of that
  // neighbour's plane.
  CHECK(vb.self_hit == 1);
}
