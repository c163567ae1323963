// Replay run: a whole trace through a FunctionalReplayer, streamed, with the
// optional per-ray hits file (JSON Lines). Shared by `vbsim replay` and the
// system tests.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "replay/functional_replayer.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"
#include "trace/trace_source.h"

namespace vbsim {

/// A trace's scene, loaded with the header's transform, and its BVH.
struct SceneAndBvh {
  Scene scene;
  Bvh bvh;
};
/// `progress`, when given, sees the loading and building steps (progress/work_progress.h).
SceneAndBvh load_trace_scene(const TraceHeader& header, const BvhBuildOptions& bvh = {},
                             WorkProgress* progress = nullptr);

/// One line of the hits file: id, prim, t, u, v, front, rejected, and verdict
/// when scored; `reversed` for reverse-shadow rays (their t is along the
/// reversed ray, from the light).
std::string hit_json_line(const TraceRay& tr, const RayOutcome& out);
/// The same line appended to `line` (whose memory a caller can reuse).
void append_hit_json_line(std::string& line, const TraceRay& tr, const RayOutcome& out);

/// Runs `step` (which replays or emits the ray `source` returned last) and
/// turns a ParentWindowError into a TraceError at that ray, field 'parent'.
template <class Step>
auto replay_at_trace_ray(const TraceSource& source, Step&& step) -> decltype(step()) {
  try {
    return step();
  } catch (const ParentWindowError& e) {
    throw source.error_at_last_ray("parent", e.what());
  }
}

/// Called with the number of rays replayed so far, every kProgressRays rays.
using ReplayProgress = std::function<void(uint64_t rays)>;
constexpr uint64_t kProgressRays = 4096;

/// Replays every ray of `source` (whose scene is `sb`) and returns the stats.
/// Each ray's hit line goes to `hits` when it is not null. `stop` (may be
/// null) ends the run early; the stats are then marked partial. `progress`
/// (may be empty) is told how far the replay has come. Checks that every ray
/// read is counted (ConservationError otherwise).
/// With `threads` > 1 the rays are read in blocks, their lines parsed and the
/// rays replayed on that many threads (BlockReplay), and `stop` and `progress`
/// act between blocks; the statistics (but for wall_s), the hit lines and any
/// error are those of one thread.
ReplayStats run_replay(TraceSource& source, const SceneAndBvh& sb, const ReplayOptions& opt,
                       std::ostream* hits, const std::atomic<bool>* stop = nullptr,
                       const ReplayProgress& progress = {}, int threads = 1);

/// Throws OutputError "PATH: write failed: REASON" when `hits` is in a failed
/// state (a full disk): a run stops at its first failed write.
void check_hits_stream(const std::ostream& hits, const std::string& path);

/// The last line of a hits file whose run was stopped before the end of the
/// trace: {"partial":true,"rays":N}, N the ray lines before it.
std::string partial_hits_marker(uint64_t rays);

}  // namespace vbsim
