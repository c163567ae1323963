// Ray masks (docs/trace-format.md, `triangle_masks` and a ray's `mask`): both
// trace forms (binary layout 3), what the readers refuse, the scene's masks,
// and their meaning: a triangle whose mask shares no bit with the ray's is not
// there, for the search (the candidate filter) and for the exact answer alike.
#include <catch2/catch.hpp>

#include <cstring>

#include "datapath/closest_hit.h"
#include "datapath/testers.h"
#include "exact/oracle.h"
#include "scene/bvh.h"
#include "scene/triangle_masks.h"
#include "trace/binary_trace_format.h"
#include "trace/trace_file.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

const std::string kMaskedHeader =
    "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\",\"triangle_masks\":[[2,2,2],[7,1,0]]}\n";

/// Two squares, the ground at z = 0 (triangles 0, 1) and a lid at z = 1 (2, 3).
Scene two_squares() {
  auto square = [](float z) {
    const Vec3f a{-1, -1, z}, b{1, -1, z}, c{1, 1, z}, d{-1, 1, z};
    return std::vector<Triangle>{{a, b, c}, {a, c, d}};
  };
  std::vector<Triangle> tris = square(0.0f);
  for (const Triangle& t : square(1.0f)) tris.push_back(t);
  return make_scene(tris);
}

}  // namespace

TEST_CASE("ray masks: both forms (layout 3 in binary) and text to binary to text byte for byte", "[trace][masks]") {
  TempDir dir("ray-masks");
  const std::string rays = "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":1}\n"
                           "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1]}\n"
                           "{\"id\":2,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":0}\n";
  write_file(dir.file("t.jsonl"), kMaskedHeader + rays);
  auto source = open_trace(dir.file("t.jsonl"));
  REQUIRE(source->header().triangle_masks);
  const std::vector<TriangleMaskRange>& ranges = *source->header().triangle_masks;
  REQUIRE(ranges.size() == 2);
  CHECK((ranges[0].first == 2 && ranges[0].count == 2 && ranges[0].mask == 2));
  CHECK((ranges[1].first == 7 && ranges[1].count == 1 && ranges[1].mask == 0));
  const std::vector<TraceRay> got = read_all(*source);
  REQUIRE(got.size() == 3);
  CHECK(got[0].mask == 1u);
  CHECK(got[1].mask == kAllMaskBits);
  CHECK(got[2].mask == 0u);

  convert_trace_file(dir.file("t.jsonl"), dir.file("t.vbt"));
  const std::string bytes = read_file(dir.file("t.vbt"));
  uint32_t layout = 0, mask = 0, reserved = 1;
  std::memcpy(&layout, bytes.data() + 8, 4);
  CHECK(layout == 3);
  REQUIRE(bytes.size() >= 3 * 112);
  const std::size_t first = bytes.size() - 3 * 112;
  std::memcpy(&mask, bytes.data() + first + 104, 4);
  std::memcpy(&reserved, bytes.data() + first + 108, 4);
  CHECK(mask == 1u);
  CHECK(reserved == 0u);
  std::memcpy(&mask, bytes.data() + first + 112 + 104, 4);
  CHECK(mask == kAllMaskBits);
  convert_trace_file(dir.file("t.vbt"), dir.file("back.jsonl"));
  CHECK(read_file(dir.file("back.jsonl")).substr(read_file(dir.file("back.jsonl")).find('\n') + 1) == rays);
  CHECK_THAT(read_file(dir.file("back.jsonl")), Catch::Contains("\"triangle_masks\":[[2,2,2],[7,1,0]]"));

  // An empty list declares masks carried by rays alone.
  write_file(dir.file("e.jsonl"), "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\",\"triangle_masks\":[]}\n"
                                  "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":0}\n");
  convert_trace_file(dir.file("e.jsonl"), dir.file("e.vbt"));
  auto binary = open_trace(dir.file("e.vbt"));
  CHECK((binary->header().triangle_masks && binary->header().triangle_masks->empty()));
  CHECK(read_all(*binary).at(0).mask == 0u);
}

