#include "gen/scenario_trace_builder.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "datapath/closest_hit.h"
#include "datapath/hit_point.h"
#include "datapath/testers.h"
#include "replay/ray_emission.h"

namespace vbsim {

HitPointRule read_hit_point_rule(const ScenarioSettings& s, HitPointRule fallback) {
  const std::string v = s.text("hitpoint", hit_point_rule_name(fallback));
  if (v == "ray") return HitPointRule::Ray;
  if (v == "barycentric") return HitPointRule::Barycentric;
  throw std::runtime_error(fmt::format("option '--set hitpoint={}': expected ray or barycentric", v));
}

const char* hit_point_rule_name(HitPointRule r) {
  return r == HitPointRule::Ray ? "ray" : "barycentric";
}

ScenarioTraceBuilder::ScenarioTraceBuilder(std::vector<Triangle> triangles, HitPointRule rule)
    : scene_(make_scene(std::move(triangles))), bvh_(build_bvh(scene_)), rule_(rule) {}

SpawnPoint ScenarioTraceBuilder::shoot(Vec3f o, Vec3f d) {
  TraceRay r;
  r.id = static_cast<int64_t>(rays_.size());
  r.kind = RayKind::Primary;
  r.o = o;
  r.d = d;
  rays_.push_back(r);

  SpawnPoint s;
  s.parent_id = r.id;
  s.incoming = d;
  Ray ray;
  ray.o = o;
  ray.d = d;
  const CandidateFilter none{SelfIntersectionMethod{}};
  CandidateCounters cc;
  TraversalCounters tc;
  const Hit h = closest_hit<ThreeHalfPlaneTester>(bvh_, ray, none, cc, tc);
  if (!h.valid()) return s;
  s.prim = h.prim;
  s.t = h.t;
  s.u = h.u;
  s.v = h.v;
  s.p = rule_ == HitPointRule::Ray ? hit_point_ray(o, d, h.t)
                                   : hit_point_barycentric(scene_.triangles[h.prim], h.u, h.v);
  return s;
}

void ScenarioTraceBuilder::child(const SpawnPoint& s, RayKind kind, Vec3f d, float tmax) {
  TraceRay c;
  c.id = static_cast<int64_t>(rays_.size());
  c.parent = s.parent_id;
  c.kind = kind;
  c.o = s.p;
  c.d = d;
  c.tmax = tmax;
  c.set_parent_hit(s.prim, s.t, s.u, s.v);
  c.sign = static_cast<int8_t>(parent_sign_bit(c, scene_));
  rays_.push_back(c);
}

ScenarioCase ScenarioTraceBuilder::take_case(std::string name, std::string description) {
  ScenarioCase c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.triangles = scene_.triangles;
  c.rays = std::move(rays_);
  rays_.clear();
  return c;
}

DVec3 unit_normal(const Triangle& tri) {
  const DVec3 a = to_dvec(tri.v0), b = to_dvec(tri.v1), c = to_dvec(tri.v2);
  return dunit(dcross(b - a, c - a));
}

DVec3 any_perpendicular(DVec3 n) {
  const DVec3 axis = std::fabs(n.x) < 0.6 ? DVec3{1, 0, 0} : DVec3{0, 1, 0};
  return dunit(dcross(n, axis));
}

std::vector<double> log_spaced(double lo, double hi, int64_t count) {
  std::vector<double> out;
  for (int64_t i = 0; i < count; ++i) {
    const double f = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    out.push_back(std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo))));
  }
  return out;
}

std::vector<std::string> setting_list(const ScenarioSettings& s, const char* key, const std::string& fallback) {
  const std::string text = s.text(key, fallback);
  std::vector<std::string> items;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) throw std::runtime_error(fmt::format("option '--set {}={}': empty list item", key, text));
    items.push_back(item);
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

void require_setting_range(const char* key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi))
    throw std::runtime_error(fmt::format("option '--set {}={}': must lie in [{}, {}]", key, v, lo, hi));
}

}  // namespace vbsim
