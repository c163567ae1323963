// Text trace (.jsonl) reader and writer: a hand-written trace with every
// field, writer output, float round trips, and one test per malformation.
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <random>

#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

const char* kHeader = R"({"format": "vbsim-trace", "version": 1, "scene": "scene.obj"})";

/// Writes a trace of `lines` after the standard header; returns its path.
std::string trace_file(const TempDir& dir, const std::string& lines) {
  std::string path = dir.file("t.jsonl");
  write_file(path, std::string(kHeader) + "\n" + lines);
  return path;
}

/// Reads the whole trace at `path` and returns the error it raises.
TraceError read_error(const std::string& path, int32_t triangle_count = -1) {
  return trace_error_of([&] {
    TextTraceReader reader(path);
    reader.set_triangle_count(triangle_count);
    read_all(reader);
  });
}

const char* kGoodRay = R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0]})";

}  // namespace

TEST_CASE("text trace: every field parses to its value", "[trace]") {
  TempDir dir("trace-text-fields");
  std::string path = dir.file("every.jsonl");
  write_file(path,
             "# a trace written by hand\n"
             R"({"format": "vbsim-trace", "version": 1, "scene": "scene.obj", "light": [0, 10, 0.5], )"
             R"("generator": "by hand", "description": "every field", "future": {"x": 1}, )"
             R"("transform": [2, 0, 0, 1, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]})" "\n"
             "\n"
             R"({"id": 0, "o": [0, 1, 2], "d": [0, 0, -1], "unknown_field": {"x": [1, 2]}})" "\n"
             "   # an indented comment\n"
             R"({"id": 7, "parent": 0, "kind": "reflect", "o": [0.1, -2.5, 1e-3], "d": [1, 2, 3], )"
             R"("tmin": 0.25, "tmax": 100, "parent_prim": 3, "parent_t": 1.5, "parent_uv": [0.25, 0.5], )"
             R"("parent_ns": [0, 0, 1], "sign": 1, "expect": {"prim": 2, "t": 0.123456789012345}})" "\n"
             R"({"id": 8, "parent": 7, "kind": "shadow", "o": [1, 1, 1], "d": [0, 1, 0], "tmax": 1, )"
             R"("sign": 0, "expect": {"prim": -1, "t": null}})" "\r\n"
             R"({"id": 9, "kind": "diffuse", "o": [0, 0, 0], "d": [1, 0, 0], "tmax": null, "expect": {"prim": -1}})" "\n"
             R"({"id": 10, "kind": "refract", "o": [0, 0, 0], "d": [-0.0, 1e-45, 3.4028235e38]})");
  TextTraceReader reader(path);
  const TraceHeader& h = reader.header();
  CHECK(h.version == 1);
  CHECK(h.scene == "scene.obj");
  CHECK(h.scene_path == dir.file("scene.obj"));
  REQUIRE(h.light.has_value());
  CHECK(*h.light == Vec3f{0, 10, 0.5f});
  CHECK(h.generator == "by hand");
  CHECK(h.description == "every field");
  REQUIRE(h.transform.has_value());
  CHECK((*h.transform)[0] == 2.0f);
  CHECK((*h.transform)[3] == 1.0f);
  CHECK((*h.transform)[15] == 1.0f);

  TraceRay r;
  REQUIRE(reader.next(r));
  CHECK(reader.line_number() == 4);
  CHECK(r.id == 0);
  CHECK(r.parent == -1);
  CHECK(r.kind == RayKind::Primary);
  CHECK(r.o == Vec3f{0, 1, 2});
  CHECK(r.d == Vec3f{0, 0, -1});
  CHECK(r.tmin == 0.0f);
  CHECK(std::isinf(r.tmax));
  CHECK(r.parent_prim == -1);
  CHECK_FALSE(r.has_parent_t);
  CHECK_FALSE(r.has_parent_uv);
  CHECK_FALSE(r.has_parent_ns);
  CHECK(r.sign == -1);
  CHECK_FALSE(r.has_expect);

  REQUIRE(reader.next(r));
  CHECK(reader.line_number() == 6);
  CHECK(r.id == 7);
  CHECK(r.parent == 0);
  CHECK(r.kind == RayKind::Reflect);
  CHECK(r.o == Vec3f{0.1f, -2.5f, 0.001f});
  CHECK(r.d == Vec3f{1, 2, 3});
  CHECK(r.tmin == 0.25f);
  CHECK(r.tmax == 100.0f);
  CHECK(r.parent_prim == 3);
  CHECK(r.has_parent_t);
  CHECK(r.parent_t == 1.5f);
  CHECK(r.has_parent_uv);
  CHECK(r.parent_u == 0.25f);
  CHECK(r.parent_v == 0.5f);
  CHECK(r.has_parent_ns);
  CHECK(r.parent_ns == Vec3f{0, 0, 1});
  CHECK(r.sign == 1);
  CHECK(r.has_expect);
  CHECK(r.expect_prim == 2);
  CHECK(r.has_expect_t);
  CHECK(r.expect_t == 0.123456789012345);  // kept as a double, not rounded to float32

  REQUIRE(reader.next(r));  // CRLF line ending
  CHECK(r.id == 8);
  CHECK(r.kind == RayKind::Shadow);
  CHECK(r.tmax == 1.0f);
  CHECK(r.sign == 0);
  CHECK(r.has_expect);
  CHECK(r.expect_prim == -1);
  CHECK_FALSE(r.has_expect_t);

  REQUIRE(reader.next(r));
  CHECK(r.id == 9);
  CHECK(r.kind == RayKind::Diffuse);
  CHECK(std::isinf(r.tmax));
  CHECK(r.has_expect);
  CHECK(r.expect_prim == -1);
  CHECK_FALSE(r.has_expect_t);

  REQUIRE(reader.next(r));
  CHECK(r.kind == RayKind::Refract);
  CHECK(std::signbit(r.d.x));             // -0.0 keeps its sign
  CHECK(r.d.y == std::nextafter(0.0f, 1.0f));  // smallest subnormal
  CHECK(r.d.z == FLT_MAX);

  CHECK_FALSE(reader.next(r));
  CHECK_FALSE(reader.next(r));
}

