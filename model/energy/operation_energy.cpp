#include "energy/operation_energy.h"

#include "datapath/datapath_ops.h"
#include "datapath/method_costs.h"
#include "datapath/ray.h"

namespace vbsim {

OperationEnergy operation_energy(const TechFile& t, const SelfIntersectionMethod& m, TesterKind tester,
                                 const ReplayStats& stats) {
  const KindStats k = stats.total();
  const MethodOps mo = method_ops(m);
  const double rays = static_cast<double>(k.rays);
  const TraversalCounters& tc = k.traversal;
  const double entry_bits_pj = kStackEntryBits * t.register_bit_pj;
  OperationEnergy e;
  for (const RayCategory& c : ray_categories(stats)) {
    e.emission += c.rays * t.energy_pj(emission_ops_for(m, c.child, c.shadow));
    e.result += c.rays * t.energy_pj(result_ops_for(m, c.shadow));
  }
  // Every search with a scene tests the root box: the box tests' count is at
  // least one per searched ray, and a search sets both units up once.
  e.box = tc.box_tests * t.energy_pj(box_test_ops()) + rays * t.energy_pj(box_setup_ops());
  e.triangle = tc.triangle_tests * t.energy_pj(triangle_test_ops(tester)) + rays * t.energy_pj(triangle_setup_ops(tester));
  e.candidate_filter = k.candidates.candidates * t.energy_pj(mo.candidate);
  e.avoidance = k.candidates.suspects * t.energy_pj(mo.suspect);
  e.stack = tc.stack_pushes * (t.energy_pj(stack_push_ops()) + entry_bits_pj) +
            tc.stack_pops * (t.energy_pj(stack_pop_ops()) + entry_bits_pj);
  e.ray_records = rays * m.bits_per_ray() * t.register_bit_pj;
  e.method = e.emission + e.result + e.candidate_filter + e.avoidance +
             rays * (m.bits_per_ray() - kBaseRayBits) * t.register_bit_pj;
  return e;
}

nlohmann::json operation_parts_json(const OperationEnergy& e) {
  return {{"emission", e.emission},
          {"result", e.result},
          {"box", e.box},
          {"triangle", e.triangle},
          {"candidate_filter", e.candidate_filter},
          {"avoidance", e.avoidance},
          {"stack", e.stack},
          {"ray_records", e.ray_records}};
}

nlohmann::json operation_energy_json(const TechFile& t, const OperationEnergy& e, uint64_t rays) {
  return {{"tech", t.path},
          {"scope", "operations only (functional mode: no memory, no leakage)"},
          {"dynamic_pj", operation_parts_json(e)},
          {"dynamic_total_pj", e.total()},
          {"per_ray_pj", per_ray(e.total(), rays)},
          {"method_pj", e.method},
          {"method_per_ray_pj", per_ray(e.method, rays)},
          {"mrays_per_j", mrays_per_joule(e.total(), rays)}};
}

}  // namespace vbsim
