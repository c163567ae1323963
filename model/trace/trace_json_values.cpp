#include "trace/trace_json_values.h"

#include <cfloat>
#include <cmath>
#include <iterator>
#include <limits>

namespace vbsim {

namespace {

using json = nlohmann::json;

/// Doubles at or beyond this magnitude round to infinity in float32: the
/// midpoint between FLT_MAX and 2^128 (a tie rounds to even, i.e. to 2^128).
constexpr double kFloat32OverflowBound = 0x1.ffffffp127;

[[noreturn]] void problem(const char* field, std::string message) {
  throw TraceFieldProblem{field, std::move(message)};
}

/// A short rendering of a JSON value for messages.
std::string shown(const json& v) {
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

/// Text after nlohmann's "[json.exception.x.n] " prefix and its "line 1, column n: ".
std::string json_error_text(const char* what) {
  std::string w = what;
  std::size_t p = w.find("] ");
  if (p != std::string::npos) w = w.substr(p + 2);
  std::size_t c = w.find("column ");
  if (c != std::string::npos) {
    std::size_t q = w.find(": ", c);
    if (q != std::string::npos) w = w.substr(q + 2);
  }
  return w;
}

}  // namespace

json JsonObjectLineParser::parse(std::string_view text) {
  keys_.clear();
  scopes_.clear();
  last_top_key_.clear();
  duplicate_.clear();
  auto callback = [this](int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: scopes_.push_back(keys_.size()); break;
      case json::parse_event_t::object_end:
        if (!scopes_.empty()) {
          keys_.resize(scopes_.back());
          scopes_.pop_back();
        }
        break;
      case json::parse_event_t::key: {
        const std::string& key = parsed.get_ref<const std::string&>();
        if (!scopes_.empty() && duplicate_.empty()) {
          for (std::size_t i = scopes_.back(); i < keys_.size(); ++i)
            if (keys_[i] == key)
              duplicate_ = scopes_.size() == 1 ? key : last_top_key_ + "." + key;
        }
        if (scopes_.size() == 1) last_top_key_ = key;
        keys_.push_back(key);
        break;
      }
      default: break;
    }
    return true;
  };
  json value;
  try {
    value = json::parse(text.begin(), text.end(), callback);
  } catch (const json::parse_error& e) {
    throw TraceFieldProblem{"", fmt::format("bad JSON at column {}: {}", e.byte,
                                            json_error_text(e.what()))};
  } catch (const json::out_of_range& e) {
    // A number too large for a double: nlohmann throws while reading the value
    // of the key it last reported.
    throw TraceFieldProblem{last_top_key_, json_error_text(e.what())};
  } catch (const json::exception& e) {
    throw TraceFieldProblem{"", fmt::format("bad JSON: {}", json_error_text(e.what()))};
  }
  if (!value.is_object())
    throw TraceFieldProblem{"", fmt::format("expected a JSON object, got {}", shown(value))};
  if (!duplicate_.empty()) throw TraceFieldProblem{duplicate_, "appears twice"};
  return value;
}

int64_t json_int64(const json& v, const char* field) {
  if (v.is_number_unsigned()) {
    uint64_t u = v.get<uint64_t>();
    if (u > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()))
      problem(field, fmt::format("{} is out of the int64 range", u));
    return static_cast<int64_t>(u);
  }
  if (v.is_number_integer()) return v.get<int64_t>();
  problem(field, fmt::format("expected an integer, got {}", shown(v)));
}

int32_t json_int32(const json& v, const char* field) {
  int64_t x = json_int64(v, field);
  if (x < std::numeric_limits<int32_t>::min() || x > std::numeric_limits<int32_t>::max())
    problem(field, fmt::format("{} is out of the int32 range", x));
  return static_cast<int32_t>(x);
}

double json_double(const json& v, const char* field) {
  if (!v.is_number()) problem(field, fmt::format("expected a number, got {}", shown(v)));
  double d = v.get<double>();
  if (!std::isfinite(d)) problem(field, fmt::format("{} is not finite", d));
  return d;
}

float json_float32(const json& v, const char* field) {
  double d = json_double(v, field);
  if (std::fabs(d) >= kFloat32OverflowBound)
    problem(field, fmt::format("{} overflows float32 (largest finite float32: {})", d, FLT_MAX));
  // Between FLT_MAX and the bound the nearest float32 is FLT_MAX; clamp so the
  // conversion below never sees an out-of-range value.
  if (std::fabs(d) > FLT_MAX) return d > 0 ? FLT_MAX : -FLT_MAX;
  return static_cast<float>(d);
}

void json_float32_array(const json& v, const char* field, float* out, std::size_t n) {
  if (!v.is_array() || v.size() != n)
    problem(field, fmt::format("expected an array of {} numbers, got {}", n, shown(v)));
  for (std::size_t i = 0; i < n; ++i) out[i] = json_float32(v[i], field);
}

Vec3f json_vec3(const json& v, const char* field) {
  float xyz[3];
  json_float32_array(v, field, xyz, 3);
  return {xyz[0], xyz[1], xyz[2]};
}

std::string json_string(const json& v, const char* field) {
  if (!v.is_string()) problem(field, fmt::format("expected a string, got {}", shown(v)));
  return v.get<std::string>();
}

void append_json_float(fmt::memory_buffer& out, float x) {
  // "-0" would read back as the integer 0 and lose the sign.
  if (x == 0.0f && std::signbit(x)) {
    fmt::format_to(std::back_inserter(out), "-0.0");
    return;
  }
  fmt::format_to(std::back_inserter(out), "{}", x);
}

void append_json_double(fmt::memory_buffer& out, double x) {
  if (x == 0.0 && std::signbit(x)) {
    fmt::format_to(std::back_inserter(out), "-0.0");
    return;
  }
  fmt::format_to(std::back_inserter(out), "{}", x);
}

void append_json_vec3(fmt::memory_buffer& out, Vec3f v) {
  out.push_back('[');
  append_json_float(out, v.x);
  out.push_back(',');
  append_json_float(out, v.y);
  out.push_back(',');
  append_json_float(out, v.z);
  out.push_back(']');
}

void append_json_string(fmt::memory_buffer& out, const std::string& s, const char* field) {
  std::string quoted;
  try {
    quoted = json(s).dump();
  } catch (const json::exception&) {
    problem(field, "is not valid UTF-8");
  }
  out.append(quoted.data(), quoted.data() + quoted.size());
}

}  // namespace vbsim