TEST_CASE("ray masks: what the readers refuse and the field they name", "[trace][masks]") {
  TempDir dir("ray-masks-errors");
  const std::string plain = "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n";
  write_file(dir.file("a.jsonl"), plain + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":1}\n");
  TraceError e = error_reading(dir.file("a.jsonl"));
  CHECK(e.line == 2);
  CHECK(e.field == "mask");

  write_file(dir.file("b.jsonl"), kMaskedHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":4294967296}\n");
  e = error_reading(dir.file("b.jsonl"));
  CHECK(e.line == 2);
  CHECK(e.field == "mask");
  write_file(dir.file("c.jsonl"), kMaskedHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"mask\":-1}\n");
  CHECK(error_reading(dir.file("c.jsonl")).field == "mask");

  for (const char* masks : {"[[2,2,2],[3,1,0]]", "[[0,0,1]]", "[[0,1]]", "{}", "[[-1,1,1]]", "[[0,1,4294967296]]"}) {
    INFO(masks);
    write_file(dir.file("h.jsonl"), std::string("{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\","
                                                "\"triangle_masks\":") +
                                        masks + "}\n");
    const TraceError h = trace_error_of([&] { open_trace(dir.file("h.jsonl")); });
    CHECK(h.field == "triangle_masks");
  }

  // A writer refuses a mask the header does not declare.
  TraceHeader header;
  header.scene = "s.ply";
  TraceRay ray;
  ray.d = {0, 0, -1};
  ray.mask = 1;
  for (const char* name : {"w.jsonl", "w.vbt"}) {
    auto sink = create_trace_writer(dir.file(name), header);
    CHECK(trace_error_of([&] { sink->write(ray); }).field == "mask");
  }
}

TEST_CASE("ray masks: the scene masks from the header ranges and back", "[trace][masks][scene]") {
  Scene scene = two_squares();
  apply_triangle_masks(scene, {{2, 2, 0x2u}});
  REQUIRE(scene.mask_table() != nullptr);
  CHECK(scene.triangle_masks == std::vector<uint32_t>{kAllMaskBits, kAllMaskBits, 2u, 2u});
  const std::vector<TriangleMaskRange> back = triangle_mask_ranges(scene.triangle_masks);
  REQUIRE(back.size() == 1);
  CHECK((back[0].first == 2 && back[0].count == 2 && back[0].mask == 2u));
  CHECK(triangle_mask_ranges({1u, 1u, kAllMaskBits, 0u}).size() == 2);
  // All-bits ranges leave the scene without a table; a range past the end is refused.
  Scene plain = two_squares();
  apply_triangle_masks(plain, {{0, 4, kAllMaskBits}});
  CHECK(plain.mask_table() == nullptr);
  CHECK_THROWS_WITH(apply_triangle_masks(plain, {{3, 2, 1u}}),
                    Catch::Contains("triangle_masks") && Catch::Contains("entry 0") && Catch::Contains("holds 4"));
}

TEST_CASE("ray masks: the search and the exact answer skip the triangles a ray's mask hides", "[datapath][masks]") {
  Scene scene = two_squares();
  apply_triangle_masks(scene, {{2, 2, 0x2u}});  // the lid has mask 0x2
  const Bvh bvh = build_bvh(scene);
  const Oracle oracle(scene, bvh);
  const CandidateFilter filter(SelfIntersectionMethod{}, scene.mask_table());
  struct Case {
    uint32_t ray_mask;
    int32_t lid_or_ground;  // 1: the lid answers, 0: the ground, -1: nothing
  };
  for (const Case c : {Case{0x1u, 0}, Case{0x2u, 1}, Case{0x3u, 1}, Case{0x0u, -1}, Case{kAllMaskBits, 1}}) {
    INFO("ray mask " << c.ray_mask);
    Ray ray;
    ray.o = {0.25f, -0.5f, 5.0f};
    ray.d = {0.0f, 0.0f, -1.0f};
    ray.mask = c.ray_mask;
    CandidateCounters cc;
    TraversalCounters tc;
    const Hit h = closest_hit<ThreeHalfPlaneTester>(bvh, ray, filter, cc, tc);
    TraceRay tr;
    tr.o = ray.o;
    tr.d = ray.d;
    tr.mask = c.ray_mask;
    const OracleAnswer exact = oracle.answer(intended_ray(tr, scene, nullptr));
    if (c.lid_or_ground < 0) {
      CHECK(h.prim == -1);
      CHECK(exact.prim == -1);
      CHECK(cc.rejected_mask == 2);  // one triangle of each square under the ray
    } else {
      REQUIRE(h.prim >= 0);
      CHECK(h.prim / 2 == c.lid_or_ground);
      CHECK(exact.prim == h.prim);
      CHECK(h.t == (c.lid_or_ground == 1 ? 4.0f : 5.0f));
      CHECK(cc.rejected_mask == (c.lid_or_ground == 0 ? 1u : 0u));
    }
    // Without the scene's masks (every triangle all bits) the filter shows
    // the lid to every ray but one of mask 0, which sees nothing.
    const CandidateFilter unmasked(SelfIntersectionMethod{});
    const Hit all_bits = closest_hit<ThreeHalfPlaneTester>(bvh, ray, unmasked, cc, tc);
    if (c.ray_mask == 0) CHECK(all_bits.prim == -1);
    else CHECK(all_bits.prim / 2 == 1);
  }
}
