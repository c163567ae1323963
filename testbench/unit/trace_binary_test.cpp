// Binary trace (.vbt): layout checked byte by byte, lossless conversion to and
// from the text form, streaming past one buffer, truncation and bad records.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>

#include "trace/binary_trace_format.h"
#include "trace/binary_trace_reader.h"
#include "trace/binary_trace_writer.h"
#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

/// A hand-written text trace using every field and the odd values (-0, subnormal, FLT_MAX).
const char* kEveryFieldTrace =
    R"({"format": "vbsim-trace", "version": 1, "scene": "../scenes/room.obj", "light": [0, 10, 0.1], )"
    R"("generator": "by hand", "description": "every field \u00e9", )"
    R"("transform": [2, 0, 0, 1, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]})" "\n"
    R"({"id": 0, "o": [0, 1, 2], "d": [0, 0, -1]})" "\n"
    R"({"id": 7, "parent": 0, "kind": "reflect", "o": [0.1, -2.5, 1e-3], "d": [1, 2, 3], )"
    R"("tmin": 0.25, "tmax": 100, "parent_prim": 3, "parent_t": 1.5, "parent_uv": [0.25, 0.5], )"
    R"("parent_ns": [0, 0, 1], "sign": 1, "expect": {"prim": 2, "t": 0.123456789012345}})" "\n"
    R"({"id": 8, "parent": 7, "kind": "shadow", "o": [1, 1, 1], "d": [0, 1, 0], "tmax": 1, )"
    R"("sign": 0, "expect": {"prim": -1, "t": null}})" "\n"
    R"({"id": 3, "kind": "refract", "o": [-0.0, 1e-45, 3.4028235e38], "d": [1, 0, 0], "tmin": -0.0, "expect": {"prim": 0}})" "\n"
    R"({"id": 4, "kind": "diffuse", "o": [0, 0, 0], "d": [0.3, 0.3, 0.3], "parent_prim": 0, "parent_uv": [0, 1]})" "\n";

TraceRay simple_ray(int64_t id) {
  TraceRay r;
  r.id = id;
  r.o = {static_cast<float>(id), 0.5f, -1};
  r.d = {0, 0, 1};
  return r;
}

TraceHeader simple_header() {
  TraceHeader h;
  h.scene = "scene.obj";
  return h;
}

/// Writes `rays` as a binary trace at `path`.
void write_binary(const std::string& path, const std::vector<TraceRay>& rays) {
  BinaryTraceWriter writer(path, simple_header());
  for (const TraceRay& r : rays) writer.write(r);
  writer.close();
}

uint64_t le_bytes(const std::string& bytes, std::size_t at, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<uint8_t>(bytes[at + i]);
  return v;
}

float le_f32(const std::string& bytes, std::size_t at) {
  uint32_t bits = static_cast<uint32_t>(le_bytes(bytes, at, 4));
  float x;
  std::memcpy(&x, &bits, 4);
  return x;
}

/// Offset of the first record in a file written with simple_header().
std::size_t first_record_offset() {
  return 16 + binary_trace_padded_header_bytes(trace_header_json(simple_header()).size());
}

void patch(std::string& bytes, std::size_t at, const void* value, std::size_t n) {
  std::memcpy(&bytes[at], value, n);
}

}  // namespace

TEST_CASE("binary trace: text to binary to text is byte-identical", "[trace]") {
  TempDir dir("trace-binary-roundtrip");
  write_file(dir.file("hand.jsonl"), kEveryFieldTrace);
  // One normalisation through the text writer, then the binary round trip.
  CHECK(convert_trace_file(dir.file("hand.jsonl"), dir.file("a.jsonl")) == 5);
  CHECK(convert_trace_file(dir.file("a.jsonl"), dir.file("b.vbt")) == 5);
  CHECK(convert_trace_file(dir.file("b.vbt"), dir.file("c.jsonl")) == 5);
  std::string text = read_file(dir.file("a.jsonl"));
  CHECK(read_file(dir.file("c.jsonl")) == text);
  CHECK(read_file(dir.file("b.vbt")).compare(0, 8, "VBSIMTRB") == 0);
  // And the other way round: binary to text to binary.
  CHECK(convert_trace_file(dir.file("c.jsonl"), dir.file("d.vbt")) == 5);
  CHECK(read_file(dir.file("d.vbt")) == read_file(dir.file("b.vbt")));

  // The rays themselves, bit for bit, and the header.
  TextTraceReader original(dir.file("hand.jsonl"));
  BinaryTraceReader binary(dir.file("b.vbt"));
  CHECK(binary.header().scene == "../scenes/room.obj");
  CHECK(binary.header().description == original.header().description);
  CHECK(binary.header().transform == original.header().transform);
  CHECK(binary.record_count() == 5);
  std::vector<TraceRay> a = read_all(original), b = read_all(binary);
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) CHECK(same_ray(a[i], b[i]));
  CHECK(std::signbit(b[3].o.x));
  CHECK(std::signbit(b[3].tmin));
}

