// The header-only C++ trace writer (model/include/vbsim/trace_writer.hpp) against
// vbsim's own readers and converter: every field back bit for bit in both
// forms, its binary records identical to vbsim's conversion of its text, and
// the errors it raises.
#include <catch2/catch.hpp>

#include <cfloat>
#include <filesystem>

#include "trace/binary_trace_format.h"
#include "trace/binary_trace_reader.h"
#include "trace/incomplete_reasons.h"
#include "trace/text_trace_reader.h"
#include "trace/trace_file.h"
#include "trace_test_support.h"
#include "vbsim/trace_writer.hpp"

using namespace vbsim;
using namespace vbsim::test;
namespace w = vbsim::writer;

namespace {

float from_bits(uint32_t b) {
  float x;
  std::memcpy(&x, &b, 4);
  return x;
}

/// Rays with the values that are hard to write: -0, the one float32 whose
/// shortest decimal is a double tie (0x15ae43fd), a subnormal, FLT_MAX, a
/// finite tmax, every optional field, and a miss in expect.
std::vector<w::Ray> hard_rays() {
  std::vector<w::Ray> rays(3);
  rays[0].id = 0;
  rays[0].o = {-0.0f, from_bits(0x15ae43fd), 1e-45f};
  rays[0].d = {FLT_MAX, -from_bits(0x15ae43fd), 0.1f};
  rays[0].expect_prim = 7;
  rays[0].expect_t = 0.1;
  rays[1].id = 3;
  rays[1].parent = 0;
  rays[1].kind = w::Kind::Refract;
  rays[1].o = {1, 2, 3};
  rays[1].d = {0, 0, -1};
  rays[1].tmin = 1e-4f;
  rays[1].tmax = 123456.79f;
  rays[1].parent_prim = 7;
  rays[1].parent_t = 17.314083f;
  rays[1].parent_uv = {{0.47456515f, -0.0f}};
  rays[1].parent_ns = {{0.0f, 1e-38f, -1.0f}};
  rays[1].sign = 1;
  rays[1].expect_prim = -1;
  rays[2].id = 4;
  rays[2].parent = 3;
  rays[2].kind = w::Kind::Shadow;
  rays[2].o = {16777216.0f, 1e16f, 100000.0f};
  rays[2].d = {0, 1, 0};
  rays[2].tmax = 1.0f;
  rays[2].parent_prim = 2;
  rays[2].sign = 0;
  rays[2].incomplete = kIncompleteInstance | kIncompleteFilter;  // "incomplete":["instance","filter"]
  return rays;
}

bool same_float(float a, float b) { return same_bits(a, b); }

void check_same(const TraceRay& got, const w::Ray& want) {
  INFO("ray " << want.id);
  CHECK(got.id == want.id);
  CHECK(got.parent == want.parent);
  CHECK(static_cast<int>(got.kind) == static_cast<int>(want.kind));
  for (int i = 0; i < 3; ++i) {
    CHECK(same_float(got.o[i], want.o[i]));
    CHECK(same_float(got.d[i], want.d[i]));
  }
  CHECK(same_float(got.tmin, want.tmin));
  CHECK(same_float(got.tmax, want.tmax));
  CHECK(got.parent_prim == want.parent_prim);
  CHECK(got.has_parent_t == want.parent_t.has_value());
  if (want.parent_t) CHECK(same_float(got.parent_t, *want.parent_t));
  CHECK(got.has_parent_uv == want.parent_uv.has_value());
  if (want.parent_uv) CHECK((same_float(got.parent_u, (*want.parent_uv)[0]) && same_float(got.parent_v, (*want.parent_uv)[1])));
  CHECK(got.has_parent_ns == want.parent_ns.has_value());
  if (want.parent_ns) CHECK(same_bits(got.parent_ns, Vec3f{(*want.parent_ns)[0], (*want.parent_ns)[1], (*want.parent_ns)[2]}));
  CHECK(got.sign == (want.sign ? *want.sign : -1));
  CHECK(got.has_expect == want.expect_prim.has_value());
  if (want.expect_prim) CHECK(got.expect_prim == *want.expect_prim);
  CHECK(got.has_expect_t == want.expect_t.has_value());
  if (want.expect_t) CHECK(same_bits(got.expect_t, *want.expect_t));
  CHECK(got.incomplete == want.incomplete);
}

std::string records_of(const std::string& vbt) {
  const std::string bytes = read_file(vbt);
  uint32_t n;
  std::memcpy(&n, bytes.data() + 12, 4);
  return bytes.substr(kBinaryTracePreambleBytes + binary_trace_padded_header_bytes(n));
}

}  // namespace

