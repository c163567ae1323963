#include "trace/trace_json_values.h"

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>

#include "io/json_document.h"

namespace vbsim {

namespace {

using json = nlohmann::json;

/// The midpoint between FLT_MAX and 2^128: doubles above it round to infinity
/// in float32, and it is itself a tie (decided by the decimal it came from).
constexpr double kFloat32OverflowBound = 0x1.ffffffp127;

[[noreturn]] void problem(const char* field, std::string message) {
  throw TraceFieldProblem{field, std::move(message)};
}

/// A float32 tie as parse_json_object_line stores it: the double, then the float32.
constexpr std::size_t kTieBytes = sizeof(double) + sizeof(float);

json tie_value(double d, float nearest) {
  std::vector<uint8_t> bytes(kTieBytes);
  std::memcpy(bytes.data(), &d, sizeof d);
  std::memcpy(bytes.data() + sizeof d, &nearest, sizeof nearest);
  return json::binary(std::move(bytes));
}
bool is_tie_value(const json& v) { return v.is_binary() && v.get_binary().size() == kTieBytes; }
double tie_double(const json& v) {
  double d;
  std::memcpy(&d, v.get_binary().data(), sizeof d);
  return d;
}
float tie_float32(const json& v) {
  float f;
  std::memcpy(&f, v.get_binary().data() + sizeof(double), sizeof f);
  return f;
}

/// A short rendering of a JSON value for messages.
std::string shown(const json& v) {
  if (is_tie_value(v)) return fmt::format("{}", tie_double(v));
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

/// Text of a nlohmann exception without its "[json.exception.x.n] " prefix and
/// its "line 1, column n: " position (the caller reports the position itself).
std::string json_error_text(const std::string& what) {
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

/// Builds the DOM of one line from nlohmann's SAX events, so that a number's
/// text is at hand (for float32 ties) and a repeated key is seen when it arrives.
class LineSax {
 public:
  explicit LineSax(json& root) : root_(root) {}

  bool null() { return put(json(nullptr)); }
  bool boolean(bool v) { return put(json(v)); }
  bool number_integer(json::number_integer_t v) { return put(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return put(json(v)); }
  bool number_float(json::number_float_t v, const std::string& text) {
    // nlohmann wrote the locale's decimal point into `text`, as strtof expects.
    if (is_float32_tie(v)) return put(tie_value(v, std::strtof(text.c_str(), nullptr)));
    return put(json(v));
  }
  bool string(std::string& v) { return put(json(std::move(v))); }
  bool binary(json::binary_t&) { return fail("", "binary values are not JSON text"); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(std::string& k) {
    json& object = *stack_.back();
    if (stack_.size() == 1) top_key_ = k;
    key_path_ = stack_.size() == 1 ? k : top_key_ + "." + k;
    if (object.contains(k)) return fail(key_path_, "appears twice");
    key_ = std::move(k);
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    // Number overflow (id 406) comes after the number's key: name that field.
    if (e.id == 406) return fail(stack_.empty() ? "" : key_path_, json_error_text(e.what()));
    return fail("", fmt::format("bad JSON at column {}: {}", position, json_error_text(e.what())));
  }

  /// The first problem met, if any (parsing stops there).
  const TraceFieldProblem* problem() const { return failed_ ? &problem_ : nullptr; }

 private:
  bool put(json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
    } else if (stack_.back()->is_array()) {
      stack_.back()->push_back(std::move(v));
    } else {
      (*stack_.back())[key_] = std::move(v);
    }
    return true;
  }
  bool open(json&& container) {
    // The depth is bounded before the DOM grows (io/json_document.h): code that
    // walks or prints a value recurses once per level.
    if (stack_.size() >= static_cast<std::size_t>(kMaxJsonDepth))
      return fail(stack_.size() > 1 ? top_key_ : key_path_,
                  fmt::format("nested deeper than {} levels of arrays and objects", kMaxJsonDepth));
    json* slot;
    if (stack_.empty()) {
      root_ = std::move(container);
      slot = &root_;
    } else if (stack_.back()->is_array()) {
      stack_.back()->push_back(std::move(container));
      slot = &stack_.back()->back();
    } else {
      slot = &((*stack_.back())[key_] = std::move(container));
    }
    stack_.push_back(slot);  // stays valid: its parent grows only after it closes
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  bool fail(std::string field, std::string message) {
    if (!failed_) problem_ = TraceFieldProblem{std::move(field), std::move(message)};
    failed_ = true;
    return false;
  }

  json& root_;
  std::vector<json*> stack_;  ///< containers being filled, innermost last
  std::string key_;           ///< key of the next value in the innermost object
  std::string top_key_;       ///< latest key of the outermost object
  std::string key_path_;      ///< latest key, as "key" or "outer.key"
  bool failed_ = false;
  TraceFieldProblem problem_;
};

}  // namespace

bool is_float32_tie(double d) {
  double a = std::fabs(d);
  if (a == kFloat32OverflowBound) return true;
  if (!(a < FLT_MAX)) return false;  // beyond FLT_MAX only the bound itself is a tie
  float f = static_cast<float>(a);
  if (static_cast<double>(f) == a) return false;
  float other = static_cast<double>(f) < a ? std::nextafter(f, INFINITY) : std::nextafter(f, 0.0f);
  // The sum of two adjacent float32 values is exact in double, and so is the halving.
  return a == (static_cast<double>(f) + static_cast<double>(other)) * 0.5;
}

json parse_json_object_line(std::string_view text) {
  json value;
  LineSax sax(value);
  bool ok = json::sax_parse(text.begin(), text.end(), &sax, json::input_format_t::json, true);
  if (!ok || sax.problem()) {
    if (sax.problem()) throw *sax.problem();
    throw TraceFieldProblem{"", "bad JSON"};
  }
  if (!value.is_object())
    throw TraceFieldProblem{"", fmt::format("expected a JSON object, got {}", shown(value))};
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
  if (is_tie_value(v)) return tie_double(v);
  if (!v.is_number()) problem(field, fmt::format("expected a number, got {}", shown(v)));
  double d = v.get<double>();
  if (!std::isfinite(d)) problem(field, fmt::format("{} is not finite", d));
  return d;
}

float json_float32(const json& v, const char* field) {
  // Integers convert in one rounding (going through double could round twice).
  if (v.is_number_unsigned()) return static_cast<float>(v.get<uint64_t>());
  if (v.is_number_integer()) return static_cast<float>(v.get<int64_t>());
  double d = json_double(v, field);
  float f;
  if (is_tie_value(v)) {
    f = tie_float32(v);  // the decimal decides; strtof gives inf past the overflow bound
  } else if (std::fabs(d) > kFloat32OverflowBound) {
    f = static_cast<float>(d > 0 ? INFINITY : -INFINITY);
  } else if (std::fabs(d) > FLT_MAX) {
    f = d > 0 ? FLT_MAX : -FLT_MAX;  // nearest float32; avoids an out-of-range conversion
  } else {
    f = static_cast<float>(d);
  }
  if (std::isinf(f))
    problem(field, fmt::format("{} overflows float32 (largest finite float32: {})", d, FLT_MAX));
  return f;
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
  // A NUL byte (\u0000) would end the string for every C-string reader of it
  // (a kind's name, a scene's path): refused rather than read cut short.
  const std::string& s = v.get_ref<const std::string&>();
  if (s.find('\0') != std::string::npos)
    problem(field, fmt::format("a NUL byte (\\u0000) inside the string {}", shown(v)));
  return s;
}

void append_json_float(fmt::memory_buffer& out, float x) {
  // "-0" would read back as the integer 0 and lose the sign.
  if (x == 0.0f && std::signbit(x)) {
    fmt::format_to(std::back_inserter(out), "-0.0");
    return;
  }
  char text[32];
  char* end = fmt::format_to_n(text, sizeof text - 1, "{}", x).out;
  *end = '\0';
  // A reader that parses a double and rounds it to float32 (Python's json with
  // numpy, JavaScript) misreads the rare shortest decimal whose double is a
  // float32 tie; print the float32's exact double value for those instead.
  if (is_float32_tie(std::strtod(text, nullptr))) {
    fmt::format_to(std::back_inserter(out), "{}", static_cast<double>(x));
    return;
  }
  out.append(text, end);
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
