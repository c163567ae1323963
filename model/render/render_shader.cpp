#include "render/render_shader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "datapath/dvec3.h"
#include "datapath/hit_point.h"
#include "render/render_colours.h"
#include "render/render_random.h"

namespace vbsim {

namespace {

Vec3f times(Vec3f a, Vec3f b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

/// The exact answer to `ray` as a hit: its triangle, t rounded to float32,
/// and the barycentrics of o + t d on the triangle (in double, then float32).
Hit exact_hit(const TraceRay& ray, const Scene& scene) {
  Hit h;
  if (!ray.has_expect || ray.expect_prim < 0) return h;
  h.prim = ray.expect_prim;
  h.t = static_cast<float>(ray.expect_t);
  const Triangle& tri = scene.triangles[static_cast<size_t>(h.prim)];
  const DVec3 v0 = to_dvec(tri.v0), e1 = to_dvec(tri.v1) - v0, e2 = to_dvec(tri.v2) - v0;
  const DVec3 w = to_dvec(ray.o) + ray.expect_t * to_dvec(ray.d) - v0;
  const double d00 = ddot(e1, e1), d01 = ddot(e1, e2), d11 = ddot(e2, e2);
  const double d20 = ddot(w, e1), d21 = ddot(w, e2);
  const double denom = d00 * d11 - d01 * d01;
  if (denom > 0.0) {
    h.u = static_cast<float>((d11 * d20 - d01 * d21) / denom);
    h.v = static_cast<float>((d00 * d21 - d01 * d20) / denom);
  }
  return h;
}

void put(std::vector<uint8_t>& rgb, size_t pixel, const Rgb8& c) {
  for (int i = 0; i < 3; ++i) rgb[3 * pixel + i] = c[i];
}

}  // namespace

RenderShader::RenderShader(const Scene& scene, const Bvh& bvh, const RenderSettings& settings,
                           int64_t parent_window)
    : scene_(scene), settings_((check_render_settings(settings), settings)),
      camera_(settings.camera, scene.bounds, settings.width, settings.height),
      filler_(scene, bvh, parent_window),
      pixels_(static_cast<uint32_t>(settings.width) * static_cast<uint32_t>(settings.height)),
      slots_(static_cast<uint32_t>(settings.max_bounces) + 2),
      ao_length_(settings.ao_radius * length(scene.bounds.hi - scene.bounds.lo)),
      camera_rays_(settings.integrator == RenderIntegrator::Ao ? 1u : static_cast<uint32_t>(settings.samples)) {
  RenderResult& r = result_;
  r.width = settings.width;
  r.height = settings.height;
  r.image.assign(3 * size_t{pixels_}, 0);
  r.errors.assign(3 * size_t{pixels_}, 0);
  r.marks.assign(pixels_, 0);
  r.primary_prim.assign(pixels_, -1);
}

void RenderShader::make_primary() {
  const uint32_t pixel = next_pixel_, sample = next_sample_;
  const int x = static_cast<int>(pixel % static_cast<uint32_t>(settings_.width));
  const int y = static_cast<int>(pixel / static_cast<uint32_t>(settings_.width));
  PixelState& p = pixels_live_[pixel];
  if (settings_.integrator == RenderIntegrator::Path && p.terms.empty())
    p.terms.assign(size_t{slots_} * static_cast<size_t>(settings_.samples), Vec3f{0, 0, 0});
  ++p.primaries;
  TraceRay r;
  r.kind = RayKind::Primary;
  r.o = camera_.eye();
  if (camera_rays_ == 1) {
    r.d = camera_.direction(x, y);  // the pixel's centre
  } else {
    const RenderRandom rng(settings_.seed, pixel, sample);
    r.d = camera_.direction_at(float(x) + rng.uniform(0, 0), float(y) + rng.uniform(0, 1));
  }
  push_child(r, RayContext{pixel, sample, 0, Role::Primary, Vec3f{1, 1, 1}});
  if (++next_sample_ == camera_rays_) {
    next_sample_ = 0;
    ++next_pixel_;
  }
}

void RenderShader::push_child(const TraceRay& ray, const RayContext& context) {
  ++pixels_live_.at(context.pixel).pending;
  children_.push_back(Pending{ray, context});
}

ShaderAnswer RenderShader::next_ray(TraceRay& out, uint64_t) {
  if (children_.empty() && next_pixel_ < pixels_) make_primary();
  if (children_.empty()) return in_flight_.empty() ? ShaderAnswer::Finished : ShaderAnswer::Later;
  const Pending& next = children_.front();
  out = next.ray;
  out.id = next_id_++;
  filler_.fill(out);  // the exact answer, with the parent as the oracle's window holds it
  in_flight_.emplace(out.id, next.context);
  children_.pop_front();
  if (on_cast_) on_cast_(out);
  return ShaderAnswer::Ray;
}

void RenderShader::on_result(const TraceRay& ray, const RayOutcome& outcome, uint64_t) {
  const auto it = in_flight_.find(ray.id);
  if (it == in_flight_.end())
    throw std::logic_error(fmt::format("render: an answer for ray {}, which is not in flight", ray.id));
  const RayContext c = it->second;
  in_flight_.erase(it);
  PixelState& p = pixels_live_.at(c.pixel);
  if (c.role != Role::Primary) {  // primary rays are scored but not marked: no method acts on them
    if (outcome.verdict == Verdict::SelfHit) p.marks |= kMarkAcne;
    if (outcome.verdict == Verdict::Missed || outcome.verdict == Verdict::FalseHit) p.marks |= kMarkLeak;
  }
  result_.unscored_rays += outcome.verdict == Verdict::Unscored;
  const bool path = settings_.integrator == RenderIntegrator::Path;
  // What decides the children: the method's answer, or the exact one (the reference renderer).
  const Hit hit = settings_.children_from_exact ? exact_hit(ray, scene_) : outcome.hit;
  const int32_t answer = settings_.children_from_exact ? hit.prim : outcome.answer;
  switch (c.role) {
    case Role::Primary:
      if (c.sample == 0) result_.primary_prim[c.pixel] = answer;
      if (answer >= 0) shade_hit(ray, hit, c);
      else if (path) term(p, c.sample, slots_ - 1) = background_linear();
      break;
    case Role::Shadow:
      if (answer < 0) {
        if (path) term(p, c.sample, c.depth) = c.weight;
        else p.lit[c.depth] = c.weight.x;
      }
      break;
    case Role::Occlusion:
      if (answer < 0) p.lit[0] += c.weight.x;
      break;
    case Role::Bounce:
      if (answer >= 0) {
        p.bounce_hit = true;
        shade_hit(ray, hit, c);
      } else if (path) {
        term(p, c.sample, slots_ - 1) = times(c.weight, background_linear());
      } else if (settings_.integrator == RenderIntegrator::Glass) {
        p.escaped = times(c.weight, background_linear());
      }
      break;
  }
  if (--p.pending == 0 && p.primaries == camera_rays_) {
    finish_pixel(c.pixel, p);
    pixels_live_.erase(c.pixel);
  }
}

void RenderShader::shade_hit(const TraceRay& in, const Hit& h, const RayContext& at) {
  const Triangle& tri = scene_.triangles[h.prim];
  const Vec3f dn = normalize(in.d);
  Vec3f ng = normalize(geometric_normal(tri));
  if (!is_finite(ng)) ng = -dn;  // a sliver whose normal underflows: face the viewer
  const Vec3f ng_in = dot(dn, ng) < 0.0f ? ng : -ng;  // the side the ray came from

  TraceRay child;
  child.parent = in.id;
  child.set_parent_hit(h.prim, h.t, h.u, h.v);
  child.o = hit_point_barycentric(tri, h.u, h.v);
  Vec3f ns = ng_in;
  if (scene_.has_normals()) {
    const Vec3f n = normalize(scene_.shading_normal(h.prim, h.u, h.v));
    if (is_finite(n)) {
      child.has_parent_ns = true;
      child.parent_ns = n;
      ns = dot(n, ng_in) < 0.0f ? -n : n;  // the shading normal on the viewer's side
    }
  }

  if (settings_.integrator == RenderIntegrator::Ao) return cast_occlusion(child, ns, at);
  if (settings_.integrator == RenderIntegrator::Glass) return cast_glass(child, dn, ng, ns, at);

  // The hit's number along its path: 0 at the primary hit.
  const uint32_t depth = at.role == Role::Primary ? 0 : at.depth;
  const bool path = settings_.integrator == RenderIntegrator::Path;
  const Vec3f throughput = at.role == Role::Primary ? Vec3f{1, 1, 1} : at.weight;
  const RenderLight& light = settings_.light;
  const bool point = light.kind == RenderLight::Kind::Point;
  const Vec3f to_light = point ? light.value - child.o : light.value;
  const float lambert = dot(ns, normalize(to_light));
  if (lambert > 0.0f && to_light != Vec3f{0, 0, 0}) {
    TraceRay shadow = child;
    shadow.kind = RayKind::Shadow;
    shadow.d = to_light;
    shadow.tmax = point ? 1.0f : std::numeric_limits<float>::infinity();
    const Vec3f weight = path ? lambert * times(throughput, kAlbedo) : Vec3f{lambert, 0, 0};
    push_child(shadow, RayContext{at.pixel, at.sample, depth, Role::Shadow, weight});
  }

  TraceRay bounce = child;
  bounce.kind = RayKind::Reflect;
  if (path) {
    if (depth >= static_cast<uint32_t>(settings_.max_bounces)) return;
    bounce.kind = RayKind::Diffuse;
    const RenderRandom rng(settings_.seed, at.pixel, at.sample);
    bounce.d = rng.cosine_direction(ns, depth);
    push_child(bounce, RayContext{at.pixel, at.sample, depth + 1, Role::Bounce, times(throughput, kAlbedo)});
    return;
  }
  if (depth > 0) return;  // mirror: one bounce
  bounce.d = dn - (2.0f * dot(dn, ns)) * ns;
  if (bounce.d == Vec3f{0, 0, 0}) return;
  pixels_live_.at(at.pixel).bounced = true;
  push_child(bounce, RayContext{at.pixel, at.sample, 1, Role::Bounce, throughput});
}

void RenderShader::cast_occlusion(const TraceRay& child, Vec3f ns, const RayContext& at) {
  const float weight = 1.0f / static_cast<float>(settings_.samples);
  for (uint32_t k = 0; k < static_cast<uint32_t>(settings_.samples); ++k) {
    TraceRay ray = child;
    ray.kind = RayKind::Shadow;
    ray.d = ao_length_ * RenderRandom(settings_.seed, at.pixel, k).cosine_direction(ns, 0);
    ray.tmax = 1.0f;
    if (ray.d == Vec3f{0, 0, 0} || !is_finite(ray.d)) continue;  // a zero-size scene: nothing to occlude
    push_child(ray, RayContext{at.pixel, k, 0, Role::Occlusion, Vec3f{weight, 0, 0}});
  }
}

void RenderShader::cast_glass(const TraceRay& child, Vec3f dn, Vec3f ng, Vec3f ns, const RayContext& at) {
  const uint32_t depth = at.role == Role::Primary ? 0 : at.depth;
  if (depth >= static_cast<uint32_t>(settings_.max_bounces)) return;  // still inside: black
  const bool entering = dot(dn, ng) < 0.0f;  // the front side, by the winding
  const float eta = entering ? 1.0f / kGlassIor : kGlassIor;
  const float cos_i = std::min(1.0f, std::max(0.0f, -dot(dn, ns)));
  const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  const Vec3f throughput = at.role == Role::Primary ? Vec3f{1, 1, 1} : at.weight;
  TraceRay ray = child;
  Vec3f weight = throughput;
  if (sin2_t >= 1.0f) {  // total internal reflection
    ray.kind = RayKind::Reflect;
    ray.d = dn + (2.0f * cos_i) * ns;
  } else {
    const float cos_t = std::sqrt(1.0f - sin2_t);
    ray.kind = RayKind::Refract;
    ray.d = eta * dn + (eta * cos_i - cos_t) * ns;
    // Schlick's Fresnel reflectance, at the angle on the air side.
    const float f0 = ((1.0f - kGlassIor) / (1.0f + kGlassIor)) * ((1.0f - kGlassIor) / (1.0f + kGlassIor));
    const float c = 1.0f - (entering ? cos_i : cos_t);
    weight = (1.0f - (f0 + (1.0f - f0) * c * c * c * c * c)) * throughput;
  }
  if (ray.d == Vec3f{0, 0, 0} || !is_finite(ray.d)) return;
  push_child(ray, RayContext{at.pixel, at.sample, depth + 1, Role::Bounce, weight});
}

void RenderShader::finish_pixel(uint32_t pixel, PixelState& p) {
  Vec3f colour = background_linear();
  if (settings_.integrator == RenderIntegrator::Glass) {
    if (result_.primary_prim[pixel] >= 0) colour = p.escaped;
  } else if (settings_.integrator == RenderIntegrator::Ao) {
    if (result_.primary_prim[pixel] >= 0) colour = p.lit[0] * kAlbedo;
  } else if (settings_.integrator == RenderIntegrator::Path) {
    Vec3f sum{0, 0, 0};
    for (uint32_t s = 0; s < static_cast<uint32_t>(settings_.samples); ++s)
      for (uint32_t slot = 0; slot < slots_; ++slot) sum = sum + term(p, s, slot);
    colour = (1.0f / static_cast<float>(settings_.samples)) * sum;
  } else if (result_.primary_prim[pixel] >= 0) {
    colour = (kAmbient + (1.0f - kAmbient) * p.lit[0]) * kAlbedo;
    if (p.bounced) {
      const Vec3f seen =
          p.bounce_hit ? (kAmbient + (1.0f - kAmbient) * p.lit[1]) * kAlbedo : background_linear();
      colour = (1.0f - kMirrorWeight) * colour + kMirrorWeight * seen;
    }
  }
  const Rgb8 shaded = to_rgb8(colour);
  put(result_.image, pixel, shaded);
  const uint8_t m = p.marks;
  const uint8_t g = grey_of(shaded);
  put(result_.errors, pixel,
      m == (kMarkAcne | kMarkLeak) ? kBothRgb
      : m == kMarkAcne             ? kAcneRgb
      : m == kMarkLeak             ? kLeakRgb
                                   : Rgb8{g, g, g});
  result_.marks[pixel] = m;
  result_.acne_pixels += (m & kMarkAcne) != 0;
  result_.leak_pixels += (m & kMarkLeak) != 0;
  ++finished_;
  if (on_pixel_) on_pixel_(finished_);
}

RenderResult RenderShader::take_result() {
  if (finished_ != pixels_)
    throw std::logic_error(fmt::format("render: {} of {} pixels finished", finished_, pixels_));
  return std::move(result_);
}

}  // namespace vbsim
