// A replay against the capturing renderer's own answers: a `vbsim replay
// --hits` file compared ray by ray with a capture's embree_hits.jsonl, or with
// the `reference` answers a trace carries (both in trace order), streamed. For every ray where the replay's
// answer differs from Embree's it gives both answers and the replay's verdict
// from the oracle (the trace's `expect`): with a scored trace this says, per
// ray, whether the hardware would have rendered what the renderer rendered,
// and if not, whether the oracle sides with the replay (`correct`: Embree's
// answer was the rounded one) or with Embree.
#pragma once
#include <cstdint>
#include <map>
#include <ostream>
#include <string>

namespace vbsim::capture {

struct ReferenceComparison {
  int64_t rays = 0;
  int64_t agree = 0;             ///< the same answer (occluded or not; the same triangle or distance)
  int64_t agree_same_t = 0;      ///< of those, another triangle at Embree's distance (a shared edge or vertex)
  int64_t differ = 0;
  int64_t differ_outside = 0;    ///< of those, Embree hit geometry outside the trace (an incomplete ray)
  std::map<std::string, int64_t> differ_by_verdict;  ///< the replay's verdict ("unscored" without expect)
};

/// Compares the files (`reference_path`: embree_hits.jsonl, or a trace whose
/// rays carry `reference`); writes one JSON line per differing ray to `differences`
/// (may be null): {"id", "verdict", "replay": {"prim", "t"}, "reference": {...}}.
/// Throws std::runtime_error naming the file and line on a malformed line, a
/// stopped replay's hits, or ids that do not pair up.
ReferenceComparison compare_with_reference(const std::string& hits_path, const std::string& reference_path,
                                           std::ostream* differences);

}  // namespace vbsim::capture