TEST_CASE("text trace: writer omits defaults and prints shortest float32 decimals", "[trace]") {
  TempDir dir("trace-text-writer");
  TraceHeader h;
  h.scene = "scene.obj";
  h.light = Vec3f{0, 10, 0.1f};
  h.generator = "gen \"quoted\"";
  std::string path = dir.file("out.jsonl");
  TextTraceWriter writer(path, h);

  TraceRay camera;
  camera.id = 0;
  camera.o = {0.1f, -2.5f, 1e-3f};
  camera.d = {0, 0, -1};
  writer.write(camera);

  TraceRay shadow;
  shadow.id = 8;
  shadow.parent = 7;
  shadow.kind = RayKind::Shadow;
  shadow.o = {1, 1, 1};
  shadow.d = {0, 1.0f / 3.0f, -0.0f};
  shadow.tmax = 1;
  shadow.sign = 0;
  shadow.has_expect = true;
  shadow.expect_prim = -1;
  writer.write(shadow);

  TraceRay child;
  child.id = 9;
  child.parent = 0;
  child.kind = RayKind::Reflect;
  child.o = {16777216.0f, 1e30f, 3.4028235e38f};
  child.d = {1, 2, 3};
  child.tmin = 0.25f;
  child.parent_prim = 12;
  child.has_parent_t = true;
  child.parent_t = 2.5f;
  child.has_parent_uv = true;
  child.parent_u = 0.1f;
  child.parent_v = 0.2f;
  child.has_parent_ns = true;
  child.parent_ns = {0, 1, 0};
  child.sign = 1;
  child.has_expect = true;
  child.expect_prim = 4;
  child.has_expect_t = true;
  child.expect_t = 0.1;
  writer.write(child);
  writer.close();

  CHECK(read_file(path) ==
        R"({"format":"vbsim-trace","version":1,"scene":"scene.obj","light":[0,10,0.1],"generator":"gen \"quoted\""})" "\n"
        R"({"id":0,"o":[0.1,-2.5,0.001],"d":[0,0,-1]})" "\n"
        R"({"id":8,"parent":7,"kind":"shadow","o":[1,1,1],"d":[0,0.33333334,-0.0],"tmax":1,"sign":0,"expect":{"prim":-1}})" "\n"
        R"({"id":9,"parent":0,"kind":"reflect","o":[16777216,1e+30,3.4028235e+38],"d":[1,2,3],"tmin":0.25,)"
        R"("parent_prim":12,"parent_t":2.5,"parent_uv":[0.1,0.2],"parent_ns":[0,1,0],"sign":1,"expect":{"prim":4,"t":0.1}})" "\n");

  TextTraceReader reader(path);
  CHECK(reader.header().generator == h.generator);
  std::vector<TraceRay> back = read_all(reader);
  REQUIRE(back.size() == 3);
  CHECK(same_ray(back[0], camera));
  CHECK(same_ray(back[1], shadow));
  CHECK(same_ray(back[2], child));
}

