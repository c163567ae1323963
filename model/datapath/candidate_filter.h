// CandidateFilter: the per-candidate part of a self-intersection method, applied
// inside the closest-hit search the way an Embree filter function is: a rejected
// candidate does not shorten the ray interval, so the search goes on.
// Order: the ray mask first (Embree's ray masks: a triangle whose mask shares
// no bit with the ray's is no candidate), then primid exclusion (neither needs
// arithmetic), then the avoidance unit.
#pragma once
#include <cstdint>

#include "datapath/avoidance_unit.h"
#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/self_intersection_method.h"
#include "datapath/triangle.h"

namespace vbsim {

/// What the candidate filter saw; summed per ray kind by the replay.
struct CandidateCounters {
  uint64_t candidates = 0;         ///< hits the tester reported inside the interval
  uint64_t suspects = 0;           ///< avoidance unit: sign bit equal to front/back bit
  uint64_t rejected = 0;           ///< candidates dropped by any filter
  uint64_t rejected_mask = 0;      ///< dropped because the triangle's mask shares no bit with the ray's
  uint64_t rejected_primid = 0;    ///< dropped because prim == parent_prim
  uint64_t rejected_sign_only = 0; ///< dropped by the bit alone (policy sign-only)
  uint64_t invalid_normal = 0;     ///< rejected suspects whose normal test said invalid
  uint64_t invalid_ray = 0;        ///< ... whose along-the-ray test said invalid
  uint64_t invalid_component = 0;  ///< ... whose component-wise test said invalid

  void add(const CandidateCounters& o);
};

class CandidateFilter {
 public:
  /// `triangle_masks`: triangle k's mask at [k] (Scene::mask_table()), or
  /// null when every triangle has all bits (a ray of mask 0 still sees none);
  /// it must outlive the filter.
  explicit CandidateFilter(const SelfIntersectionMethod& method, const uint32_t* triangle_masks = nullptr)
      : primid_(method.primid), avoid_(method.validity_bit), cfg_(method.avoidance), masks_(triangle_masks) {}

  /// True when the candidate `hit` on triangle `prim` may become the closest hit.
  bool accept(const Ray& ray, const Triangle& tri, int32_t prim, const Hit& hit,
              CandidateCounters& c) const {
    return accept(ray, tri, prim, hit, c,
                  [&](const AvoidanceConfig& cfg) { return avoidance_decide(cfg, ray, tri, hit); });
  }

  /// The same, with the avoidance unit's decision from `decide(config)`
  /// (asked only for a candidate that reaches the unit: validity bit, not a
  /// camera ray, not dropped by primid) in place of avoidance_decide().
  template <class Decide>
  bool accept(const Ray& ray, const Triangle& /*tri*/, int32_t prim, const Hit& /*hit*/, CandidateCounters& c,
              Decide&& decide) const {
    ++c.candidates;
    if (((masks_ != nullptr ? masks_[prim] : 0xffffffffu) & ray.mask) == 0) {
      ++c.rejected;
      ++c.rejected_mask;
      return false;
    }
    if (primid_ && prim == ray.parent_prim) {
      ++c.rejected;
      ++c.rejected_primid;
      return false;
    }
    // A camera ray has no parent surface to re-hit: the unit leaves it alone. The
    // hardware tells it by the ray's kind field, which every ray already carries.
    if (!avoid_ || ray.kind == RayKind::Primary) return true;
    const AvoidanceDecision dec = decide(cfg_);
    c.suspects += dec.suspect;
    if (!dec.reject) return true;
    ++c.rejected;
    c.rejected_sign_only += (cfg_.policy == AvoidancePolicy::SignOnly);
    c.invalid_normal += (dec.invalid & AvoidanceDecision::kTestNormal) != 0;
    c.invalid_ray += (dec.invalid & AvoidanceDecision::kTestRay) != 0;
    c.invalid_component += (dec.invalid & AvoidanceDecision::kTestComponent) != 0;
    return false;
  }

  const AvoidanceConfig& avoidance() const { return cfg_; }
  bool uses_avoidance() const { return avoid_; }

 private:
  bool primid_;
  bool avoid_;
  AvoidanceConfig cfg_;
  const uint32_t* masks_;
};

}  // namespace vbsim
