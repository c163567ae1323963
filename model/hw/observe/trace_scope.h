// TraceScope: which module instances a VCD or timeline records
// (`--trace-scope`). A scope is a comma-separated list of patterns; an
// instance is recorded when a pattern names it or one of its parents in the
// hierarchy:
//   accelerator.core_1     core_1 and every instance below it
//                          (accelerator.core_1.l1, ...), not core_10
//   accelerator.core_*     every core and what is below them ('*' stands for
//                          any characters within one level: never a '.')
// An empty scope records every instance. A scope that names no instance of the
// design is an error (TraceScope::check), so that a typo does not write an
// empty file.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace vbsim::hw {

/// A scope that names no instance: what() names it and lists the instances.
struct TraceScopeError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

class TraceScope {
 public:
  TraceScope() = default;
  /// Throws TraceScopeError for an empty pattern in the list ("a,,b").
  explicit TraceScope(const std::string& scope);

  bool empty() const { return patterns_.empty(); }
  /// Whether `instance` (a hierarchical name, "accelerator.core_1.l1") is recorded.
  bool matches(const std::string& instance) const;
  /// Throws TraceScopeError naming each pattern that matches none of
  /// `instances`, with the instances' names (the first 40) as a hint.
  void check(const std::vector<std::string>& instances) const;
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  std::vector<std::string> patterns_;
};

/// Whether `pattern` ('*': any characters but '.') names `instance` or one of its parents.
bool scope_pattern_matches(const std::string& pattern, const std::string& instance);

}  // namespace vbsim::hw
