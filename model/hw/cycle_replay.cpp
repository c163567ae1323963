#include "hw/cycle_replay.h"

#include <chrono>
#include <fstream>
#include <stdexcept>

#include "hw/hw_stats.h"
#include "io/atomic_output_file.h"
#include "replay/ray_conservation.h"

namespace vbsim::hw {

CycleRunResult run_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options) {
  const std::unique_ptr<MemoryPort> memory = make_memory(cfg.memory, static_cast<int>(cfg.cores));
  FunctionalReplayer replayer(scene, bvh, opt);
  replayer.set_track_parents(options.track_parents);
  const auto start = std::chrono::steady_clock::now();
  uint64_t fed = 0;  // rays in, for the conservation check
  const RayFeed counted = [&feed, &fed](TraceRay& tr) {
    const bool got = feed(tr);
    fed += got ? 1 : 0;
    return got;
  };
  const std::unique_ptr<CycleEngine> engine = make_cycle_engine(cfg, replayer, bvh, *memory, counted, sink);
  std::vector<TimelineEvent> timeline;
  if (!options.timeline.empty())
    engine->set_timeline_window(options.timeline_first, options.timeline_cycles, &timeline);
  const DriveResult sc = drive_with_systemc(*engine, cfg, options.drive);

  CycleRunResult r;
  r.stats = replayer.stats();
  r.stats.mode = "cycle";
  r.stats.partial = engine->stopped();
  r.stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Rays in = rays out; a stopped run drops the rays in its slots and the one the source holds.
  const uint64_t done = r.stats.total().rays;
  r.stats.rays_dropped = fed >= done ? fed - done : 0;
  if (!r.stats.partial)
    check_ray_conservation("cycle-level replay", fed, done);
  else if (done > fed || r.stats.rays_dropped > engine->rays_in_flight() + 1)
    check_ray_conservation("stopped cycle-level replay", fed, done, engine->rays_in_flight());
  r.counters = engine->counters();
  const nlohmann::json mem = memory->stats();
  const HwReport report{r.counters, cfg, r.stats, mem, sc};
  r.hw = hw_stats_json(report);
  r.table = hw_summary_table(report);
  if (!options.timeline.empty()) write_timeline(options.timeline, timeline);
  return r;
}

void write_timeline(const std::string& path, const std::vector<TimelineEvent>& events) {
  nlohmann::json list = nlohmann::json::array();
  for (const TimelineEvent& e : events)
    list.push_back({{"name", e.name},
                    {"ph", "X"},
                    {"ts", e.start},
                    {"dur", e.end - e.start},
                    {"pid", e.core},
                    {"tid", e.slot},
                    {"args", {{"ray", e.ray_id}}}});
  write_output_file(path, nlohmann::json{{"traceEvents", list}, {"displayTimeUnit", "ns"}}.dump() + "\n", "timeline");
}

}  // namespace vbsim::hw