TEST_CASE("binary trace: bytes sit at the documented offsets", "[trace]") {
  TempDir dir("trace-binary-layout");
  std::string path = dir.file("one.vbt");
  TraceRay r;
  r.id = 0x0102030405060708;
  r.parent = -1;
  r.kind = RayKind::Refract;
  r.o = {1, 2, 3};
  r.d = {-1, 0.5f, 0.25f};
  r.tmin = 0.125f;
  r.parent_prim = 77;
  r.has_parent_uv = true;
  r.parent_u = 0.75f;
  r.parent_v = 0.125f;
  r.sign = 1;
  r.has_expect = true;
  r.expect_prim = 9;
  r.has_expect_t = true;
  r.expect_t = 2.5;
  write_binary(path, {r});
  std::string bytes = read_file(path);

  std::string header_json = trace_header_json(simple_header());
  CHECK(header_json == R"({"format":"vbsim-trace","version":1,"scene":"scene.obj"})");
  const std::size_t n = header_json.size();  // 56
  const std::size_t start = first_record_offset();
  CHECK(start == 16 + 56);
  REQUIRE(bytes.size() == start + 96);
  CHECK(bytes.substr(0, 8) == "VBSIMTRB");
  CHECK(le_bytes(bytes, 8, 4) == 1);
  CHECK(le_bytes(bytes, 12, 4) == n);
  CHECK(bytes.substr(16, n) == header_json);
  CHECK(bytes.substr(16 + n, start - 16 - n) == std::string(start - 16 - n, ' '));

  CHECK(le_bytes(bytes, start + 0, 8) == 0x0102030405060708u);
  CHECK(le_bytes(bytes, start + 8, 8) == ~uint64_t{0});  // parent -1
  CHECK(le_f32(bytes, start + 16) == 1.0f);
  CHECK(le_f32(bytes, start + 24) == 3.0f);
  CHECK(le_f32(bytes, start + 28) == -1.0f);
  CHECK(le_f32(bytes, start + 36) == 0.25f);
  CHECK(le_f32(bytes, start + 40) == 0.125f);
  CHECK(le_bytes(bytes, start + 44, 4) == 0x7f800000u);  // tmax +inf
  CHECK(le_bytes(bytes, start + 48, 4) == 77);
  CHECK(le_bytes(bytes, start + 52, 4) == 0);  // parent_t absent: zero
  CHECK(le_f32(bytes, start + 56) == 0.75f);
  CHECK(le_f32(bytes, start + 60) == 0.125f);
  CHECK(le_bytes(bytes, start + 64, 12) == 0);  // parent_ns absent
  CHECK(le_bytes(bytes, start + 76, 4) == 9);
  CHECK(le_bytes(bytes, start + 80, 8) == 0x4004000000000000u);  // 2.5 as a double
  CHECK(static_cast<uint8_t>(bytes[start + 88]) == 2);           // refract
  CHECK(static_cast<uint8_t>(bytes[start + 89]) == 1);           // sign
  // flags: has_parent_uv (2) | has_expect (8) | has_expect_t (16) | sign given (32)
  CHECK(le_bytes(bytes, start + 90, 2) == 2 + 8 + 16 + 32);
  CHECK(le_bytes(bytes, start + 92, 4) == 0);
}

TEST_CASE("binary trace: streams past its read buffer and dispatches by content", "[trace]") {
  TempDir dir("trace-binary-stream");
  std::vector<TraceRay> rays;
  for (int64_t i = 0; i < 2500; ++i) rays.push_back(simple_ray(i));
  // A binary trace under a text-looking name is still read as binary.
  std::string path = dir.file("many.jsonl");
  write_binary(path, rays);
  std::unique_ptr<TraceSource> source = open_trace(path);
  CHECK(dynamic_cast<BinaryTraceReader*>(source.get()) != nullptr);
  std::vector<TraceRay> back = read_all(*source);
  REQUIRE(back.size() == rays.size());
  CHECK(same_ray(back[0], rays[0]));
  CHECK(same_ray(back[1024], rays[1024]));
  CHECK(same_ray(back[2499], rays[2499]));

  std::unique_ptr<TraceSink> sink = create_trace_writer(dir.file("x.vbt"), simple_header());
  CHECK(dynamic_cast<BinaryTraceWriter*>(sink.get()) != nullptr);
  sink = create_trace_writer(dir.file("x.jsonl"), simple_header());
  CHECK(dynamic_cast<TextTraceWriter*>(sink.get()) != nullptr);
}

