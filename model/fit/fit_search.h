// Fit search: for one parameter, the smallest grid value at which no ray of the
// traces has a self_hit or is missed, or the rays proving that none exists.
//
// Per ray, the search assumes monotone verdicts along the grid: a self_hit at
// small values gives way to an acceptable answer, then to a miss at large
// values. It finds by bisection each ray's lowest acceptable index a (no
// self_hit from there on) and highest acceptable index b (no miss up to there),
// then intersects: [max a, min b]. For the validity-bit epsilons and tmin the
// assumption holds by construction (a larger value only rejects more
// candidates, so the closest accepted hit moves away); for the origin offsets
// it need not, so the answer is checked by replaying every ray at it and just
// below it, and the check is reported.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fit/fit_parameter.h"
#include "replay/replay_run.h"
#include "trace/trace_blocks.h"
#include "trace/trace_record.h"

namespace vbsim {

/// A trace held in memory with its scene, for repeated replays of single rays.
struct FitTrace {
  std::string path;
  std::unique_ptr<TraceSource> file;    ///< the trace file's reader
  std::unique_ptr<TraceSource> source;  ///< `file` through the consistency checks (a child after its parent)
  SceneAndBvh scene;
  std::unique_ptr<TraceBlocks> blocks;  ///< one block: every ray of the trace
  const std::vector<TraceRay>& rays() const { return blocks->rays(); }
};

/// Reads a whole trace and loads its scene. Throws TraceError.
FitTrace load_fit_trace(const std::string& path);

/// A ray named in a report.
struct FitRay {
  std::string trace;
  int64_t id = -1;
  std::string kind;
};

struct FitResult {
  std::string key, description;
  uint64_t rays = 0;      ///< scored rays searched
  double searched_low = 0, searched_high = 0;  ///< grid values of index 1 and the top
  double resolution = 0;  ///< relative step of a geometric grid (0: integers)
  bool feasible = false;
  bool self_hit_at_top = false;  ///< a ray self-hits even at the largest value searched
  bool missed_at_zero = false;   ///< a ray is missed even at 0
  // Lower end: the smallest grid index with no self_hit on any ray, and the ray
  // that needs it (self-hits one grid step below). Index top+1: none in range.
  int lowest_index = 0;
  double lowest = 0.0, below = 0.0;  ///< value at lowest_index and one step below
  FitRay needs_at_least;             ///< empty trace when no ray self-hits at 0
  // Upper end: the largest grid index at which no ray is missed, and the ray
  // missed one step above. Index -1: missed even at 0.
  int highest_index = 0;
  double highest = 0.0, above = 0.0;
  FitRay needs_at_most;              ///< empty trace when no ray is missed at the top
  // The check (when feasible): every ray replayed at `lowest` and one step
  // below. Rays that fail at `lowest` (not monotone) move the answer up to the
  // next grid value where every ray passes, `repaired`, if there is one.
  bool checked = false;
  std::vector<FitRay> check_failures;  ///< the first 10 rays (trace, id order) with self_hit or missed at `lowest`
  int repaired_index = -1;             ///< -1: not needed, or none up to `highest` passes (then not feasible)
  double repaired = 0.0;
  // Counts at the answer (`repaired` when found, else `lowest`), and at `below`.
  uint64_t check_self_hit = 0, check_missed = 0, check_false_hit = 0;
  uint64_t below_self_hit = 0;
};

/// Searches one parameter over every scored ray of `traces` on `threads` threads.
FitResult fit_parameter(const FitParameter& param, const std::vector<FitTrace>& traces, int threads);

}  // namespace vbsim
