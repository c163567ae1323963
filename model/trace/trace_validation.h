// The format's rules for one ray, shared by every reader (so text, binary and
// rtcore files reject the same things with the same words) and by the writers
// (so they never produce a file a reader would reject).
#pragma once
#include <cstdint>
#include <unordered_set>

#include "trace/trace_error.h"
#include "trace/trace_record.h"

namespace vbsim {

/// Checks one ray on its own: id >= 0, parent >= -1, a known kind (not
/// primary when a parent is given), finite
/// origin, finite non-zero direction, 0 <= tmin <= tmax (tmax may be +inf,
/// never NaN), parent_prim and expect.prim in [-1, triangle_count) (upper bound
/// skipped when triangle_count is -1), finite optional values, sign 0/1/absent,
/// expect.t only with a hit in expect, known incomplete bits. On failure fills `problem`, returns false.
bool check_trace_ray(const TraceRay& ray, int32_t triangle_count, TraceFieldProblem& problem);

/// The ids seen so far, to reject duplicates. Ids arriving in order k, k+1,
/// k+2, ... from any first id k cost no memory (one dense run); others go to a
/// hash set (O(rays) ints at worst) until the run reaches them.
class TraceIdSet {
 public:
  /// Adds `id` (>= 0); false when it was already present.
  bool insert(int64_t id);
  /// Whether `id` has been added.
  bool contains(int64_t id) const {
    return (id >= dense_begin_ && id < dense_end_) || sparse_.count(id) != 0;
  }

 private:
  int64_t dense_begin_ = -1, dense_end_ = -1;  ///< every id in [begin, end) has been seen; -1: none yet
  std::unordered_set<int64_t> sparse_;  ///< seen ids outside [begin, end)
};

/// check_trace_ray plus the duplicate-id rule, over a stream of rays.
class TraceRayValidator {
 public:
  /// See TraceSource::set_triangle_count; -1 = unknown.
  void set_triangle_count(int32_t n) { triangle_count_ = n; }
  int32_t triangle_count() const { return triangle_count_; }
  /// Checks `ray` and records its id; false (with `problem`) when it breaks a rule.
  bool check(const TraceRay& ray, TraceFieldProblem& problem);

 private:
  int32_t triangle_count_ = -1;
  TraceIdSet ids_;
};

}  // namespace vbsim