TEST_CASE("text trace: random float32 bit patterns survive write and read", "[trace]") {
  // Every finite float32, including subnormals and -0, must come back bit for bit
  // through the shortest decimal and the reader's double-then-float32 rounding.
  TempDir dir("trace-text-random");
  std::mt19937 rng(12345);
  auto random_float = [&rng]() {
    for (;;) {
      uint32_t bits = static_cast<uint32_t>(rng());
      float x;
      std::memcpy(&x, &bits, 4);
      if (std::isfinite(x)) return x;
    }
  };
  TraceHeader h;
  h.scene = "s.obj";
  std::string path = dir.file("random.jsonl");
  std::vector<TraceRay> rays(40000);
  {
    TextTraceWriter writer(path, h);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      TraceRay& r = rays[i];
      r.id = static_cast<int64_t>(i);
      r.o = {random_float(), random_float(), random_float()};
      do r.d = {random_float(), random_float(), random_float()};
      while (r.d == Vec3f{0, 0, 0});
      r.has_parent_t = true;
      r.parent_t = random_float();
      r.has_expect = true;
      r.expect_prim = 0;
      r.has_expect_t = true;
      uint64_t bits = (static_cast<uint64_t>(rng()) << 32) | rng();
      std::memcpy(&r.expect_t, &bits, 8);
      if (!std::isfinite(r.expect_t)) r.expect_t = 1.0;
      writer.write(r);
    }
    writer.close();
  }
  TextTraceReader reader(path);
  std::vector<TraceRay> back = read_all(reader);
  REQUIRE(back.size() == rays.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) differing += same_ray(rays[i], back[i]) ? 0 : 1;
  CHECK(differing == 0);
}

TEST_CASE("text trace: error message names file, line and field", "[trace]") {
  TempDir dir("trace-text-message");
  std::string path = trace_file(dir, std::string(kGoodRay) + "\n# comment\n\n" +
                                         R"({"id": 1, "o": [0, 0, 0], "d": [0, 0, 0]})" "\n");
  TraceError e = read_error(path);
  CHECK(e.file == path);
  CHECK(e.place == TraceError::Place::Line);
  CHECK(e.line == 5);
  CHECK(e.field == "d");
  CHECK(std::string(e.what()) == path + ":5: field 'd': direction is zero");
}

TEST_CASE("text trace: bad JSON", "[trace]") {
  TempDir dir("trace-text-badjson");
  TraceError e = read_error(
      trace_file(dir, std::string(kGoodRay) + "\n" + R"({"id": 1, "o": [0, 0, 0], "d": [1, 0, 0])" "\n"));
  CHECK(e.line == 3);
  CHECK(e.field.empty());
  CHECK_THAT(e.message, Catch::Contains("bad JSON"));

  // Not an object at all.
  e = read_error(trace_file(dir, "[1, 2, 3]\n"));
  CHECK(e.line == 2);
  CHECK_THAT(e.message, Catch::Contains("expected a JSON object"));

  // A key given twice would otherwise be silently resolved to one of its values.
  e = read_error(trace_file(dir, R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0], "d": [0, 1, 0]})" "\n"));
  CHECK(e.line == 2);
  CHECK(e.field == "d");
  CHECK_THAT(e.message, Catch::Contains("twice"));
}

TEST_CASE("text trace: missing required field", "[trace]") {
  TempDir dir("trace-text-missing");
  struct Case {
    const char* line;
    const char* field;
  };
  const Case cases[] = {
      {R"({"o": [0, 0, 0], "d": [1, 0, 0]})", "id"},
      {R"({"id": 4, "d": [1, 0, 0]})", "o"},
      {R"({"id": 4, "o": [0, 0, 0]})", "d"},
  };
  for (const Case& c : cases) {
    TraceError e = read_error(trace_file(dir, std::string(kGoodRay) + "\n" + c.line + "\n"));
    CHECK(e.line == 3);
    CHECK(e.field == c.field);
    CHECK_THAT(e.message, Catch::Contains("missing"));
  }
}

