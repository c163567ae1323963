// The trace format's optional `incomplete` field (docs/trace-format.md): read
// and written in both forms, text -> binary -> text byte for byte, old traces
// (without it) unchanged, and a bad value refused naming the field.
#include <catch2/catch.hpp>

#include "trace/incomplete_reasons.h"
#include "trace/trace_file.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

const std::string kHeader = "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n";

}  // namespace

TEST_CASE("incomplete: names in the text form, bits in the binary form, both ways", "[trace][incomplete]") {
  TempDir dir("incomplete-field");
  const std::string rays =
      "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n"
      "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1],\"incomplete\":[\"instance\",\"filter\"]}\n"
      "{\"id\":2,\"kind\":\"shadow\",\"o\":[0,0,5],\"d\":[0,0,-1],\"incomplete\":[\"quad\",\"grid\",\"subdivision\","
      "\"curve\",\"point\",\"user\",\"motion_blur\",\"other_geometry\",\"mask\",\"unlinked\"]}\n";
  write_file(dir.file("t.jsonl"), kHeader + rays);
  auto source = open_trace(dir.file("t.jsonl"));
  const std::vector<TraceRay> got = read_all(*source);
  REQUIRE(got.size() == 3);
  CHECK(got[0].incomplete == 0);  // absent: none, as in every trace written before the field
  CHECK(got[1].incomplete == (kIncompleteInstance | kIncompleteFilter));
  CHECK(got[2].incomplete == (kIncompleteKnownBits & ~(kIncompleteInstance | kIncompleteFilter)));
  CHECK(incomplete_reasons_text(got[1].incomplete) == "instance, filter");

  convert_trace_file(dir.file("t.jsonl"), dir.file("t.vbt"));
  const std::string bytes = read_file(dir.file("t.vbt"));
  // Record 1's incomplete word (offset 92 of the 96-byte record), little-endian.
  const std::size_t records = bytes.size() - 3 * 96;
  uint32_t word = 0;
  std::memcpy(&word, bytes.data() + records + 96 + 92, 4);
  CHECK(word == 0x201u);
  convert_trace_file(dir.file("t.vbt"), dir.file("back.jsonl"));
  const std::string back = read_file(dir.file("back.jsonl"));
  CHECK(back.substr(back.find('\n') + 1) == rays);  // the writer's layout: reasons in bit order
}

TEST_CASE("incomplete: an unknown reason or a value that is not a list is refused naming the field",
          "[trace][incomplete]") {
  TempDir dir("incomplete-errors");
  write_file(dir.file("a.jsonl"), kHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"incomplete\":[\"teapot\"]}\n");
  TraceError e = error_reading(dir.file("a.jsonl"));
  CHECK(e.line == 2);
  CHECK(e.field == "incomplete");
  CHECK_THAT(e.message, Catch::Contains("teapot") && Catch::Contains("instance"));
  write_file(dir.file("b.jsonl"), kHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"incomplete\":\"instance\"}\n");
  e = error_reading(dir.file("b.jsonl"));
  CHECK(e.field == "incomplete");
  // The binary form: a bit beyond the twelve reasons.
  write_file(dir.file("c.jsonl"), kHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  convert_trace_file(dir.file("c.jsonl"), dir.file("c.vbt"));
  std::string bytes = read_file(dir.file("c.vbt"));
  bytes[bytes.size() - 96 + 93] = 0x10;  // bit 12
  write_file(dir.file("c.vbt"), bytes);
  e = error_reading(dir.file("c.vbt"));
  CHECK(e.record == 0);
  CHECK(e.field == "incomplete");
}
