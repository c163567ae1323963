#include "gen/random_triangles_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "gen/pbrt_reintersect.h"
#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"

namespace vbsim {

namespace {

constexpr int kMaxDrawsPerTriangle = 1000;

DVec3 random_unit(SeededRandom& rng) { return to_dvec(rng.unit_vector()); }

/// A uniform random point of `tri` (double barycentrics, rounded once to float).
Vec3f random_point_on(const Triangle& tri, SeededRandom& rng) {
  double a = rng.uniform(), b = rng.uniform();
  if (a + b > 1) a = 1 - a, b = 1 - b;
  const DVec3 p = (1 - a - b) * to_dvec(tri.v0) + a * to_dvec(tri.v1) + b * to_dvec(tri.v2);
  return to_vec3f(p);
}

struct RtgParams {
  double size_lo, size_hi, dist_lo, dist_hi, straddle;
  int64_t children;
};

struct PbrtParams {
  double exp;
  int64_t children, targets;
};

/// pbrt's pExp with a random sign: +-10^U[-exp, exp].
float signed_p_exp(SeededRandom& rng, double exp) {
  const float m = static_cast<float>(std::pow(10.0, rng.uniform(-exp, exp)));
  return rng.uniform() < 0.5 ? -m : m;
}

Vec3f p_exp_point(SeededRandom& rng, double exp) {
  const float x = signed_p_exp(rng, exp), y = signed_p_exp(rng, exp);
  return {x, y, signed_p_exp(rng, exp)};
}

/// One rtg trial, or nothing when the triangle is degenerate or its camera ray missed.
std::optional<ScenarioTraceBuilder> rtg_trial(const RtgParams& p, HitPointRule rule, SeededRandom& rng) {
  DVec3 centre = std::exp2(rng.uniform(p.dist_lo, p.dist_hi)) * random_unit(rng);
  if (rng.uniform() < p.straddle) {
    const int axis = static_cast<int>(rng.below(3));
    (axis == 0 ? centre.x : axis == 1 ? centre.y : centre.z) = 0.0;
  }
  const double size = std::exp2(rng.uniform(p.size_lo, p.size_hi));
  Triangle tri;
  for (Vec3f* v : {&tri.v0, &tri.v1, &tri.v2}) *v = to_vec3f(centre + size * random_unit(rng));
  const Vec3f ng = geometric_normal(tri);
  if (!(dot(ng, ng) > 0) || !is_finite(ng)) return std::nullopt;
  const Vec3f target = random_point_on(tri, rng);
  // Camera in front of the triangle, off the plane by at least 0.2 of its distance.
  const DVec3 n = unit_normal(tri);
  DVec3 w = random_unit(rng);
  if (ddot(w, n) < 0) w = -1.0 * w;
  w = dunit(w + 0.2 * n);
  const DVec3 camera = to_dvec(target) + size * std::exp2(rng.uniform(-2, 4)) * w;
  std::optional<ScenarioTraceBuilder> out;
  ScenarioTraceBuilder& b = out.emplace(std::vector<Triangle>{tri}, rule);
  const Vec3f o = to_vec3f(camera);
  const SpawnPoint s = b.shoot(o, target - o);
  if (!s.hit()) return std::nullopt;
  const DVec3 d = dunit(to_dvec(s.incoming));
  b.child(s, RayKind::Reflect, to_vec3f(d - 2.0 * ddot(d, n) * n));
  for (int64_t k = 1; k < p.children; ++k) b.child(s, RayKind::Diffuse, rng.unit_vector());
  return out;
}

/// One pbrt trial, or nothing when the triangle is dropped or its camera ray missed.
std::optional<ScenarioTraceBuilder> pbrt_trial(const PbrtParams& p, HitPointRule rule, SeededRandom& rng) {
  Triangle tri{p_exp_point(rng, p.exp), p_exp_point(rng, p.exp), p_exp_point(rng, p.exp)};
  const Vec3f ng = geometric_normal(tri);
  if (!(dot(ng, ng) >= 1e-20f)) return std::nullopt;  // pbrt's degenerate-triangle test, in float
  const Vec3f target = random_point_on(tri, rng);
  const Vec3f o = p_exp_point(rng, p.exp);
  std::optional<ScenarioTraceBuilder> out;
  ScenarioTraceBuilder& b = out.emplace(std::vector<Triangle>{tri}, rule);
  const SpawnPoint s = b.shoot(o, target - o);
  if (!s.hit()) return std::nullopt;
  for (int64_t k = 0; k < p.children; ++k) b.child(s, RayKind::Diffuse, rng.unit_vector());
  for (int64_t k = 0; k < p.targets; ++k) {
    const Vec3f to = p_exp_point(rng, p.exp) - s.p;
    b.child(s, RayKind::Shadow, to, 1.0f);
    b.child(s, RayKind::Shadow, to, 1.0f - 1e-4f);
  }
  return out;
}

/// pbrt-v4's own protocol: one case per triangle index that is not degenerate;
/// a skipped triangle (camera miss) keeps its camera ray, without children.
std::vector<ScenarioCase> pbrt_v4_cases(const ScenarioSettings& s) {
  const int64_t children = s.integer("children", 8);
  const int64_t first = s.integer("first", 0);
  const double exp = s.number("exp", 8);
  require_setting_range("children", static_cast<double>(children), 0, 1000000);
  require_setting_range("first", static_cast<double>(first), 0, 1e15);
  require_setting_range("exp", exp, 0, 30);
  std::vector<PbrtReintersectTrial> trials;
  int64_t degenerate = 0, skipped = 0;
  for (int64_t k = 0; k < s.rays(); ++k) {
    trials.push_back(pbrt_reintersect_trial(static_cast<uint64_t>(first + k), children, static_cast<float>(exp)));
    degenerate += trials.back().degenerate;
    skipped += !trials.back().degenerate && !trials.back().camera_hit;
  }
  std::vector<ScenarioCase> cases;
  for (PbrtReintersectTrial& t : trials) {
    if (t.degenerate) continue;
    ScenarioCase c;
    c.name = fmt::format("pbrt-v4-{:07d}", t.index);
    c.description = fmt::format(
        "random-triangles protocol=pbrt-v4: pbrt-v4's Triangle Reintersect trial RNG({}), {} SpawnRay and {} "
        "SpawnRayTo children{}; of the {} triangles from RNG({}), {} were dropped as degenerate and {} skipped "
        "because pbrt's test missed their camera ray",
        t.index, t.camera_hit ? children : 0, t.camera_hit ? children : 0,
        t.camera_hit ? "" : " (skipped: pbrt's test missed the camera ray)", s.rays(), first, degenerate, skipped);
    c.triangles = {t.tri};
    c.rays = std::move(t.rays);
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace

std::vector<ScenarioCase> generate_random_triangles_scenario(const ScenarioSettings& s) {
  const std::string protocol = s.text("protocol", "rtg");
  if (protocol == "pbrt-v4") return pbrt_v4_cases(s);
  if (protocol != "rtg" && protocol != "pbrt")
    throw std::runtime_error(fmt::format("option '--set protocol={}': expected rtg, pbrt or pbrt-v4", protocol));
  const bool rtg = protocol == "rtg";
  const HitPointRule rule = read_hit_point_rule(s, HitPointRule::Barycentric);
  RtgParams rp{};
  PbrtParams pp{};
  if (rtg) {
    rp.size_lo = s.number("size_min_log2", -16);
    rp.size_hi = s.number("size_max_log2", 22);
    rp.dist_lo = s.number("dist_min_log2", -16);
    rp.dist_hi = s.number("dist_max_log2", 22);
    rp.straddle = s.number("straddle", 0.1);
    rp.children = s.integer("children", 8);
    require_setting_range("size_min_log2", rp.size_lo, -100, 100);
    require_setting_range("size_max_log2", rp.size_hi, rp.size_lo, 100);
    require_setting_range("dist_min_log2", rp.dist_lo, -100, 100);
    require_setting_range("dist_max_log2", rp.dist_hi, rp.dist_lo, 100);
    require_setting_range("straddle", rp.straddle, 0, 1);
    require_setting_range("children", static_cast<double>(rp.children), 1, 10000);
  } else {
    pp.exp = s.number("exp", 8);
    pp.children = s.integer("children", 8);
    pp.targets = s.integer("targets", 4);
    require_setting_range("exp", pp.exp, 0, 30);
    require_setting_range("children", static_cast<double>(pp.children), 0, 10000);
    require_setting_range("targets", static_cast<double>(pp.targets), 0, 10000);
  }

  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (int64_t i = 0; i < s.rays(); ++i) {
    std::optional<ScenarioTraceBuilder> b;
    for (int draws = 0; !b; ++draws) {
      if (draws == kMaxDrawsPerTriangle)
        throw std::runtime_error(fmt::format("random-triangles: no usable triangle in {} draws", draws));
      b = rtg ? rtg_trial(rp, rule, rng) : pbrt_trial(pp, rule, rng);
    }
    const std::string description = fmt::format(
        "random-triangles protocol={} trial {} of {}: one isolated triangle; hit points by {}; every "
        "replay hit is a re-intersection of it",
        protocol, i, s.rays(), hit_point_rule_name(rule));
    cases.push_back(b->take_case(fmt::format("{}-{:04d}", protocol, i), description));
  }
  return cases;
}

}  // namespace vbsim
