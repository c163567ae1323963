// Fields: reads the members of one JSON object of a configuration file,
// checking types and remembering which names were read, so that any member
// never read is reported as an unknown field. Errors are ConfigError
// "FILE: field 'a.b': reason".
#pragma once
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "replay/replay_config.h"

namespace vbsim::config_fields {

[[noreturn]] inline void fail(const std::string& file, const std::string& field, const std::string& why) {
  throw ConfigError(fmt::format("{}: field '{}': {}", file, field, why));
}

/// Reads the fields of one JSON object, remembering which were known.
class Fields {
 public:
  Fields(const nlohmann::json& j, std::string file, std::string prefix)
      : j_(j), file_(std::move(file)), prefix_(std::move(prefix)) {
    if (!j_.is_object()) fail(file_, prefix_.empty() ? "<root>" : prefix_, "must be an object");
  }
  ~Fields() noexcept(false) {
    if (std::uncaught_exceptions()) return;
    for (const auto& [key, value] : j_.items())
      if (!seen_.count(key)) fail(file_, path(key), "unknown field");
  }
  std::string path(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  const nlohmann::json* get(const std::string& key) {
    seen_.insert({key, true});
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  // Every number is checked in the type it is stored in: a float32 field
  // refuses a value that overflows to inf or that is not zero but rounds to
  // zero; an integer field refuses a value outside its type's range (no
  // wrap-around, no truncation of 2.5).
  void number(const std::string& key, float& out) {
    if (const auto* v = get(key)) {
      const double x = finite_number(*v, key);
      const float f = static_cast<float>(x);
      if (!std::isfinite(f))
        fail(file_, path(key), fmt::format("{} is out of range for a float32 (largest {:g})", v->dump(), FLT_MAX));
      if (f == 0.0f && x != 0.0)
        fail(file_, path(key), fmt::format("{} is too small for a float32: it rounds to 0", v->dump()));
      out = f;
    }
  }
  void integer(const std::string& key, int& out) {
    if (const auto* v = get(key))
      out = static_cast<int>(integer_in(*v, key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
  }
  void number(const std::string& key, double& out) {
    if (const auto* v = get(key)) out = finite_number(*v, key);
  }
  /// An integer in [lo, hi].
  void integer(const std::string& key, uint32_t& out, uint32_t lo, uint32_t hi) {
    if (const auto* v = get(key)) out = static_cast<uint32_t>(integer_in(*v, key, lo, hi));
  }
  /// An integer in [lo, hi] (hi < 2^63).
  void integer(const std::string& key, uint64_t& out, uint64_t lo, uint64_t hi) {
    if (const auto* v = get(key))
      out = static_cast<uint64_t>(integer_in(*v, key, static_cast<int64_t>(lo), static_cast<int64_t>(hi)));
  }
  void boolean(const std::string& key, bool& out) {
    if (const auto* v = get(key)) {
      if (!v->is_boolean()) fail(file_, path(key), "must be true or false");
      out = v->get<bool>();
    }
  }
  /// A name `parse` accepts; the error lists `choices` (e.g. "a, b, c") when given.
  template <class Parse>
  void name(const std::string& key, Parse parse, const std::string& choices = "") {
    if (const auto* v = get(key)) {
      if (!v->is_string() || !parse(v->get<std::string>()))
        fail(file_, path(key), "unknown value " + v->dump() + (choices.empty() ? "" : "; one of: " + choices));
    }
  }
  const std::string& file() const { return file_; }

 private:
  double finite_number(const nlohmann::json& v, const std::string& key) const {
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(file_, path(key), "must be a finite number");
    return v.get<double>();
  }
  /// The integer `v` when lo <= v <= hi, read without wrapping (JSON keeps
  /// integers above 2^63 - 1 unsigned).
  int64_t integer_in(const nlohmann::json& v, const std::string& key, int64_t lo, int64_t hi) const {
    if (!v.is_number_integer()) fail(file_, path(key), fmt::format("must be an integer, got {}", v.dump()));
    const bool is_unsigned = v.is_number_unsigned();
    const bool above = is_unsigned ? v.get<uint64_t>() > static_cast<uint64_t>(hi) : v.get<int64_t>() > hi;
    const bool below = is_unsigned ? lo > 0 && v.get<uint64_t>() < static_cast<uint64_t>(lo) : v.get<int64_t>() < lo;
    if (above || below) fail(file_, path(key), fmt::format("{} is out of range: must be in {}..{}", v.dump(), lo, hi));
    return v.is_number_unsigned() ? static_cast<int64_t>(v.get<uint64_t>()) : v.get<int64_t>();
  }

  const nlohmann::json& j_;
  std::string file_, prefix_;
  std::map<std::string, bool> seen_;
};

}  // namespace vbsim::config_fields
