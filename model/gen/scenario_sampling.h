// Sampling helpers shared by the scenario generators.
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "gen/renderer_hits.h"
#include "gen/scenario.h"
#include "gen/seeded_random.h"

namespace vbsim {

/// Uniform barycentrics (u, v) on a triangle: p = (1-u-v) v0 + u v1 + v v2.
inline void uniform_barycentrics(SeededRandom& rng, float& u, float& v) {
  const double s = std::sqrt(rng.uniform()), r = rng.uniform();
  u = static_cast<float>(s * (1.0 - r));
  v = static_cast<float>(s * r);
}

/// The `hitpoint` setting: "ray", "barycentric" or "both" (alternate, starting
/// with the ray equation). Returns the rule for the `index`-th hit.
class HitPointSetting {
 public:
  explicit HitPointSetting(const ScenarioSettings& s) : mode_(s.text("hitpoint", "both")) {
    if (mode_ != "ray" && mode_ != "barycentric" && mode_ != "both")
      throw std::runtime_error(
          fmt::format("option '--set hitpoint={}': expected ray, barycentric or both", mode_));
  }
  RendererHitPoint rule(int64_t index) const {
    if (mode_ == "ray") return RendererHitPoint::RayEquation;
    if (mode_ == "barycentric") return RendererHitPoint::Barycentric;
    return index % 2 == 0 ? RendererHitPoint::RayEquation : RendererHitPoint::Barycentric;
  }

 private:
  std::string mode_;
};

/// Rays per case when `total` rays (> 0: ScenarioSettings checks it) are spread
/// over `cases` cases (at least 1).
inline int64_t rays_per_case(int64_t total, size_t cases) {
  return std::max<int64_t>(1, total / static_cast<int64_t>(std::max<size_t>(cases, 1)));
}

}  // namespace vbsim
