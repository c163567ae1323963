// JSON reading and writing helpers for the trace layer (text rays and the
// header object of both forms). Internal to model/trace.
// Contract: readers throw TraceFieldProblem naming the field; numbers become
// float32 by rounding the parsed double; writers print the shortest decimal that
// reads back to the same float32 (or double), with negative zero as "-0.0".
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "datapath/vec3.h"
#include "trace/trace_error.h"

namespace vbsim {

/// Parses one line holding one JSON object; rejects bad JSON, a value that is
/// not an object, and a key that appears twice in one object (which plain
/// parsing would silently resolve). Reuses its buffers from line to line.
class JsonObjectLineParser {
 public:
  /// Throws TraceFieldProblem (field empty unless the fault is in one field's value).
  nlohmann::json parse(std::string_view text);

 private:
  std::vector<std::string> keys_;     ///< keys of the objects currently open
  std::vector<std::size_t> scopes_;   ///< where each open object's keys start in keys_
  std::string last_top_key_;          ///< most recent key of the outermost object
  std::string duplicate_;             ///< first key seen twice, as a field path
};

/// The value as an int64 (a JSON integer, not 3.0).
int64_t json_int64(const nlohmann::json& v, const char* field);
/// The value as an int32 (a JSON integer within int32 range).
int32_t json_int32(const nlohmann::json& v, const char* field);
/// A finite JSON number as a double.
double json_double(const nlohmann::json& v, const char* field);
/// A finite JSON number rounded to float32; rejects values that overflow float32.
float json_float32(const nlohmann::json& v, const char* field);
/// An array of exactly n numbers, each as json_float32.
void json_float32_array(const nlohmann::json& v, const char* field, float* out, std::size_t n);
/// An array of 3 numbers.
Vec3f json_vec3(const nlohmann::json& v, const char* field);
/// A JSON string.
std::string json_string(const nlohmann::json& v, const char* field);

/// Appends the shortest decimal that rounds back to `x` (finite), "-0.0" for -0.
void append_json_float(fmt::memory_buffer& out, float x);
/// Same for a double.
void append_json_double(fmt::memory_buffer& out, double x);
/// Appends "[a,b,c]".
void append_json_vec3(fmt::memory_buffer& out, Vec3f v);
/// Appends a JSON string literal with escapes; rejects text that is not UTF-8.
void append_json_string(fmt::memory_buffer& out, const std::string& s, const char* field);

}  // namespace vbsim
