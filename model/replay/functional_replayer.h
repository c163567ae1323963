// FunctionalReplayer: untimed replay of trace rays, one at a time, in trace
// order: emission -> closest-hit search with the candidate filter -> verdict ->
// statistics. The same datapath the cycle-level model times.
//
// Memory: it keeps (o, d) of the last ReplayOptions::parent_window rays
// (ParentRayStore, about 40 bytes a ray) so that children can find their parent
// ray for intended origins and ray-equation hit points; a parent must precede
// its children in the trace, by at most that window, to be found. Nothing
// grows with the trace.
#pragma once
#include <cstdint>

#include "datapath/hit.h"
#include "replay/ray_emission.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

/// The outcome of one ray.
struct RayOutcome {
  Hit hit;                  ///< closest accepted hit (reverse-shadow: of the reversed ray)
  int32_t answer = -1;      ///< the method's answer: triangle, or -1 (shadow: occluder or -1)
  uint64_t rejected = 0;    ///< candidates the filter rejected for this ray
  bool scored = false;      ///< the trace had `expect`
  Verdict verdict = Verdict::Unscored;
  bool reversed = false;
};

/// Whether the search of `tr` (emitted as `er`) stops at the first accepted hit:
/// shadow rays, unless reversed (which need the closest hit to tell the parent
/// triangle from an occluder).
inline bool search_stops_at_any_hit(const ReplayOptions& opt, const TraceRay& tr, const EmittedRay& er) {
  return opt.any_hit_for_shadow && tr.kind == RayKind::Shadow && !er.reversed;
}

/// The outcome of a search that returned `hit` with `rejected` rejected
/// candidates for `tr` (emitted as `er`, whose `parent` gives the intended
/// origin): the method's answer and its verdict, counted into `ks`. A ray
/// marked `incomplete` is left unscored (counted in ks.incomplete_excluded)
/// unless `score_incomplete`.
RayOutcome conclude_ray(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected,
                        const Scene& scene, bool score_incomplete, KindStats& ks);

/// One ray through emission, the closest-hit search with `filter` (built from
/// opt.method) and the verdict, counted into `ks`. `parent` (may be null): the
/// ray `tr.parent` when it came before `tr`, for intended origins and
/// ray-equation hit points. Depends on nothing but its arguments: the same ray
/// and options give the same outcome whatever was replayed before.
RayOutcome replay_one_ray(const TraceRay& tr, const Scene& scene, const Bvh& bvh,
                          const ReplayOptions& opt, const CandidateFilter& filter,
                          const ParentRay* parent, KindStats& ks);

class FunctionalReplayer {
 public:
  /// `scene` and `bvh` must outlive the replayer. Throws when the BVH is too deep.
  FunctionalReplayer(const Scene& scene, const Bvh& bvh, const ReplayOptions& options);

  /// Replays one ray and adds it to the statistics. Precondition: the ray's
  /// triangle indices are in range for the scene (the trace readers check this).
  /// Throws ParentWindowError (before counting the ray) when its parent lies
  /// beyond the parent window.
  RayOutcome replay(const TraceRay& tr);

  // The three parts of replay(), for a timing model that runs the search
  // itself (hw/cycle_engine): emit() before the search (it looks the parent
  // up, throwing ParentWindowError as replay() does, and records the ray as a
  // possible parent), conclude() after it with the search's result.
  // Each ray must go through both, in trace order for emit().
  EmittedRay emit(const TraceRay& tr);
  /// Whether the search of `tr` (emitted as `er`) stops at the first accepted hit.
  bool any_hit(const TraceRay& tr, const EmittedRay& er) const {
    return search_stops_at_any_hit(opt_, tr, er);
  }
  /// The outcome of a search that returned `hit` with `rejected` rejected
  /// candidates; adds the ray to the statistics.
  RayOutcome conclude(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected);
  const CandidateFilter& filter() const { return filter_; }

  /// Keep parent rays for intended origins (default true; a benchmark on
  /// parentless rays turns it off).
  void set_track_parents(bool on) { track_parents_ = on; }
  ReplayStats& stats() { return stats_; }
  const ReplayOptions& options() const { return opt_; }

 private:
  const Scene& scene_;
  const Bvh& bvh_;
  ReplayOptions opt_;
  CandidateFilter filter_;
  ParentRayStore parents_;
  bool track_parents_ = true;
  ReplayStats stats_;
};

}  // namespace vbsim