TEST_CASE("C++ writer: both forms read back bit for bit by vbsim's readers", "[writer]") {
  TempDir dir("cpp-writer");
  w::Header header;
  header.scene = "scene \"quoted\".ply";
  header.light = {{0, 10, -0.0f}};
  header.generator = "cpp_trace_writer_test";
  header.transform = {{1, 0, 0, 100000, 0, 1, 0, 0, 0, 0, 1, 1e-5f, 0, 0, 0, 1}};
  for (const char* name : {"hard.jsonl", "hard.vbt"}) {
    w::TraceWriter out(dir.file(name), header);
    for (const w::Ray& r : hard_rays()) out.write(r);
    CHECK(out.close() == 3);
  }
  TextTraceReader text(dir.file("hard.jsonl"));
  BinaryTraceReader binary(dir.file("hard.vbt"));
  for (TraceSource* source : {static_cast<TraceSource*>(&text), static_cast<TraceSource*>(&binary)}) {
    CHECK(source->header().scene == header.scene);
    CHECK(source->header().generator == header.generator);
    REQUIRE(source->header().light);
    CHECK(same_bits(*source->header().light, Vec3f{0, 10, -0.0f}));
    REQUIRE(source->header().transform);
    CHECK(same_float((*source->header().transform)[11], 1e-5f));
    const std::vector<TraceRay> rays = read_all(*source);
    REQUIRE(rays.size() == 3);
    for (std::size_t i = 0; i < rays.size(); ++i) check_same(rays[i], hard_rays()[i]);
  }
  // vbsim's own conversion of the text form gives the binary form's records byte for byte.
  convert_trace_file(dir.file("hard.jsonl"), dir.file("converted.vbt"));
  CHECK(records_of(dir.file("converted.vbt")) == records_of(dir.file("hard.vbt")));
  CHECK(records_of(dir.file("hard.vbt")).size() == 3 * kBinaryTraceRecordBytes);
  CHECK_FALSE(std::filesystem::exists(dir.file("hard.vbt.partial")));
}

TEST_CASE("C++ writer: errors name the line or record and field, and an unfinished file is removed", "[writer]") {
  TempDir dir("cpp-writer-errors");
  auto message_of = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const w::TraceWriteError& e) {
      return e.what();
    }
    return "no error";
  };
  w::Ray ok;
  ok.id = 0;
  ok.o = {0, 0, 5};
  ok.d = {0, 0, -1};
  {
    w::TraceWriter out(dir.file("bad.jsonl"), {"s.ply"});
    out.write(ok);
    w::Ray zero = ok;
    zero.id = 1;
    zero.d = {0, 0, 0};
    CHECK_THAT(message_of([&] { out.write(zero); }), Catch::Contains("bad.jsonl: line 3: field 'd'"));
    w::Ray orphan = ok;
    orphan.id = 1;
    orphan.parent = 2;
    CHECK_THAT(message_of([&] { out.write(orphan); }),
               Catch::Contains("field 'parent'") && Catch::Contains("a parent must precede its children"));
    w::Ray tie = ok;
    tie.id = 1;
    tie.expect_prim = -1;
    tie.expect_t = 2.0;
    CHECK_THAT(message_of([&] { out.write(tie); }), Catch::Contains("field 'expect.t'"));
    // Destroyed without close(): neither the file nor its partial form remains.
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("bad.jsonl")));
  CHECK_FALSE(std::filesystem::exists(dir.file("bad.jsonl.partial")));
  {
    w::TraceWriter out(dir.file("bad.vbt"), {"s.ply"});
    out.write(ok);
    w::Ray neg = ok;
    neg.id = 1;
    neg.tmin = -1;
    CHECK_THAT(message_of([&] { out.write(neg); }), Catch::Contains("bad.vbt: record 1: field 'tmin'"));
  }
  CHECK_THAT(message_of([&] { w::TraceWriter out(dir.file("x.jsonl"), {""}); }), Catch::Contains("field 'scene'"));
  // What every reader refuses: a duplicate id (in order or not) and a child of kind primary.
  for (const char* name : {"dup.jsonl", "dup.vbt"}) {
    w::TraceWriter out(dir.file(name), {"s.ply"});
    for (int64_t id : {5, 3, 9, 4}) {
      w::Ray r = ok;
      r.id = id;
      out.write(r);
    }
    for (int64_t id : {3, 5, 9}) {
      w::Ray again = ok;
      again.id = id;
      CHECK_THAT(message_of([&] { out.write(again); }),
                 Catch::Contains("field 'id': " + std::to_string(id) + " was given before"));
    }
    w::Ray child = ok;
    child.id = 10;
    child.parent = 9;
    child.parent_prim = 0;
    CHECK_THAT(message_of([&] { out.write(child); }), Catch::Contains("field 'kind': primary") && Catch::Contains("parent 9"));
    child.kind = w::Kind::Diffuse;
    out.write(child);
    child.id = 11;
    child.incomplete = 1u << 11;
    CHECK_THAT(message_of([&] { out.write(child); }), Catch::Contains("field 'incomplete'"));
    CHECK(out.close() == 5);
  }
  // vbsim's readers refuse the same two rays.
  write_file(dir.file("h.jsonl"), "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n"
                                  "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n"
                                  "{\"id\":1,\"parent\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"parent_prim\":1}\n");
  auto source = open_trace(dir.file("h.jsonl"));
  TraceRay r;
  CHECK(source->next(r));
  try {
    source->next(r);
    FAIL("a child of kind primary was read");
  } catch (const TraceError& e) {
    CHECK(e.line == 3);
    CHECK(e.field == "kind");
  }
}
