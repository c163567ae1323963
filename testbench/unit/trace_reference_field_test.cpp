// The trace format's optional per-ray `reference` answer and the header's
// `reference` (docs/trace-format.md): both forms (the binary one in layout 2,
// 104-byte records), text -> binary -> text byte for byte, traces without it
// unchanged (layout 1), and what the readers refuse.
#include <catch2/catch.hpp>

#include "trace/binary_trace_format.h"
#include "trace/trace_file.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

const std::string kHeader =
    "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\",\"reference\":\"Embree in the renderer\"}\n";

uint32_t layout_of(const std::string& vbt) {
  const std::string bytes = read_file(vbt);
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + 8, 4);
  return v;
}

}  // namespace

TEST_CASE("reference: the renderer's answer in both forms, layout 2 in binary", "[trace][reference]") {
  TempDir dir("reference-field");
  const std::string rays =
      "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"reference\":{\"prim\":3,\"t\":1.5}}\n"
      "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,1],\"reference\":{\"prim\":-1}}\n"
      "{\"id\":2,\"parent\":0,\"kind\":\"shadow\",\"o\":[0,0,3.5],\"d\":[0,1,0],\"reference\":{\"occluded\":true}}\n"
      "{\"id\":3,\"parent\":0,\"kind\":\"shadow\",\"o\":[0,0,3.5],\"d\":[1,0,0],\"reference\":{\"occluded\":false}}\n"
      "{\"id\":4,\"o\":[0,0,5],\"d\":[0,0,-1]}\n";
  write_file(dir.file("t.jsonl"), kHeader + rays);
  auto source = open_trace(dir.file("t.jsonl"));
  CHECK(source->header().reference == "Embree in the renderer");
  const std::vector<TraceRay> got = read_all(*source);
  REQUIRE(got.size() == 5);
  CHECK((got[0].has_reference && got[0].reference_prim == 3 && got[0].has_reference_t && got[0].reference_t == 1.5f));
  CHECK((got[1].has_reference && got[1].reference_prim == -1 && !got[1].has_reference_t));
  CHECK(got[2].reference_prim == kReferenceOccluded);
  CHECK((got[3].has_reference && got[3].reference_prim == -1));
  CHECK(!got[4].has_reference);

  convert_trace_file(dir.file("t.jsonl"), dir.file("t.vbt"));
  CHECK(layout_of(dir.file("t.vbt")) == 2);
  const std::string bytes = read_file(dir.file("t.vbt"));
  const std::size_t first = bytes.size() - 5 * 104;
  int32_t prim;
  float t;
  std::memcpy(&prim, bytes.data() + first + 96, 4);
  std::memcpy(&t, bytes.data() + first + 100, 4);
  CHECK(prim == 3);
  CHECK(t == 1.5f);
  convert_trace_file(dir.file("t.vbt"), dir.file("back.jsonl"));
  const std::string back = read_file(dir.file("back.jsonl"));
  CHECK(back.substr(back.find('\n') + 1) == rays);
  CHECK_THAT(back.substr(0, back.find('\n')), Catch::Contains("\"reference\":\"Embree in the renderer\""));

  // A trace without references stays in layout 1, 96-byte records.
  write_file(dir.file("plain.jsonl"), "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n"
                                      "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  convert_trace_file(dir.file("plain.jsonl"), dir.file("plain.vbt"));
  CHECK(layout_of(dir.file("plain.vbt")) == 1);
}

TEST_CASE("reference: refused without the header's reference, or malformed", "[trace][reference]") {
  TempDir dir("reference-errors");
  write_file(dir.file("a.jsonl"), "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n"
                                  "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"reference\":{\"prim\":1}}\n");
  TraceError e = error_reading(dir.file("a.jsonl"));
  CHECK(e.line == 2);
  CHECK(e.field == "reference");
  write_file(dir.file("b.jsonl"), kHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"reference\":{\"t\":1}}\n");
  CHECK(error_reading(dir.file("b.jsonl")).field == "reference.prim");
  write_file(dir.file("c.jsonl"), kHeader + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"reference\":{\"prim\":-1,\"t\":2}}\n");
  CHECK(error_reading(dir.file("c.jsonl")).field == "reference.t");
  // Layout 1 has no room for it: its flag bit is unknown there.
  write_file(dir.file("d.jsonl"), "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n"
                                  "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  convert_trace_file(dir.file("d.jsonl"), dir.file("d.vbt"));
  std::string bytes = read_file(dir.file("d.vbt"));
  bytes[bytes.size() - 96 + 90] = static_cast<char>(kHasReference);
  write_file(dir.file("d.vbt"), bytes);
  e = error_reading(dir.file("d.vbt"));
  CHECK(e.record == 0);
  CHECK(e.field == "flags");
}
