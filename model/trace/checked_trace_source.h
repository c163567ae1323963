// CheckedTraceSource: a TraceSource that passes another one's rays through
// the consistency checks (trace_consistency.h). An error (a child before its
// parent) is thrown as a TraceError naming the file, line or record and field;
// warnings are counted, with the first of each kind kept in full. Replay
// (both modes), oracle and convert read their traces through it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "trace/trace_consistency.h"
#include "trace/trace_source.h"

namespace vbsim {

class TextTraceReader;

class CheckedTraceSource final : public TraceSource {
 public:
  /// `inner` must outlive this source. `options.triangles` may be null (the
  /// checks against the scene are then skipped, e.g. in convert).
  CheckedTraceSource(TraceSource& inner, const TraceConsistencyChecker::Options& options);

  const TraceHeader& header() const override { return inner_.header(); }
  /// The inner source's next ray, checked. Throws TraceError on a format error
  /// (from the inner source) or a consistency error.
  bool next(TraceRay& out) override;
  void set_triangle_count(int32_t n) override { inner_.set_triangle_count(n); }
  void set_parse_threads(int threads) override { inner_.set_parse_threads(threads); }
  int64_t ids_not_checked() const override { return inner_.ids_not_checked(); }
  const std::string& path() const override { return inner_.path(); }
  TraceError error_at_last_ray(const std::string& field, const std::string& message) const override {
    return inner_.error_at_last_ray(field, message);
  }

  /// Rays that raised `check` so far.
  int64_t count(TraceCheck check) const { return counts_[static_cast<int>(check)]; }
  /// "file:line: field 'f': message" of the first ray that raised `check`, or empty.
  const std::string& first(TraceCheck check) const { return first_[static_cast<int>(check)]; }
  const TraceConsistencyChecker& checker() const { return checker_; }

  /// The counts as statistics JSON: {"window", "warnings": {name: n}, "first": {name: text},
  /// "parents_not_checked", "order_unchecked", "ids_not_checked"}.
  nlohmann::json summary_json() const;
  /// One line per warning kind that occurred (missing expect only when
  /// `with_missing_expect`), each prefixed with `program` ("vbsim replay").
  std::string warning_lines(const std::string& program, bool with_missing_expect) const;

 private:
  TraceSource& inner_;
  TraceConsistencyChecker checker_;
  const char* position_word_;  ///< "line" for a text trace, "record" otherwise
  const TextTraceReader* text_ = nullptr;  ///< set when the inner source is text (its line numbers)
  int64_t rays_ = 0;
  std::vector<TraceFinding> findings_;
  std::array<int64_t, kTraceCheckCount> counts_{};
  std::array<std::string, kTraceCheckCount> first_;
};

/// Where the ray last returned by `source` sits: its text line, or for binary
/// and rtcore files its 0-based record index (`rays_read` - 1).
int64_t last_ray_position(const TraceSource& source, int64_t rays_read);
/// "line" for a text trace, "record" for the other forms.
const char* position_word(const TraceSource& source);

}  // namespace vbsim
