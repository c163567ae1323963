#include "reduced_precision/precision_study.h"

#include "hw/cycle_replay.h"
#include "reduced_precision/reduced_precision_units.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

namespace vbsim::hw {

PrecisionRun precision_run(const std::string& trace, const HwConfig& cfg, const ReplayOptions& opt,
                           const AcceleratorUnits& units, const std::vector<int32_t>* reference,
                           std::vector<int32_t>* answers) {
  auto src = open_trace(trace);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  PrecisionRun r;
  std::vector<int32_t> got;
  const RayResultSink sink = [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
    if (got.size() <= index) got.resize(index + 1, -2);
    got[index] = out.answer;
  };
  CycleRunOptions options;
  options.units = units;
  const CycleRunResult run =
      run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh, opt, cfg, sink, options);
  const KindStats t = run.stats.total();
  r.rays = t.rays;
  r.cycles = run.counters.cycles;
  r.box_tests = t.traversal.box_tests;
  r.triangle_tests = t.traversal.triangle_tests;
  r.self_hits = t.verdicts[static_cast<int>(Verdict::SelfHit)];
  r.box_ops = run.counters.box.ops;
  r.triangle_ops = run.counters.triangle.ops;
  if (reference)
    for (size_t i = 0; i < got.size(); ++i) r.changed += i >= reference->size() || (*reference)[i] != got[i];
  if (answers) *answers = std::move(got);
  return r;
}

std::vector<PrecisionRun> precision_study(const std::string& trace, const HwConfig& cfg, const ReplayOptions& opt,
                                          const std::vector<int>& box_bits, const std::vector<int>& triangle_bits) {
  std::vector<PrecisionRun> out;
  std::vector<int32_t> reference;
  out.push_back(precision_run(trace, cfg, opt, {}, nullptr, &reference));
  out.back().units = "built-in";
  for (const int bits : box_bits) {
    AcceleratorUnits units;
    units.box_unit = reduced_precision_box_unit(bits);
    out.push_back(precision_run(trace, cfg, opt, units, &reference, nullptr));
    out.back().units = "box " + std::to_string(bits) + " bits";
    out.back().bits = bits;
  }
  for (const int bits : triangle_bits) {
    AcceleratorUnits units;
    units.triangle_tester = reduced_precision_triangle_tester(bits, opt.tester);
    out.push_back(precision_run(trace, cfg, opt, units, &reference, nullptr));
    out.back().units = "triangle " + std::to_string(bits) + " bits";
    out.back().bits = bits;
  }
  return out;
}

}  // namespace vbsim::hw
