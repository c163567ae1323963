// TraceConsistencyChecker on hand-made rays over one triangle, and
// CheckedTraceSource: a child before its parent is an error naming the line,
// the other checks are counted warnings.
#include <catch2/catch.hpp>

#include <cmath>

#include "trace/checked_trace_source.h"
#include "trace/text_trace_reader.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

// v0 (0,0,0), v1 (1,0,0), v2 (0,1,0): Ng = (v1-v0) x (v2-v0) = (0,0,1).
const std::vector<Triangle> kTriangles = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};

/// Camera ray 0 from (0.25, 0.25, 1) straight down: it meets the triangle at
/// t = 1, the point (0.25, 0.25, 0), barycentrics (0.25, 0.25).
TraceRay camera_ray() {
  TraceRay r;
  r.id = 0;
  r.o = {0.25f, 0.25f, 1.0f};
  r.d = {0, 0, -1};
  r.has_expect = true;
  r.expect_prim = 0;
  return r;
}

/// A reflection of ray 0 with every parent field consistent: sign 0, since
/// dot(d, Ng) = 1 > 0.
TraceRay reflection() {
  TraceRay r;
  r.id = 1;
  r.parent = 0;
  r.kind = RayKind::Reflect;
  r.o = {0.25f, 0.25f, 0.0f};
  r.d = {0, 0, 1};
  r.set_parent_hit(0, 1.0f, 0.25f, 0.25f);
  r.sign = 0;
  r.has_expect = true;
  return r;
}

/// The checks the child raises after the camera ray, by name.
std::vector<std::string> findings_of(const TraceRay& child, const TraceRay& parent = camera_ray()) {
  TraceConsistencyChecker::Options opt;
  opt.triangles = &kTriangles;
  TraceConsistencyChecker checker(opt);
  std::vector<TraceFinding> out;
  checker.check(parent, 2, "line", out);
  REQUIRE(out.empty());
  checker.check(child, 3, "line", out);
  std::vector<std::string> names;
  for (const TraceFinding& f : out) names.push_back(std::string(trace_check_name(f.check)) + ":" + f.field);
  return names;
}

using Names = std::vector<std::string>;

}  // namespace

TEST_CASE("consistency: a consistent child passes, each broken field is named", "[trace][checks]") {
  CHECK(findings_of(reflection()).empty());

  TraceRay r = reflection();
  r.sign = 1;
  CHECK(findings_of(r) == Names{"sign:sign"});

  r = reflection();
  r.parent_t = 2.0f;  // the parent ray at t = 2 is (0.25, 0.25, -1), a unit from o
  CHECK(findings_of(r) == Names{"parent_data:o"});

  r = reflection();
  r.parent_u = 0.5f;  // the point at (0.5, 0.25) is a quarter unit from o
  CHECK(findings_of(r) == Names{"parent_data:parent_uv"});

  r = reflection();
  r.o = {0.9f, 0.9f, 0.0f};  // consistent with a parent ray through (0.9, 0.9) ...
  r.parent_u = r.parent_v = 0.9f;  // ... but outside the triangle
  TraceRay p = camera_ray();
  p.o = {0.9f, 0.9f, 1.0f};
  CHECK(findings_of(r, p) == Names{"parent_data:parent_uv"});

  p = camera_ray();
  p.tmax = 0.5f;  // the parent's interval ends before parent_t = 1
  CHECK(findings_of(reflection(), p) == Names{"parent_data:parent_t"});

  p = camera_ray();
  p.kind = RayKind::Shadow;
  CHECK(findings_of(reflection(), p) == Names{"parent_data:parent"});

  r = reflection();
  r.parent_prim = -1;
  r.sign = -1;
  CHECK(findings_of(r) == Names{"parent_data:parent_prim"});

  r = reflection();
  r.has_parent_uv = false;
  r.parent_t = 1.5f;  // no barycentrics: the ray point (0.25, 0.25, -0.5) is off the plane
  r.o = {0.25f, 0.25f, -0.5f};
  CHECK(findings_of(r) == Names{"parent_data:parent_t"});

  r = reflection();
  r.has_expect = false;
  CHECK(findings_of(r) == Names{"missing_expect:expect"});
}

