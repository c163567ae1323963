// rtcore-systemc ray files: headerless records of 7 little-endian float32
// (ox oy oz dx dy dz tmax). Import, export, and the errors they can raise.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

#include "trace/rtcore_ray_import.h"
#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace/trace_file.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

/// Little-endian bytes of the float32 values, written independently of the writer.
std::string rtcore_bytes(const std::vector<float>& values) {
  std::string bytes;
  for (float x : values) {
    uint32_t bits;
    std::memcpy(&bits, &x, 4);
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>(bits >> (8 * i)));
  }
  return bytes;
}

TraceError rtcore_error(const std::string& path) {
  return trace_error_of([&] {
    RtcoreRayReader reader(path, "kitchen.ply");
    read_all(reader);
  });
}

}  // namespace

TEST_CASE("rtcore rays: hand-made file imports as primary rays", "[trace]") {
  TempDir dir("trace-rtcore-import");
  std::string path = dir.file("ray_queries.bin");
  write_file(path, rtcore_bytes({1, 2, 3, 0, 0, -1, 100,  //
                                 -0.5f, 0.25f, 8, 1, 1, 0, INFINITY}));
  RtcoreRayReader reader(path, dir.file("kitchen.ply"));
  CHECK(reader.header().scene == "kitchen.ply");
  CHECK(reader.header().scene_path == dir.file("kitchen.ply"));
  CHECK(reader.record_count() == 2);
  std::vector<TraceRay> rays = read_all(reader);
  REQUIRE(rays.size() == 2);
  CHECK(rays[0].id == 0);
  CHECK(rays[0].o == Vec3f{1, 2, 3});
  CHECK(rays[0].d == Vec3f{0, 0, -1});
  CHECK(rays[0].tmin == 0.0f);
  CHECK(rays[0].tmax == 100.0f);
  CHECK(rays[0].kind == RayKind::Primary);
  CHECK(rays[0].parent == -1);
  CHECK(rays[0].sign == -1);
  CHECK(rays[1].id == 1);
  CHECK(rays[1].o == Vec3f{-0.5f, 0.25f, 8});
  CHECK(std::isinf(rays[1].tmax));
}

TEST_CASE("rtcore rays: writer and reader round trip, and conversion to text", "[trace]") {
  TempDir dir("trace-rtcore-roundtrip");
  std::vector<TraceRay> rays(3);
  for (int i = 0; i < 3; ++i) {
    rays[i].id = i;
    rays[i].o = {0.1f * i, -1e-20f, 3e30f};
    rays[i].d = {1, -0.0f, 1.0f / 3.0f};
    rays[i].tmax = i == 2 ? INFINITY : 2.5f + i;
  }
  std::string path = dir.file("rays.bin");
  {
    RtcoreRayWriter writer(path);
    for (const TraceRay& r : rays) writer.write(r);
    writer.close();
  }
  std::string bytes = read_file(path);
  REQUIRE(bytes.size() == 3 * 28);
  CHECK(bytes.substr(28, 28) == rtcore_bytes({0.1f, -1e-20f, 3e30f, 1, -0.0f, 1.0f / 3.0f, 3.5f}));

  RtcoreRayReader reader(path, dir.file("mesh.ply"));
  std::vector<TraceRay> back = read_all(reader);
  REQUIRE(back.size() == 3);
  for (int i = 0; i < 3; ++i) CHECK(same_ray(back[i], rays[i]));

  // Imported rays become an ordinary text trace with the same values.
  RtcoreRayReader again(path, dir.file("mesh.ply"));
  {
    TextTraceWriter text(dir.file("rays.jsonl"), again.header());
    CHECK(copy_trace(again, text) == 3);
    text.close();
  }
  TextTraceReader text_reader(dir.file("rays.jsonl"));
  CHECK(text_reader.header().scene == "mesh.ply");
  std::vector<TraceRay> from_text = read_all(text_reader);
  REQUIRE(from_text.size() == 3);
  for (int i = 0; i < 3; ++i) CHECK(same_ray(from_text[i], rays[i]));
}

TEST_CASE("rtcore rays: a partial last record is an error", "[trace]") {
  TempDir dir("trace-rtcore-partial");
  std::string path = dir.file("rays.bin");
  write_file(path, rtcore_bytes({0, 0, 0, 1, 0, 0, 5, 0, 0, 0, 0, 1, 0, 5}) + std::string(12, '\0'));
  TraceError e = trace_error_of([&] { RtcoreRayReader reader(path, "kitchen.ply"); });
  CHECK(e.place == TraceError::Place::Record);
  CHECK(e.record == 2);
  CHECK(e.field.empty());
  CHECK_THAT(e.message, Catch::Contains("ends 12 bytes into this 28-byte record"));
}

TEST_CASE("rtcore rays: bad values name the record and field", "[trace]") {
  TempDir dir("trace-rtcore-bad");
  std::string path = dir.file("rays.bin");
  const float nan = std::nanf("");
  struct Case {
    std::vector<float> second_ray;
    const char* field;
  };
  const Case cases[] = {
      {{0, 0, 0, 0, 0, 0, 1}, "d"},
      {{0, 0, 0, INFINITY, 0, 0, 1}, "d"},
      {{0, 0, 0, 1, nan, 0, 1}, "d"},
      {{nan, 0, 0, 1, 0, 0, 1}, "o"},
      {{0, 0, 0, 1, 0, 0, -1}, "tmax"},
      {{0, 0, 0, 1, 0, 0, nan}, "tmax"},
  };
  for (const Case& c : cases) {
    std::vector<float> values = {0, 0, 0, 1, 0, 0, 1};
    values.insert(values.end(), c.second_ray.begin(), c.second_ray.end());
    write_file(path, rtcore_bytes(values));
    TraceError e = rtcore_error(path);
    CHECK(e.record == 1);
    CHECK(e.field == c.field);
  }
  write_file(path, rtcore_bytes({0, 0, 0, 0, 0, 0, 1}));
  CHECK(std::string(rtcore_error(path).what()) ==
        path + ": record 0: field 'd': direction is zero");
}

TEST_CASE("rtcore rays: writer refuses a tmin it cannot store", "[trace]") {
  TempDir dir("trace-rtcore-tmin");
  RtcoreRayWriter writer(dir.file("rays.bin"));
  TraceRay r;
  r.d = {0, 1, 0};
  writer.write(r);
  r.tmin = 0.5f;
  TraceError e = trace_error_of([&] { writer.write(r); });
  CHECK(e.record == 1);
  CHECK(e.field == "tmin");
}
