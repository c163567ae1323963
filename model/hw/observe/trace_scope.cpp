#include "hw/observe/trace_scope.h"

#include <fmt/format.h>

namespace vbsim::hw {

namespace {

/// Whether `pattern` matches all of `name` ('*': any run of characters but '.').
bool glob(const char* pattern, const char* name) {
  for (; *pattern; ++pattern, ++name) {
    if (*pattern == '*') {
      for (const char* n = name;; ++n) {
        if (glob(pattern + 1, n)) return true;
        if (*n == '\0' || *n == '.') return false;
      }
    }
    if (*name != *pattern) return false;
  }
  return *name == '\0';
}

}  // namespace

bool scope_pattern_matches(const std::string& pattern, const std::string& instance) {
  // The instance itself, or any parent: the name cut before each '.'.
  for (size_t end = 0; end != std::string::npos;) {
    end = instance.find('.', end == 0 ? 0 : end + 1);
    if (glob(pattern.c_str(), instance.substr(0, end).c_str())) return true;
  }
  return false;
}

TraceScope::TraceScope(const std::string& scope) : text_(scope) {
  if (scope.empty()) return;
  size_t at = 0;
  for (;;) {
    const size_t comma = scope.find(',', at);
    const std::string p = scope.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    if (p.empty()) throw TraceScopeError(fmt::format("trace scope '{}': an empty pattern in the list", scope));
    patterns_.push_back(p);
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
}

bool TraceScope::matches(const std::string& instance) const {
  if (patterns_.empty()) return true;
  for (const std::string& p : patterns_)
    if (scope_pattern_matches(p, instance)) return true;
  return false;
}

void TraceScope::check(const std::vector<std::string>& instances) const {
  std::string unmatched;
  for (const std::string& p : patterns_) {
    bool any = false;
    for (const std::string& i : instances) any = any || scope_pattern_matches(p, i);
    if (!any) unmatched += (unmatched.empty() ? "'" : ", '") + p + "'";
  }
  if (unmatched.empty()) return;
  std::string names;
  for (size_t i = 0; i < instances.size() && i < 40; ++i) names += (i ? ", " : "") + instances[i];
  if (instances.size() > 40) names += fmt::format(", ... ({} in all)", instances.size());
  throw TraceScopeError(fmt::format(
      "trace scope {} names no instance of the design (a pattern names an instance by its full hierarchical "
      "name, or with '*' for any characters within one level, e.g. accelerator.core_*); instances: {}",
      unmatched, names));
}

}  // namespace vbsim::hw
