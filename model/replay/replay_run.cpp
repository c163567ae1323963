#include "replay/replay_run.h"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>
#include <iterator>

#include "io/atomic_output_file.h"
#include "replay/block_replay.h"
#include "replay/ray_conservation.h"
#include "scene/triangle_masks.h"
#include "trace/trace_blocks.h"
#include "trace/trace_source.h"

namespace vbsim {

SceneAndBvh load_trace_scene(const TraceHeader& header, const BvhBuildOptions& bvh, WorkProgress* progress) {
  SceneAndBvh sb;
  sb.scene = load_header_scene(header, progress);
  sb.bvh = build_bvh(sb.scene, bvh, progress);
  return sb;
}

void append_hit_json_line(std::string& s, const TraceRay& tr, const RayOutcome& out) {
  auto to = std::back_inserter(s);
  fmt::format_to(to, "{{\"id\":{},\"prim\":{}", tr.id, out.hit.prim);
  if (out.hit.prim >= 0)
    fmt::format_to(to, ",\"t\":{},\"u\":{},\"v\":{},\"front\":{}", out.hit.t, out.hit.u, out.hit.v, out.hit.front);
  fmt::format_to(to, ",\"rejected\":{}", out.rejected);
  if (out.reversed) s += ",\"reversed\":true";
  if (out.scored) fmt::format_to(to, ",\"verdict\":\"{}\"", verdict_name(out.verdict));
  s += "}\n";
}

std::string hit_json_line(const TraceRay& tr, const RayOutcome& out) {
  std::string s;
  append_hit_json_line(s, tr, out);
  return s;
}

void check_hits_stream(const std::ostream& hits, const std::string& path) {
  if (!hits) throw OutputError(path, fmt::format("write failed: {}", errno ? std::strerror(errno) : "I/O error"));
}

std::string partial_hits_marker(uint64_t rays) { return fmt::format("{{\"partial\":true,\"rays\":{}}}\n", rays); }

namespace {

/// Rays read, then replayed, at a time on several threads.
constexpr std::size_t kBlockRays = 8192;

/// run_replay on `threads` > 1 threads, a block of rays at a time.
ReplayStats run_replay_blocks(TraceSource& source, const SceneAndBvh& sb, const ReplayOptions& opt,
                              std::ostream* hits, const std::atomic<bool>* stop, const ReplayProgress& progress,
                              int threads) {
  source.set_parse_threads(threads);
  BlockReplay replayer(sb.scene, sb.bvh, opt, threads);
  TraceBlocks blocks(source, opt.parent_window);
  ReplayStats stats;
  const auto start = std::chrono::steady_clock::now();
  uint64_t rays_read = 0;
  for (bool more = true; more;) {
    // An error at a ray of the block comes after the rays before it, as in a replay one ray at a time.
    std::exception_ptr error;
    try {
      more = blocks.next_block(kBlockRays);
    } catch (...) {
      error = std::current_exception();
    }
    replayer.replay(blocks, stats, hits);
    if (hits) check_hits_stream(*hits, "hits output");
    rays_read += blocks.rays().size();
    if (error) std::rethrow_exception(error);
    if (blocks.rays().empty()) break;
    if (progress) progress(rays_read);
    if (stop && stop->load(std::memory_order_relaxed)) {
      stats.partial = true;
      break;
    }
  }
  stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  check_ray_conservation(source.path(), rays_read, stats.total().rays);
  return stats;
}

}  // namespace

ReplayStats run_replay(TraceSource& source, const SceneAndBvh& sb, const ReplayOptions& opt,
                       std::ostream* hits, const std::atomic<bool>* stop, const ReplayProgress& progress,
                       int threads) {
  source.set_triangle_count(sb.scene.size());
  if (threads > 1) return run_replay_blocks(source, sb, opt, hits, stop, progress, threads);
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