TEST_CASE("text trace: zero direction", "[trace]") {
  TempDir dir("trace-text-zero-d");
  TraceError e = read_error(trace_file(dir, R"({"id": 0, "o": [1, 2, 3], "d": [0, -0.0, 0]})" "\n"));
  CHECK(e.line == 2);
  CHECK(e.field == "d");
  CHECK(e.message == "direction is zero");
}

TEST_CASE("text trace: non-finite direction (float32 overflow)", "[trace]") {
  TempDir dir("trace-text-inf-d");
  // The midpoint between FLT_MAX and 2^128 is 3.40282356779...e38: a number
  // below it rounds to FLT_MAX, one above it overflows.
  TraceError e = read_error(trace_file(dir, std::string(kGoodRay) + "\n" +
                                                R"({"id": 1, "o": [0, 0, 0], "d": [3.40282356e38, 0, 0]})" "\n" +
                                                R"({"id": 2, "o": [0, 0, 0], "d": [1, 3.40282357e38, 0]})" "\n"));
  CHECK(e.line == 4);
  CHECK(e.field == "d");
  CHECK_THAT(e.message, Catch::Contains("overflows float32"));

  // Beyond double range the JSON parser itself gives up; the field is still named.
  e = read_error(trace_file(dir, R"({"id": 1, "o": [0, 0, 0], "d": [1e400, 0, 0]})" "\n"));
  CHECK(e.line == 2);
  CHECK(e.field == "d");
}

