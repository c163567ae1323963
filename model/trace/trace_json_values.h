// JSON reading and writing helpers for the trace layer (text rays and the
// header object of both forms). Internal to model/trace.
// Contract: readers throw TraceFieldProblem naming the field. A number becomes
// the float32 nearest to the decimal as written: the parsed double rounded to
// float32, except when that double lies exactly halfway between two float32
// values, where the decimal text decides (rounding the double would pick the
// even neighbour whatever side the decimal was on). Writers print the shortest
// decimal that reads back to the same float32 (or double), -0 as "-0.0".
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "datapath/vec3.h"
#include "trace/trace_error.h"

namespace vbsim {

/// True when `d` lies exactly halfway between two adjacent float32 values
/// (including halfway between FLT_MAX and 2^128).
bool is_float32_tie(double d);

/// Parses one line holding one JSON object; rejects bad JSON, a value that is
/// not an object, and a key that appears twice in one object (which plain
/// parsing would silently resolve). A number whose double is a float32 tie is
/// stored as a binary value (which JSON text cannot produce) holding the double
/// and the float32 nearest to its decimal; the json_* readers below unpack it.
/// Throws TraceFieldProblem (field empty unless the fault is in one field's value).
nlohmann::json parse_json_object_line(std::string_view text);

/// The value as an int64 (a JSON integer, not 3.0).
int64_t json_int64(const nlohmann::json& v, const char* field);
/// The value as an int32 (a JSON integer within int32 range).
int32_t json_int32(const nlohmann::json& v, const char* field);
/// A finite JSON number as a double.
double json_double(const nlohmann::json& v, const char* field);
/// A JSON number as the nearest float32 (see above); rejects values that overflow float32.
float json_float32(const nlohmann::json& v, const char* field);
/// An array of exactly n numbers, each as json_float32.
void json_float32_array(const nlohmann::json& v, const char* field, float* out, std::size_t n);
/// An array of 3 numbers.
Vec3f json_vec3(const nlohmann::json& v, const char* field);
/// A JSON string.
std::string json_string(const nlohmann::json& v, const char* field);

/// Appends the shortest decimal that reads back to `x` (finite) both when
/// rounded directly to float32 and when parsed as a double first; "-0.0" for -0.
void append_json_float(fmt::memory_buffer& out, float x);
/// The shortest decimal that reads back to `x` (finite); "-0.0" for -0.
void append_json_double(fmt::memory_buffer& out, double x);
/// Appends "[a,b,c]".
void append_json_vec3(fmt::memory_buffer& out, Vec3f v);
/// Appends a JSON string literal with escapes; rejects text that is not UTF-8.
void append_json_string(fmt::memory_buffer& out, const std::string& s, const char* field);

}  // namespace vbsim
