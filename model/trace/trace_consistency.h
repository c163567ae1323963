// TraceConsistencyChecker: the rules that relate a ray to the rays before it
// and to the scene, which the per-ray format rules (trace_validation.h) cannot
// see. Streaming, bounded state; shared by `vbsim check`, replay, oracle and
// convert (through CheckedTraceSource). What each check decides and the
// tolerances: docs/trace-format.md, "Consistency checks".
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "datapath/triangle.h"
#include "trace/parent_order_check.h"
#include "trace/trace_record.h"

namespace vbsim {

/// The consistency checks, in report order.
enum class TraceCheck : uint8_t {
  ChildBeforeParent,  ///< error: a parent must precede its children
  IdOrder,            ///< warning: an id not greater than the one before
  ParentData,         ///< warning: parent fields that disagree with the parent ray or triangle
  Sign,               ///< warning: a given sign bit that contradicts dot(d, Ng(parent_prim))
  MissingExpect,      ///< warning: no expect (scoring needs `vbsim oracle`)
};
constexpr int kTraceCheckCount = 5;

/// Snake-case name, as in statistics JSON ("child_before_parent", ...).
const char* trace_check_name(TraceCheck check);
/// Only ChildBeforeParent is an error; the others are counted warnings.
bool trace_check_is_error(TraceCheck check);

struct TraceFinding {
  TraceCheck check;
  std::string field;    ///< the field at fault, e.g. "parent_t"
  std::string message;  ///< without the location
};

/// Relative tolerances of the geometric checks.
struct TraceCheckTolerances {
  /// A child's o may differ from its parent's hit point (the parent ray at
  /// parent_t, or the point at parent_uv) by this fraction of the point's
  /// magnitude per axis: 2^-10 admits any rounding and a renderer's own
  /// small offsets, and catches a wrong parent, t or triangle.
  float point = 1.0f / 1024.0f;
  /// parent_uv may leave the triangle by this much (barycentric units).
  float barycentric = 1.0f / 1024.0f;
  /// A given sign contradicts the normal only when |dot(d, Ng)| exceeds this
  /// fraction of |d| |v1-v0| |v2-v0| (float32 rounding of any writer stays
  /// far below it; nearer to the plane the sign is not decided).
  double sign = 1.0 / 65536.0;
};

class TraceConsistencyChecker {
 public:
  struct Options {
    std::size_t window = ParentOrderCheck::kDefaultWindow;  ///< recent rays kept
    /// The scene's triangles, for the checks against parent_prim; null skips them.
    const std::vector<Triangle>* triangles = nullptr;
    TraceCheckTolerances tolerances;
  };

  explicit TraceConsistencyChecker(const Options& options);

  /// Checks the next ray of the trace (already valid on its own: the readers
  /// ran check_trace_ray) and appends what is wrong to `out`. `position` is
  /// the caller's locator of the ray (line or record), used in messages about
  /// an earlier ray; `position_word` names it ("line", "record").
  void check(const TraceRay& ray, int64_t position, const char* position_word,
             std::vector<TraceFinding>& out);

  /// Children whose parent was not among the recent rays: their parent data
  /// was not checked (the parent is older than the window or not in the trace).
  int64_t parents_not_checked() const { return parents_not_checked_; }
  /// Children whose order against their parent could not be decided.
  int64_t order_unchecked() const { return order_.unchecked(); }
  std::size_t window() const { return order_.window().capacity(); }

 private:
  /// What the checks need of a recent ray.
  struct RecentRay {
    Vec3f o, d;
    float tmin, tmax;
    RayKind kind;
  };
  void check_parent_data(const TraceRay& ray, const RecentRay* parent, std::vector<TraceFinding>& out) const;
  void check_sign(const TraceRay& ray, std::vector<TraceFinding>& out) const;

  Options opt_;
  ParentOrderCheck order_;
  std::vector<RecentRay> recent_;  ///< indexed by the order check's window slots
  int64_t last_id_ = -1;
  bool any_ray_ = false;
  int64_t parents_not_checked_ = 0;
};

}  // namespace vbsim