TEST_CASE("text trace: NaN is not JSON and is rejected", "[trace]") {
  TempDir dir("trace-text-nan");
  TraceError e = read_error(trace_file(dir, std::string(kGoodRay) + "\n" +
                                                R"({"id": 1, "o": [NaN, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.line == 3);
  CHECK_THAT(e.message, Catch::Contains("bad JSON"));
}

TEST_CASE("text trace: triangle index out of range once the scene size is known", "[trace]") {
  TempDir dir("trace-text-prim-range");
  std::string path = trace_file(dir, std::string(kGoodRay) + "\n" +
                                         R"({"id": 1, "o": [0, 0, 0], "d": [1, 0, 0], "parent_prim": 4})" "\n" +
                                         R"({"id": 2, "o": [0, 0, 0], "d": [1, 0, 0], "parent_prim": 5})" "\n");
  {
    TextTraceReader unknown_size(path);  // -1: the range check is skipped
    CHECK(read_all(unknown_size).size() == 3);
  }
  TraceError e = read_error(path, 5);
  CHECK(e.line == 4);
  CHECK(e.field == "parent_prim");
  CHECK_THAT(e.message, Catch::Contains("out of range"));

  e = read_error(trace_file(dir, R"({"id": 1, "o": [0, 0, 0], "d": [1, 0, 0], "expect": {"prim": 5, "t": 2}})" "\n"), 5);
  CHECK(e.line == 2);
  CHECK(e.field == "expect.prim");
}

TEST_CASE("text trace: duplicate id", "[trace]") {
  TempDir dir("trace-text-dup-id");
  TraceError e = read_error(trace_file(dir, R"({"id": 5, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"
                                            R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"
                                            R"({"id": 1, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"
                                            R"({"id": 5, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.line == 5);
  CHECK(e.field == "id");
  CHECK_THAT(e.message, Catch::Contains("duplicate id 5"));

  e = read_error(trace_file(dir, R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"
                                 R"({"id": 1, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"
                                 R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.line == 4);
  CHECK(e.field == "id");
}

TEST_CASE("text trace: bad kind", "[trace]") {
  TempDir dir("trace-text-kind");
  TraceError e = read_error(trace_file(dir, R"({"id": 0, "kind": "Primary", "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.line == 2);
  CHECK(e.field == "kind");
  CHECK_THAT(e.message, Catch::Contains("unknown kind \"Primary\""));
  e = read_error(trace_file(dir, R"({"id": 0, "kind": 1, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.field == "kind");
}

TEST_CASE("text trace: bad sign", "[trace]") {
  TempDir dir("trace-text-sign");
  for (const char* sign : {"2", "-1", "true", "0.5"}) {
    TraceError e = read_error(trace_file(
        dir, std::string(R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0], "sign": )") + sign + "}\n"));
    CHECK(e.line == 2);
    CHECK(e.field == "sign");
  }
}

TEST_CASE("text trace: bad header", "[trace]") {
  TempDir dir("trace-text-header");
  std::string path = dir.file("h.jsonl");
  struct Case {
    const char* header;
    const char* field;
  };
  const Case cases[] = {
      {R"({"format": "other", "version": 1, "scene": "s.obj"})", "format"},
      {R"({"id": 0, "o": [0, 0, 0], "d": [1, 0, 0]})", "format"},
      {R"({"format": "vbsim-trace", "version": 2, "scene": "s.obj"})", "version"},
      {R"({"format": "vbsim-trace", "scene": "s.obj"})", "version"},
      {R"({"format": "vbsim-trace", "version": 1})", "scene"},
      {R"({"format": "vbsim-trace", "version": 1, "scene": 3})", "scene"},
      {R"({"format": "vbsim-trace", "version": 1, "scene": "s.obj", "light": [0, 1]})", "light"},
      {R"({"format": "vbsim-trace", "version": 1, "scene": "s.obj", "generator": 1})", "generator"},
      {R"({"format": "vbsim-trace", "version": 1, "scene": "s.obj", "transform": [1, 0, 0]})", "transform"},
  };
  for (const Case& c : cases) {
    write_file(path, std::string(c.header) + "\n" + kGoodRay + "\n");
    TraceError e = trace_error_of([&] { TextTraceReader reader(path); });
    CHECK(e.line == 1);
    CHECK(e.field == c.field);
  }
  write_file(path, "# only a comment\n\n");
  TraceError e = trace_error_of([&] { TextTraceReader reader(path); });
  CHECK(e.place == TraceError::Place::File);
  CHECK_THAT(e.message, Catch::Contains("no header"));

  e = trace_error_of([&] { TextTraceReader reader(dir.file("absent.jsonl")); });
  CHECK_THAT(e.message, Catch::Contains("cannot open"));
}

TEST_CASE("text trace: the other rules on a ray's fields", "[trace]") {
  TempDir dir("trace-text-rules");
  struct Case {
    const char* extra;  ///< fields added to a valid ray
    const char* field;
  };
  const Case cases[] = {
      {R"("tmin": "0")", "tmin"},
      {R"("tmin": -0.5)", "tmin"},
      {R"("tmin": 2, "tmax": 1)", "tmax"},
      {R"("tmax": "inf")", "tmax"},
      {R"("parent_uv": [0.5])", "parent_uv"},
      {R"("parent_uv": [0.5, "a"])", "parent_uv"},
      {R"("parent_ns": [0, 1])", "parent_ns"},
      {R"("parent_t": null)", "parent_t"},
      {R"("parent": -2)", "parent"},
      {R"("parent": 1.0)", "parent"},
      {R"("parent_prim": -2)", "parent_prim"},
      {R"("parent_prim": 4294967296)", "parent_prim"},
      {R"("expect": {"t": 1})", "expect.prim"},
      {R"("expect": {"prim": -2})", "expect.prim"},
      {R"("expect": {"prim": -1, "t": 3})", "expect.t"},
      {R"("expect": {"prim": 1, "t": "x"})", "expect.t"},
      {R"("expect": 3)", "expect"},
      {R"("expect": {"prim": 1, "prim": 2})", "expect.prim"},
  };
  for (const Case& c : cases) {
    TraceError e = read_error(trace_file(
        dir, std::string(R"({"id": 3, "o": [0, 0, 0], "d": [1, 0, 0], )") + c.extra + "}\n"));
    INFO(c.extra);
    CHECK(e.line == 2);
    CHECK(e.field == c.field);
  }
  TraceError e = read_error(trace_file(dir, R"({"id": -1, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.field == "id");
  e = read_error(trace_file(dir, R"({"id": 1.5, "o": [0, 0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.field == "id");
  e = read_error(trace_file(dir, R"({"id": 1, "o": [0, 0], "d": [1, 0, 0]})" "\n"));
  CHECK(e.field == "o");
}

TEST_CASE("text trace: writer refuses rays a reader would reject", "[trace]") {
  TempDir dir("trace-text-writer-check");
  TraceHeader h;
  h.scene = "s.obj";
  TextTraceWriter writer(dir.file("w.jsonl"), h);
  TraceRay r;
  r.d = {1, 0, 0};
  writer.write(r);
  TraceError e = trace_error_of([&] { writer.write(r); });
  CHECK(e.line == 3);
  CHECK(e.field == "id");
  r.id = 1;
  r.o.y = std::nanf("");
  e = trace_error_of([&] { writer.write(r); });
  CHECK(e.field == "o");
}
