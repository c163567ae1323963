// The format's rules for one ray, shared by every reader (so text, binary and
// rtcore files reject the same things with the same words) and by the writers
// (so they never produce a file a reader would reject).
#pragma once
#include <cstdint>

#include "trace/trace_error.h"
#include "trace/trace_id_set.h"
#include "trace/trace_record.h"

namespace vbsim {

/// Checks one ray on its own: id >= 0, parent >= -1, a known kind (not
/// primary when a parent is given), finite
/// origin, finite non-zero direction, 0 <= tmin <= tmax (tmax may be +inf,
/// never NaN), parent_prim and expect.prim in [-1, triangle_count) (upper bound
/// skipped when triangle_count is -1), finite optional values, sign 0/1/absent,
/// expect.t only with a hit in expect, known incomplete bits. On failure fills `problem`, returns false.
bool check_trace_ray(const TraceRay& ray, int32_t triangle_count, TraceFieldProblem& problem);

/// check_trace_ray plus the duplicate-id rule, over a stream of rays.
class TraceRayValidator {
 public:
  /// See TraceSource::set_triangle_count; -1 = unknown.
  void set_triangle_count(int32_t n) { triangle_count_ = n; }
  int32_t triangle_count() const { return triangle_count_; }
  /// Checks `ray` and records its id; false (with `problem`) when it breaks a rule.
  bool check(const TraceRay& ray, TraceFieldProblem& problem);
  /// Rays whose id could not be checked against every earlier id (it fell in
  /// a merged range of the bounded id record, trace_id_set.h): a duplicate of
  /// an id that far back is not seen. 0 whenever the ids come in few runs.
  int64_t ids_not_checked() const { return ids_not_checked_; }

 private:
  int32_t triangle_count_ = -1;
  TraceIdSet ids_;
  int64_t ids_not_checked_ = 0;
};

}  // namespace vbsim
