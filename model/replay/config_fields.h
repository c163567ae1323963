// Fields: reads the members of one JSON object of a configuration file,
// checking types and remembering which names were read, so that any member
// never read is reported as an unknown field. Errors are ConfigError
// "FILE: field 'a.b': reason".
#pragma once
#include <cmath>
#include <cstdint>
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
  void number(const std::string& key, float& out) {
    if (const auto* v = get(key)) {
      if (!v->is_number() || !std::isfinite(v->get<double>())) fail(file_, path(key), "must be a finite number");
      out = v->get<float>();
    }
  }
  void integer(const std::string& key, int& out) {
    if (const auto* v = get(key)) {
      if (!v->is_number_integer()) fail(file_, path(key), "must be an integer");
      out = v->get<int>();
    }
  }
  void number(const std::string& key, double& out) {
    if (const auto* v = get(key)) {
      if (!v->is_number() || !std::isfinite(v->get<double>())) fail(file_, path(key), "must be a finite number");
      out = v->get<double>();
    }
  }
  /// An integer in [lo, hi].
  void integer(const std::string& key, uint32_t& out, uint32_t lo, uint32_t hi) {
    if (const auto* v = get(key)) {
      if (!v->is_number_integer()) fail(file_, path(key), "must be an integer");
      const int64_t x = v->get<int64_t>();
      if (x < lo || x > hi) fail(file_, path(key), fmt::format("must be in {}..{}", lo, hi));
      out = static_cast<uint32_t>(x);
    }
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
  const nlohmann::json& j_;
  std::string file_, prefix_;
  std::map<std::string, bool> seen_;
};

}  // namespace vbsim::config_fields
