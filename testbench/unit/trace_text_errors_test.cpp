// Text trace (.jsonl) malformations: one test per kind of bad input the
// format lists, each asserting the line and field the error names.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include "trace/text_trace_reader.h"
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
