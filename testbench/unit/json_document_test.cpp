// io/json_document.h: every JSON document a user hands over is read with
// bounded nesting and no repeated key, and refused with its file and line.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/json_document.h"

using namespace vbsim;

namespace {

std::string nested(const std::string& open, const std::string& inner, const std::string& close, int depth) {
  std::string s;
  for (int i = 0; i < depth; ++i) s += open;
  s += inner;
  for (int i = 0; i < depth; ++i) s += close;
  return s;
}

std::string refusal(const std::string& text) {
  try {
    parse_json_document(text, "c.json");
  } catch (const JsonDocumentError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("json document: nesting up to the limit is read, one level more is refused with its line", "[json]") {
  // The outer object is one level: 63 arrays inside it reach the limit of 64.
  CHECK(parse_json_document("{\"a\": " + nested("[", "1", "]", kMaxJsonDepth - 1) + "}", "c.json").is_object());
  const std::string deep = "{\n\"a\": 1,\n\"b\": " + nested("[", "1", "]", kMaxJsonDepth) + "}";
  CHECK(refusal(deep) == "c.json: line 3: JSON nested deeper than 64 levels of arrays and objects");
  // Far deeper than any stack: refused before parsing, not a crash.
  CHECK_THAT(refusal(nested("{\"k\":", "0", "}", 1000000)), Catch::StartsWith("c.json: line 1: JSON nested deeper"));
}

TEST_CASE("json document: brackets inside strings do not count as nesting", "[json]") {
  const std::string text = "{\"s\": \"" + std::string(500, '[') + "\\\"" + std::string(500, '{') + "\"}";
  CHECK(parse_json_document(text, "c.json")["s"].get<std::string>().size() == 1001);
  CHECK(json_nesting_overflow("\"[[[[\"", 2) == std::string::npos);
  CHECK(json_nesting_overflow("[[[", 2) == 2);
}

TEST_CASE("json document: a key twice in one object is refused with its path", "[json]") {
  CHECK(refusal("{\"tmin_eps\": 1, \"tmin_eps\": 2}") == "c.json: field 'tmin_eps': appears twice");
  CHECK(refusal("{\"hw\": {\"memory\": {\"l1\": {}, \"l1\": {}}}}") == "c.json: field 'hw.memory.l1': appears twice");
  // The same key in different objects is fine, also in objects inside arrays.
  CHECK(parse_json_document("{\"a\": {\"x\": 1}, \"b\": {\"x\": 2}, \"c\": [{\"x\": 1}, {\"x\": 2}]}", "c.json").size() == 3);
}

TEST_CASE("json document: malformed JSON and numbers beyond double name the line", "[json]") {
  CHECK_THAT(refusal("{\n\"a\": 1,\n\"b\": }"), Catch::StartsWith("c.json: line 3: not valid JSON"));
  CHECK_THAT(refusal("{\"a\": 1e999}"), Catch::StartsWith("c.json: line 1: not valid JSON"));
  CHECK_THAT(refusal(""), Catch::StartsWith("c.json: line 1: not valid JSON"));
}

TEST_CASE("json document: a number that is not zero but rounds to 0 in double names its field", "[json]") {
  CHECK(refusal("{\"tmin_eps\": 1e-999}") == "c.json: field 'tmin_eps': 1e-999 is too small for a double: it rounds to 0");
  CHECK(refusal("{\"hw\": {\"x\": [0.5, -2.5e-400]}}") ==
        "c.json: field 'hw.x': -2.5e-400 is too small for a double: it rounds to 0");
  CHECK(refusal("1e-999") == "c.json: field '<root>': 1e-999 is too small for a double: it rounds to 0");
  // Zero written any way is zero; a denormal double is not zero.
  CHECK(parse_json_document("{\"a\": 0e-999, \"b\": -0.0, \"c\": 0.000e5}", "c.json")["a"] == 0.0);
  CHECK(parse_json_document("{\"a\": 5e-324}", "c.json")["a"].get<double>() > 0.0);
}

TEST_CASE("json document: a file is read up to a bound, and a directory is named as one", "[json]") {
  const auto dir = std::filesystem::temp_directory_path() / ("vbsim_json_text_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "c.json";
  std::ofstream(file) << "{\"a\": 1}\n";
  CHECK(read_json_text(file.string()) == "{\"a\": 1}\n");
  CHECK(read_json_text(file.string(), 9) == "{\"a\": 1}\n");
  CHECK_THROWS_WITH(read_json_text(file.string(), 8), Catch::StartsWith(file.string() + ": longer than"));
  CHECK(read_json_document(file.string())["a"] == 1);
  CHECK_THROWS_WITH(read_json_document(dir.string()), dir.string() + ": is a directory, not a JSON file");
  CHECK_THROWS_WITH(read_json_document((dir / "none.json").string()),
                    (dir / "none.json").string() + ": cannot open: No such file or directory");
  // An endless file stops at the bound, not when memory runs out.
  CHECK_THROWS_WITH(read_json_document("/dev/zero"),
                    "/dev/zero: longer than 64 MiB, the limit of a JSON file (docs/config.md)");
  std::filesystem::remove_all(dir);
}
