// Text trace (.jsonl) reader and writer: a hand-written trace with every
// field, the writer's exact output, and float32 round trips.
// The malformation tests are in trace_text_errors_test.cpp.
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>

#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

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

namespace {

uint32_t bits_of(float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  return bits;
}

/// What a reader that parses a double and then rounds it to float32 gets.
float via_double(const char* decimal) { return static_cast<float>(std::strtod(decimal, nullptr)); }

}  // namespace

TEST_CASE("text trace: a decimal whose double is a float32 tie rounds as written", "[trace]") {
  // 1 + 2^-24 = 1.000000059604644775390625 is halfway between 1 and the next
  // float32. The two 17-digit decimals around it parse to exactly that double,
  // and rounding the double (ties to even) gives 1 for both; rounded directly,
  // the one above the midpoint is the next float32.
  // 7.038531e-26 is the shortest decimal of float32 0x15ae43fd and the only
  // positive finite float32 whose shortest decimal has a tie as its double
  // (an exhaustive check over all 2^31 - 2^23 of them).
  const float above_one = std::nextafter(1.0f, 2.0f);
  REQUIRE(via_double("1.0000000596046448") == 1.0f);
  REQUIRE(std::strtof("1.0000000596046448", nullptr) == above_one);
  REQUIRE(bits_of(std::strtof("7.038531e-26", nullptr)) == 0x15ae43fdu);
  REQUIRE(bits_of(via_double("7.038531e-26")) != 0x15ae43fdu);

  TempDir dir("trace-text-ties");
  std::string path = dir.file("ties.jsonl");
  write_file(path,
             R"({"format": "vbsim-trace", "version": 1, "scene": "s.obj", "light": [1.0000000596046448, 0, 0]})" "\n"
             R"({"id": 0, "o": [1.0000000596046448, 1.0000000596046447, 1.000000059604644775390625], )"
             R"("d": [7.038531e-26, -7.038531e-26, 1], "expect": {"prim": 0, "t": 1.0000000596046448}})" "\n");
  TextTraceReader reader(path);
  CHECK(reader.header().light->x == above_one);
  TraceRay r;
  REQUIRE(reader.next(r));
  CHECK(r.o.x == above_one);
  CHECK(r.o.y == 1.0f);
  CHECK(r.o.z == 1.0f);  // exactly the midpoint: ties to even
  CHECK(bits_of(r.d.x) == 0x15ae43fdu);
  CHECK(bits_of(r.d.y) == 0x95ae43fdu);
  CHECK(r.expect_t == 1.0000000596046448);  // a double field keeps the double

  // The writer avoids such decimals, so double-first readers read it right too.
  TraceHeader h;
  h.scene = "s.obj";
  std::string out = dir.file("out.jsonl");
  {
    TextTraceWriter writer(out, h);
    writer.write(r);
    writer.close();
  }
  std::string text = read_file(out);
  std::size_t at = text.find("\"d\":[") + 5;
  CHECK(bits_of(via_double(text.c_str() + at)) == 0x15ae43fdu);
  TextTraceReader back(out);
  TraceRay again;
  REQUIRE(back.next(again));
  CHECK(same_ray(again, r));
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