TEST_CASE("consistency: tolerances admit rounding and small offsets, not a nearly tangent sign", "[trace][checks]") {
  TraceRay r = reflection();
  r.o.z = 1e-5f;  // a renderer's offset along the normal, 1e-5 of a unit scene
  CHECK(findings_of(r).empty());
  r.o.z = 0.01f;  // ten times the tolerance of 2^-10
  CHECK(findings_of(r) == Names{"parent_data:o", "parent_data:parent_uv"});

  // d = (1, 0, 1e-9): dot(d, Ng) = 1e-9 is below 2^-16 |d| |e1| |e2|, so
  // neither sign contradicts it.
  r = reflection();
  r.d = {1.0f, 0.0f, 1e-9f};
  for (int8_t sign : {0, 1}) {
    r.sign = sign;
    CHECK(findings_of(r).empty());
  }
  r.d = {1.0f, 0.0f, 1e-3f};  // now decided: sign 0
  r.sign = 1;
  CHECK(findings_of(r) == Names{"sign:sign"});
}

TEST_CASE("consistency: ids out of order are a warning, a parent after its child an error", "[trace][checks]") {
  TraceConsistencyChecker checker(TraceConsistencyChecker::Options{});
  std::vector<TraceFinding> out;
  TraceRay a = camera_ray();
  a.id = 5;
  checker.check(a, 2, "line", out);
  TraceRay b = reflection();
  b.id = 3;
  b.parent = 4;  // ids no longer ascend: decided when ray 4 arrives
  checker.check(b, 3, "line", out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].check == TraceCheck::IdOrder);
  CHECK_FALSE(trace_check_is_error(out[0].check));
  out.clear();
  TraceRay c = camera_ray();
  c.id = 4;
  checker.check(c, 4, "line", out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].check == TraceCheck::ChildBeforeParent);
  CHECK(trace_check_is_error(out[0].check));
  CHECK_THAT(out[0].message, Catch::Contains("ray 4 is the parent of ray 3 (line 3)"));
}

TEST_CASE("checked source: child before parent throws naming the line, warnings are counted", "[trace][checks]") {
  TempDir dir("checked-source");
  const std::string head = "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n";
  const std::string camera = "{\"id\":0,\"o\":[0.25,0.25,1],\"d\":[0,0,-1]}\n";
  const std::string child =
      "{\"id\":1,\"parent\":0,\"kind\":\"reflect\",\"o\":[0.25,0.25,0],\"d\":[0,0,1],\"parent_prim\":0,"
      "\"parent_t\":1,\"parent_uv\":[0.25,0.25],\"sign\":1}\n";
  write_file(dir.file("good.jsonl"), head + camera + "# comment\n" + child);
  {
    TextTraceReader reader(dir.file("good.jsonl"));
    TraceConsistencyChecker::Options opt;
    opt.triangles = &kTriangles;
    CheckedTraceSource checked(reader, opt);
    CHECK(read_all(checked).size() == 2);
    CHECK(checked.count(TraceCheck::Sign) == 1);
    CHECK(checked.count(TraceCheck::MissingExpect) == 2);
    CHECK_THAT(checked.first(TraceCheck::Sign), Catch::Contains("good.jsonl:4: field 'sign'"));
    CHECK(checked.summary_json()["warnings"]["sign"] == 1);
    CHECK_THAT(checked.warning_lines("vbsim replay", false),
               Catch::Contains("1 ray: a sign bit") && !Catch::Contains("oracle"));
  }
  const std::string orphan =
      "{\"id\":1,\"parent\":2,\"kind\":\"diffuse\",\"o\":[0.25,0.25,0],\"d\":[0,0,1],\"parent_prim\":0}\n";
  write_file(dir.file("bad.jsonl"), head + camera + "\n" + orphan + "{\"id\":2,\"o\":[0,0,1],\"d\":[0,0,-1]}\n");
  TextTraceReader reader(dir.file("bad.jsonl"));
  CheckedTraceSource checked(reader, TraceConsistencyChecker::Options{});
  const TraceError e = trace_error_of([&] { read_all(checked); });
  CHECK(e.line == 4);
  CHECK(e.field == "parent");
  CHECK_THAT(std::string(e.what()), Catch::Contains("bad.jsonl:4") && Catch::Contains("child before parent"));
}
