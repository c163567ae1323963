#include "bench/bench_workload.h"

#include <algorithm>

#include "gen/seeded_random.h"
#include "replay/functional_replayer.h"
#include "replay/replay_run.h"
#include "trace/parent_ray_store.h"

namespace vbsim {

std::vector<TraceRay> bench_rays(const Scene& scene, int64_t count, uint64_t seed) {
  SeededRandom rng(seed);
  const Vec3f lo = scene.bounds.lo, hi = scene.bounds.hi;
  const Vec3f center = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * length(hi - lo), 1e-6f);
  std::vector<TraceRay> rays(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    TraceRay& r = rays[static_cast<size_t>(i)];
    r.id = i;
    r.o = center + (2.0f * radius) * rng.unit_vector();
    const Vec3f target{static_cast<float>(rng.uniform(lo.x, hi.x)), static_cast<float>(rng.uniform(lo.y, hi.y)),
                       static_cast<float>(rng.uniform(lo.z, hi.z))};
    r.d = target - r.o;
  }
  return rays;
}

BenchWorkload random_workload(const Scene& scene, const ReplayOptions& opt, int64_t count, uint64_t seed) {
  BenchWorkload w;
  w.rays = bench_rays(scene, count, seed);
  w.emitted.reserve(w.rays.size());
  w.any_hit.reserve(w.rays.size());
  for (const TraceRay& tr : w.rays) {  // camera rays: no parent
    w.emitted.push_back(emit_ray(tr, scene, opt, nullptr));
    w.any_hit.push_back(search_stops_at_any_hit(opt, tr, w.emitted.back()) ? 1 : 0);
  }
  return w;
}

BenchWorkload trace_workload(TraceSource& source, const Scene& scene, const ReplayOptions& opt, int64_t limit) {
  BenchWorkload w;
  source.set_triangle_count(scene.size());
  ParentRayStore parents(opt.parent_window);
  TraceRay tr;
  while ((limit < 0 || w.size() < limit) && source.next(tr)) {
    tr.has_expect = false;  // the bench times the search; `vbsim replay` scores
    tr.has_expect_t = false;
    tr.has_reference = false;
    tr.has_reference_t = false;
    w.rays.push_back(tr);
    w.with_parents = w.with_parents || tr.parent >= 0;
    EmittedRay er;
    replay_at_trace_ray(source, [&] { er = emit_ray(tr, scene, opt, parents.lookup(tr.parent)); });
    parents.add(tr.id, tr.o, tr.d);
    w.any_hit.push_back(search_stops_at_any_hit(opt, tr, er) ? 1 : 0);
    w.emitted.push_back(std::move(er));
  }
  return w;
}

}  // namespace vbsim
