#include "hw/cycle_replay.h"

#include <chrono>
#include <fstream>
#include <stdexcept>

#include "hw/hw_stats.h"

namespace vbsim::hw {

CycleRunResult run_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options) {
  const std::unique_ptr<MemoryPort> memory = make_memory(cfg.memory, static_cast<int>(cfg.cores));
  FunctionalReplayer replayer(scene, bvh, opt);
  replayer.set_track_parents(options.track_parents);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<CycleEngine> engine = make_cycle_engine(cfg, replayer, bvh, *memory, feed, sink);
  std::vector<TimelineEvent> timeline;
  if (!options.timeline.empty())
    engine->set_timeline_window(options.timeline_first, options.timeline_cycles, &timeline);
  const DriveResult sc = drive_with_systemc(*engine, cfg, options.drive);

  CycleRunResult r;
  r.stats = replayer.stats();
  r.stats.mode = "cycle";
  r.stats.partial = engine->stopped();
  r.stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write timeline");
  out << nlohmann::json{{"traceEvents", list}, {"displayTimeUnit", "ns"}}.dump() << "\n";
}

}  // namespace vbsim::hw
