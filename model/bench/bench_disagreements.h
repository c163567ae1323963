// Where vbsim and Embree answer a bench ray differently, which of them the exact
// oracle supports. The exact answer is that of the ray both were given (the
// emitted ray: its float origin and direction, t in the open interval
// (tmin, tmax)), not the trace spec's intended ray: the bench holds the two
// searches to the same query, whatever the self-intersection method made of it.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_workload.h"
#include "exact/exact_geometry.h"
#include "replay/replay_options.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim {

enum class DisagreementClass : uint8_t {
  Tie,          ///< both hit at the same exact t (a shared edge or vertex): both right
  EmbreeWrong,  ///< the exact answer is vbsim's
  VbsimWrong,   ///< the exact answer is Embree's: a defect of vbsim's search
  BothWrong,    ///< the exact answer is neither
  Method,       ///< vbsim's method rejected a candidate or reversed the ray: not the same query
};
constexpr int kDisagreementClassCount = 5;
/// "tie", "embree_wrong", "vbsim_wrong", "both_wrong", "method".
const char* disagreement_class_name(DisagreementClass c);

struct BenchDisagreement {
  int64_t index = 0;  ///< position of the ray in the workload
  int64_t id = 0;     ///< the ray's id
  int32_t vbsim = -1, embree = -1;  ///< the answers (kEmbreeOccluded: Embree found an any-hit ray occluded)
  DisagreementClass cls = DisagreementClass::Tie;
  /// The ray has a parent triangle and it is one of the answers or the exact
  /// one: a self-intersection at the origin, where a float t's sign decides.
  bool at_parent = false;
};

struct DisagreementReport {
  std::array<int64_t, kDisagreementClassCount> counts{};
  std::array<int64_t, kDisagreementClassCount> at_parent{};  ///< of counts, those with at_parent
  std::vector<BenchDisagreement> rays;  ///< every disagreement, in workload order
  int64_t total() const;
  int64_t count(DisagreementClass c) const { return counts[static_cast<int>(c)]; }
  /// {"tie": n, ..., "method": n, "at_parent": {"tie": n, ...},
  ///  "rays": [{index, id, vbsim, embree, class, at_parent}, ...], "rays_listed": n}
  /// with at most `max_rays` rays listed.
  nlohmann::json to_json(size_t max_rays = 1000) const;
};

/// The exact form of an emitted ray: o + tmin d as the origin and tmax - tmin as
/// the upper end, so that the oracle's (0, tmax) is the ray's (tmin, tmax).
ExactRay exact_emitted_ray(const Ray& r);

/// Whether `answer` is right for the ray `r`: on a closest-hit ray (`any_hit`
/// false) a triangle at the smallest exact t, or -1 when nothing is hit; on an
/// any-hit ray any triangle the ray meets (kEmbreeOccluded when one exists), or
/// -1 when none. `ties`: the oracle's closest_ties of the ray.
bool answer_is_right(const Scene& scene, const ExactRay& r, bool any_hit, int32_t answer,
                     const std::vector<int32_t>& ties);

/// Classifies every ray of `w` where `ours` and `theirs` disagree (the
/// bench_answers_agree rule). The oracle (and its check of `bvh`) is built only
/// when there is a disagreement; vbsim's search is run again on those rays to
/// see whether the method rejected a candidate.
DisagreementReport classify_disagreements(const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                          const BenchWorkload& w, const std::vector<int32_t>& ours,
                                          const std::vector<int32_t>& theirs);

/// Whether vbsim's answer `ours` and Embree's `theirs` agree: the same triangle
/// (or both none), or on an any-hit ray both occluded or both not.
inline bool bench_answers_agree(int32_t ours, int32_t theirs, bool any_hit) {
  return any_hit ? (ours >= 0) == (theirs != -1) : ours == theirs;
}

}  // namespace vbsim
