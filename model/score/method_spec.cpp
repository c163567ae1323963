#include "score/method_spec.h"

#include <fmt/format.h>

#include <cstdlib>
#include <map>
#include <sstream>

#include "replay/replay_config.h"

namespace vbsim {

namespace {

enum class ValueKind { Number, Integer, Text, Tests };

struct KeyTarget {
  const char* path[2];  ///< config field (one or two levels)
  ValueKind kind;
};

const std::map<std::string, KeyTarget>& spec_keys() {
  static const std::map<std::string, KeyTarget> keys = {
      {"tmin-eps", {{"tmin_eps", nullptr}, ValueKind::Number}},
      {"offset-normal-eps", {{"offset_normal_eps", nullptr}, ValueKind::Number}},
      {"offset-direction-eps", {{"offset_direction_eps", nullptr}, ValueKind::Number}},
      {"adaptive-origin", {{"adaptive", "origin"}, ValueKind::Number}},
      {"adaptive-float-scale", {{"adaptive", "float_scale"}, ValueKind::Number}},
      {"adaptive-int-scale", {{"adaptive", "int_scale"}, ValueKind::Number}},
      {"vb-policy", {{"validity_bit", "policy"}, ValueKind::Text}},
      {"vb-eps-mode", {{"validity_bit", "eps_mode"}, ValueKind::Text}},
      {"vb-eps", {{"validity_bit", "eps"}, ValueKind::Number}},
      {"vb-guard-bits", {{"validity_bit", "guard_bits"}, ValueKind::Integer}},
      {"vb-min-exponent", {{"validity_bit", "min_exponent"}, ValueKind::Integer}},
      {"vb-component-scale", {{"validity_bit", "component_scale"}, ValueKind::Number}},
      {"vb-tests", {{"validity_bit", "tests"}, ValueKind::Tests}},
      {"hitpoint", {{"hitpoint", nullptr}, ValueKind::Text}},
  };
  return keys;
}

[[noreturn]] void fail(const std::string& entry, const std::string& why) {
  throw ConfigError(fmt::format("method entry '{}': {}", entry, why));
}

nlohmann::json parse_value(const std::string& entry, const std::string& key, const std::string& text,
                           ValueKind kind) {
  if (kind == ValueKind::Text) return text;
  if (kind == ValueKind::Tests) {
    nlohmann::json tests = {{"normal", false}, {"ray", false}, {"component", false}};
    std::stringstream in(text);
    std::string t;
    while (std::getline(in, t, '+')) {
      if (!tests.contains(t)) fail(entry, fmt::format("key '{}': unknown test '{}'", key, t));
      tests[t] = true;
    }
    return tests;
  }
  char* end = nullptr;
  if (kind == ValueKind::Integer) {
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0') fail(entry, fmt::format("key '{}': '{}' is not an integer", key, text));
    return v;
  }
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') fail(entry, fmt::format("key '{}': '{}' is not a number", key, text));
  return v;
}

}  // namespace

nlohmann::json method_spec_json(const std::string& entry) {
  std::stringstream in(entry);
  std::string part;
  std::getline(in, part, ':');
  if (part.empty()) fail(entry, "no method name");
  nlohmann::json j;
  j["method"] = part;
  while (std::getline(in, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0) fail(entry, fmt::format("'{}' is not KEY=VALUE", part));
    const std::string key = part.substr(0, eq);
    const auto it = spec_keys().find(key);
    if (it == spec_keys().end()) fail(entry, fmt::format("unknown key '{}'", key));
    const KeyTarget& target = it->second;
    nlohmann::json& field = target.path[1] ? j[target.path[0]][target.path[1]] : j[target.path[0]];
    field = parse_value(entry, key, part.substr(eq + 1), target.kind);
  }
  return j;
}

MethodSpec parse_method_spec(const std::string& entry) {
  MethodSpec spec;
  spec.label = entry;
  if (entry == kRendererMethod) {  // the renderer's own answers, judged as they are
    spec.options.reference_answers = true;
    return spec;
  }
  apply_replay_config(method_spec_json(entry), fmt::format("method entry '{}'", entry), spec.options);
  return spec;
}

std::vector<MethodSpec> parse_method_list(const std::string& list) {
  std::vector<MethodSpec> out;
  std::stringstream in(list);
  std::string entry;
  while (std::getline(in, entry, ',')) {
    if (entry.empty()) throw ConfigError(fmt::format("method list '{}': empty entry", list));
    out.push_back(parse_method_spec(entry));
  }
  if (out.empty()) throw ConfigError("method list is empty");
  return out;
}

const std::vector<std::string>& default_score_methods() {
  static const std::vector<std::string> methods = {
      "none",
      "tmin",
      "primid",
      "tmin+primid",
      "offset-normal",
      "offset-direction",
      "offset-adaptive",
      "offset-adaptive+primid",
      "offset-errbound",
      "validity-bit",
      "validity-bit:vb-policy=vote",
      "validity-bit:vb-guard-bits=2",
      "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4",
      "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4:vb-policy=vote",
      "sign-only",
      "shading-position",
      "shading-position-always",
      "shading-position+offset-adaptive",
      "reverse-shadow",
  };
  return methods;
}

}  // namespace vbsim

namespace vbsim {

std::string default_score_method_list() {
  std::string s;
  for (const std::string& m : default_score_methods()) s += (s.empty() ? "" : ",") + m;
  return s;
}

}  // namespace vbsim
