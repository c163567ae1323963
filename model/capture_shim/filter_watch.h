// Filter functions seen by the shim. The application's geometry filter
// functions (rtcSetGeometryIntersectFilterFunction / OccludedFilterFunction)
// reach Embree wrapped in one of a fixed set of trampolines: each calls the
// application's function with the same arguments (so the application computes
// what it computes without the shim) and counts, on the calling thread, the
// calls that rejected a candidate hit or changed it or the ray's tfar. A ray
// call that saw the count change had its answer changed by a filter, perhaps
// (Embree runs filters on the thread that traces). Filters in the intersect
// context are not wrapped (that would write to the application's context);
// the ray hooks mark every ray of such a call instead.
#pragma once
#include <embree3/rtcore.h>

#include <cstdint>

namespace vbsim::shim {

/// Geometry filter calls on the calling thread so far that rejected or changed a candidate hit.
uint64_t filter_changes_on_this_thread();

/// Distinct application filter functions that could not get a trampoline
/// (all in use): their calls are not counted, so the merge marks every ray.
uint64_t unwatched_filter_functions();

/// The RawRayFlag bits of a ray call: create before the call, read after it.
class FilterWatch {
 public:
  explicit FilterWatch(const RTCIntersectContext* ctx)
      : before_(filter_changes_on_this_thread()), context_filter_(ctx && ctx->filter) {}
  uint32_t flags() const;

 private:
  uint64_t before_;
  bool context_filter_;
};

}  // namespace vbsim::shim
