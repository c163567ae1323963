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

namespace vbsim {

class TraceSource;

/// A trace's scene, loaded with the header's transform, and its BVH.
struct SceneAndBvh {
  Scene scene;
  Bvh bvh;
};
SceneAndBvh load_trace_scene(const TraceHeader& header);

/// One line of the hits file: id, prim, t, u, v, front, rejected, and verdict
/// when scored; `reversed` for reverse-shadow rays (their t is along the
/// reversed ray, from the light).
std::string hit_json_line(const TraceRay& tr, const RayOutcome& out);

/// Called with the number of rays replayed so far, every kProgressRays rays.
using ReplayProgress = std::function<void(uint64_t rays)>;
constexpr uint64_t kProgressRays = 4096;

/// Replays every ray of `source` (whose scene is `sb`) and returns the stats.
/// Each ray's hit line goes to `hits` when it is not null. `stop` (may be
/// null) ends the run early; the stats are then marked partial. `progress`
/// (may be empty) is told how far the replay has come.
ReplayStats run_replay(TraceSource& source, const SceneAndBvh& sb, const ReplayOptions& opt,
                       std::ostream* hits, const std::atomic<bool>* stop = nullptr,
                       const ReplayProgress& progress = {});

}  // namespace vbsim
