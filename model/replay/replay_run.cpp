#include "replay/replay_run.h"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "io/atomic_output_file.h"
#include "replay/ray_conservation.h"
#include "trace/trace_source.h"

namespace vbsim {

SceneAndBvh load_trace_scene(const TraceHeader& header, const BvhBuildOptions& bvh) {
  SceneAndBvh sb;
  sb.scene = load_scene(header.scene_path, header.transform);
  sb.bvh = build_bvh(sb.scene, bvh);
  return sb;
}

std::string hit_json_line(const TraceRay& tr, const RayOutcome& out) {
  std::string s = fmt::format("{{\"id\":{},\"prim\":{}", tr.id, out.hit.prim);
  if (out.hit.prim >= 0)
    s += fmt::format(",\"t\":{},\"u\":{},\"v\":{},\"front\":{}", out.hit.t, out.hit.u, out.hit.v,
                     out.hit.front);
  s += fmt::format(",\"rejected\":{}", out.rejected);
  if (out.reversed) s += ",\"reversed\":true";
  if (out.scored) s += fmt::format(",\"verdict\":\"{}\"", verdict_name(out.verdict));
  s += "}\n";
  return s;
}

void check_hits_stream(const std::ostream& hits, const std::string& path) {
  if (!hits) throw OutputError(path, fmt::format("write failed: {}", errno ? std::strerror(errno) : "I/O error"));
}

std::string partial_hits_marker(uint64_t rays) { return fmt::format("{{\"partial\":true,\"rays\":{}}}\n", rays); }

ReplayStats run_replay(TraceSource& source, const SceneAndBvh& sb, const ReplayOptions& opt,
                       std::ostream* hits, const std::atomic<bool>* stop, const ReplayProgress& progress) {
  source.set_triangle_count(sb.scene.size());
  FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
  const auto start = std::chrono::steady_clock::now();
  TraceRay tr;
  uint64_t rays_read = 0;
  while (source.next(tr)) {
    ++rays_read;
    const RayOutcome out = replay_at_trace_ray(source, [&] { return replayer.replay(tr); });
    if (hits) {
      *hits << hit_json_line(tr, out);
      check_hits_stream(*hits, "hits output");
    }
    if (progress && rays_read % kProgressRays == 0) progress(rays_read);
    if (stop && stop->load(std::memory_order_relaxed)) {
      replayer.stats().partial = true;
      break;
    }
  }
  ReplayStats stats = replayer.stats();
  stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  check_ray_conservation(source.path(), rays_read, stats.total().rays);
  return stats;
}

}  // namespace vbsim
