// OperationEnergy: the dynamic energy of a replay's arithmetic, from the
// counts the replay measured (rays, box and triangle tests, candidates,
// suspects, stack pushes and pops) times the datapath's operations per step
// (datapath_ops.h, method_costs.h) priced by a technology file. No memory and
// no leakage: the functional replay's energy, and the operation part of the
// cycle-level model's (hw/observe/hw_energy.h adds memory and leakage).
#pragma once
#include <nlohmann/json.hpp>

#include "datapath/self_intersection_method.h"
#include "datapath/testers.h"
#include "energy/tech_file.h"
#include "replay/replay_stats.h"

namespace vbsim {

/// Energies in pJ, by where the operations run.
struct OperationEnergy {
  double emission = 0;          ///< emission-time method operations (the ray source)
  double result = 0;            ///< per-ray operations on the answer (reverse-shadow's id compare)
  double box = 0;               ///< box tests and the box unit's per-ray set-up
  double triangle = 0;          ///< triangle tests and the tester's per-ray set-up
  double candidate_filter = 0;  ///< per-candidate compares (primid, the validity bit's sign compare)
  double avoidance = 0;         ///< the avoidance unit's tests of suspects
  double stack = 0;             ///< traversal stack pushes and pops (operations and entry bits)
  double ray_records = 0;       ///< each ray's record written once into its slot (bits per ray)
  double total() const {
    return emission + result + box + triangle + candidate_filter + avoidance + stack + ray_records;
  }
  /// What the self-intersection method itself adds: emission, result,
  /// candidate filter, avoidance unit, and its extra record bits.
  double method = 0;
};

/// The emission-time and result operations are those each ray's category
/// receives (method_costs.h, emission_ops_for; replay_stats.h, ray_categories).
OperationEnergy operation_energy(const TechFile& tech, const SelfIntersectionMethod& method, TesterKind tester,
                                 const ReplayStats& stats);

/// The parts of `e` by name, pJ: {"emission", "result", "box", ...}.
nlohmann::json operation_parts_json(const OperationEnergy& e);

/// {"tech", "dynamic_pj": {...}, "dynamic_total_pj", "per_ray_pj", "method_per_ray_pj",
///  "mrays_per_j"} of the operations alone.
nlohmann::json operation_energy_json(const TechFile& tech, const OperationEnergy& e, uint64_t rays);

/// pJ per ray, 0 when there are no rays.
inline double per_ray(double pj, uint64_t rays) { return rays ? pj / static_cast<double>(rays) : 0.0; }
/// Rays per joule / 10^6.
inline double mrays_per_joule(double pj, uint64_t rays) { return pj > 0 ? static_cast<double>(rays) / (pj * 1e-12) / 1e6 : 0.0; }

}  // namespace vbsim