TEST_CASE("binary trace: truncated file", "[trace]") {
  TempDir dir("trace-binary-truncated");
  std::string path = dir.file("t.vbt");
  write_binary(path, {simple_ray(0), simple_ray(1), simple_ray(2)});
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 10);
  TraceError e = trace_error_of([&] { BinaryTraceReader reader(path); });
  CHECK(e.place == TraceError::Place::Record);
  CHECK(e.record == 2);
  CHECK_THAT(e.message, Catch::Contains("ends 86 bytes into this 96-byte record"));
  CHECK(std::string(e.what()) == path + ": record 2: " + e.message);

  // Cut inside the header JSON, and inside the preamble.
  std::filesystem::resize_file(path, 40);
  e = trace_error_of([&] { BinaryTraceReader reader(path); });
  CHECK(e.place == TraceError::Place::Header);
  CHECK_THAT(e.message, Catch::Contains("truncated"));
  std::filesystem::resize_file(path, 12);
  e = trace_error_of([&] { BinaryTraceReader reader(path); });
  CHECK_THAT(e.message, Catch::Contains("truncated"));
}

TEST_CASE("binary trace: bad records name the record and field", "[trace]") {
  TempDir dir("trace-binary-bad");
  std::string good_path = dir.file("good.vbt");
  TraceRay with_parent = simple_ray(2);
  with_parent.parent_prim = 5;
  write_binary(good_path, {simple_ray(0), simple_ray(1), with_parent});
  const std::string good = read_file(good_path);
  const std::size_t rec1 = first_record_offset() + 96;
  const std::string path = dir.file("bad.vbt");
  auto error_after = [&](auto&& change, int32_t triangle_count = -1) {
    std::string bytes = good;
    change(bytes);
    write_file(path, bytes);
    return trace_error_of([&] {
      BinaryTraceReader reader(path);
      reader.set_triangle_count(triangle_count);
      read_all(reader);
    });
  };
  const float zero = 0.0f, nan = std::nanf(""), inf = INFINITY;

  TraceError e = error_after([&](std::string& b) {
    patch(b, rec1 + 28 + 8, &zero, 4);  // d = (0, 0, 0)
  });
  CHECK(e.record == 1);
  CHECK(e.field == "d");
  CHECK(e.message == "direction is zero");
  CHECK(std::string(e.what()) == path + ": record 1: field 'd': direction is zero");

  e = error_after([&](std::string& b) { patch(b, rec1 + 28, &inf, 4); });
  CHECK(e.field == "d");
  CHECK_THAT(e.message, Catch::Contains("not finite"));
  e = error_after([&](std::string& b) { patch(b, rec1 + 16, &nan, 4); });
  CHECK(e.field == "o");
  e = error_after([&](std::string& b) { patch(b, rec1 + 44, &nan, 4); });
  CHECK(e.field == "tmax");
  e = error_after([&](std::string& b) { b[rec1] = 0; });  // id 1 -> 0, a duplicate
  CHECK(e.record == 1);
  CHECK(e.field == "id");
  e = error_after([&](std::string& b) { b[rec1 + 88] = 5; });
  CHECK(e.field == "kind");
  e = error_after([&](std::string& b) {
    b[rec1 + 89] = 2;
    b[rec1 + 90] = static_cast<char>(kHasSign);
  });
  CHECK(e.field == "sign");
  e = error_after([&](std::string& b) { b[rec1 + 91] = 1; });  // flag bit 8: unknown
  CHECK(e.field == "flags");
  e = error_after([&](std::string& b) { b[rec1 + 90] = static_cast<char>(kHasExpectT); });
  CHECK(e.field == "expect.t");
  e = error_after([&](std::string& b) { b[rec1 + 95] = 1; });  // incomplete bit 24: unknown
  CHECK(e.field == "incomplete");
  e = error_after([](std::string&) {}, 5);
  CHECK(e.record == 2);
  CHECK(e.field == "parent_prim");
  e = error_after([](std::string& b) { b[3] = 'X'; });
  CHECK(e.place == TraceError::Place::File);
  CHECK_THAT(e.message, Catch::Contains("magic"));
  e = error_after([](std::string& b) { b[8] = 4; });  // 1, 2 (reference answers) and 3 (ray masks) are known
  CHECK_THAT(e.message, Catch::Contains("version 4"));
  e = error_after([](std::string& b) { b[8] = 3; });  // layout 3 under a header without triangle_masks
  CHECK(e.place == TraceError::Place::Header);
  CHECK(e.field == "triangle_masks");
  e = error_after([](std::string& b) { b[16 + 2] = 'F'; });  // "Format": no format field
  CHECK(e.place == TraceError::Place::Header);
  CHECK(e.field == "format");
}
