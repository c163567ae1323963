// Filter functions seen by the shim. The application's filter functions, set
// on a geometry (rtcSetGeometryIntersectFilterFunction / OccludedFilterFunction)
// or carried by the intersect context of a call (RTCIntersectContext::filter),
// reach Embree wrapped in one of a fixed set of trampolines: each calls the
// application's function with the same arguments (so the application computes
// what it computes without the shim) and compares, lane by lane, the valid
// mask, the candidate hit and the ray's tfar before and after. A ray call
// creates a FilterWatch for its duration; the trampolines report to the
// calling thread's innermost watch (Embree runs filters on the thread that
// traces; a filter that traces rays itself opens a watch of its own), which
// keeps per ray lane:
//   - the candidates the filters rejected (a valid lane cleared), when they
//     are all on one primitive (a renderer's self-exclusion of the ray's
//     parent primitive, Cycles' way): kRawFilterRejected and the ids;
//   - anything else that changed the answer (a changed hit or tfar,
//     rejections on several primitives, a filter call whose lanes cannot be
//     matched to the call's rays): kRawFilterChanged.
// A filter that accepts the hit as Embree found it changes nothing and is not
// recorded. The context's filter pointer is swapped for its trampoline during
// the call and restored after it.
#pragma once
#include <embree3/rtcore.h>

#include <cstdint>

#include "capture/raw_capture_format.h"

namespace vbsim::shim {

/// Distinct application filter functions that could not get a trampoline
/// (all in use): their calls are not seen, so the merge marks every ray.
uint64_t unwatched_filter_functions();

/// The trampoline that calls `f` (null stays null); `f` itself when every trampoline is taken.
RTCFilterFunctionN watched_filter(RTCFilterFunctionN f);

class FilterWatch {
 public:
  static constexpr unsigned kMaxLanes = 16;  ///< Embree's widest packet

  /// Watches one ray call on `lanes` rays whose lane i is the filters' lane i
  /// (1 for a single-ray call, W for a W-wide packet); `attributable` false
  /// for calls whose filter lanes do not map onto the call's rays (streams).
  FilterWatch(RTCIntersectContext* ctx, unsigned lanes, bool attributable);
  ~FilterWatch();
  FilterWatch(const FilterWatch&) = delete;
  FilterWatch& operator=(const FilterWatch&) = delete;

  /// Fills the filter fields of lane `lane`'s record (flags, rejected ids, rejections).
  void describe(unsigned lane, capture::RawRay& r) const;

  /// Called by the trampolines: filter call with `n` lanes rejected
  /// (geom, prim, inst) in lane `lane`, or changed the answer otherwise.
  void rejected(unsigned n, unsigned lane, uint32_t geom, uint32_t prim, uint32_t inst);
  void changed(unsigned n, unsigned lane);

  /// The calling thread's innermost watch, or null outside a ray call.
  static FilterWatch* current();

 private:
  struct Lane {
    uint32_t geom = capture::kInvalidId, prim = capture::kInvalidId, inst = capture::kInvalidId;
    uint32_t rejections = 0;
    bool changed = false;
  };
  bool maps(unsigned n, unsigned lane) const { return attributable_ && n == lanes_ && lane < lanes_; }

  Lane lane_[kMaxLanes];
  unsigned lanes_;
  bool attributable_;
  bool unmatched_ = false;         ///< a filter call whose lanes could not be matched: every ray changed
  bool context_unwatched_ = false; ///< the context's filter could not be wrapped
  RTCIntersectContext* ctx_;
  RTCFilterFunctionN context_filter_ = nullptr;  ///< the application's, restored on destruction
  FilterWatch* outer_;
};

}  // namespace vbsim::shim
