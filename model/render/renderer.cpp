#include "render/renderer.h"

#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>

#include "datapath/hit_point.h"
#include "exact/expected_answers.h"
#include "render/render_colours.h"
#include "replay/functional_replayer.h"

namespace vbsim {

namespace {

/// Traces the rays of one pixel at a time. Ray ids restart at 0 in every pixel
/// (primary 0, its shadow 1, the bounce 2, the bounce's shadow 3): a child's
/// parent is always the latest ray with that id, so the replayer's and the
/// oracle's parent tables stay at four entries.
class PixelTracer {
 public:
  PixelTracer(const Scene& scene, const Bvh& bvh, const ReplayOptions& options, const RenderLight& light)
      : scene_(scene), filler_(scene, bvh), replayer_(scene, bvh, options), light_(light) {}

  /// Colour of the pixel whose primary ray is (eye, d); sets its marks and primary triangle.
  Vec3f pixel(Vec3f eye, Vec3f d, uint8_t& marks, int32_t& primary_prim) {
    TraceRay primary;
    primary.id = 0;
    primary.kind = RayKind::Primary;
    primary.o = eye;
    primary.d = d;
    const RayOutcome out = run(primary, nullptr);
    primary_prim = out.answer;
    if (out.answer < 0) return background_linear();
    return shade(primary, out.hit, true, marks);
  }

  ReplayStats& stats() { return replayer_.stats(); }
  uint64_t unscored() const { return unscored_; }

 private:
  /// Exact answer first (it fills `expect`), then the method's answer and its
  /// verdict from the replayer. `marks` is null for primary rays, which are not
  /// part of the error image.
  RayOutcome run(TraceRay& r, uint8_t* marks) {
    filler_.fill(r);
    const RayOutcome out = replayer_.replay(r);
    unscored_ += out.verdict == Verdict::Unscored;
    if (marks) {
      if (out.verdict == Verdict::SelfHit) *marks |= kMarkAcne;
      if (out.verdict == Verdict::Missed || out.verdict == Verdict::FalseHit) *marks |= kMarkLeak;
    }
    return out;
  }

  /// Colour seen along `in`, which hit `h`; spawns the hit's shadow ray and,
  /// when `bounce`, its mirror ray.
  Vec3f shade(const TraceRay& in, const Hit& h, bool bounce, uint8_t& marks) {
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

    const bool point = light_.kind == RenderLight::Kind::Point;
    const Vec3f to_light = point ? light_.value - child.o : light_.value;
    const float lambert = dot(ns, normalize(to_light));
    float lit = 0.0f;
    if (lambert > 0.0f && to_light != Vec3f{0, 0, 0}) {
      TraceRay shadow = child;
      shadow.id = in.id + 1;
      shadow.kind = RayKind::Shadow;
      shadow.d = to_light;
      shadow.tmax = point ? 1.0f : std::numeric_limits<float>::infinity();
      if (run(shadow, &marks).answer < 0) lit = lambert;
    }
    Vec3f colour = (kAmbient + (1.0f - kAmbient) * lit) * kAlbedo;
    if (!bounce) return colour;

    TraceRay mirror = child;
    mirror.id = in.id + 2;
    mirror.kind = RayKind::Reflect;
    mirror.d = dn - (2.0f * dot(dn, ns)) * ns;
    if (mirror.d == Vec3f{0, 0, 0}) return colour;
    const RayOutcome out = run(mirror, &marks);
    const Vec3f seen = out.answer >= 0 ? shade(mirror, out.hit, false, marks) : background_linear();
    return (1.0f - kMirrorWeight) * colour + kMirrorWeight * seen;
  }

  const Scene& scene_;
  ExpectationFiller filler_;
  FunctionalReplayer replayer_;
  RenderLight light_;
  uint64_t unscored_ = 0;
};

void put(std::vector<uint8_t>& rgb, size_t pixel, const Rgb8& c) {
  for (int i = 0; i < 3; ++i) rgb[3 * pixel + i] = c[i];
}

}  // namespace

RenderResult render_scene(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                          const RenderSettings& settings) {
  const int w = settings.width, h = settings.height;
  if (w < 1 || h < 1 || w > 8192 || h > 8192)
    throw std::invalid_argument("image size " + std::to_string(w) + "x" + std::to_string(h) +
                                ": width and height must be 1 to 8192");
  const PinholeCamera camera(settings.camera, scene.bounds, w, h);
  PixelTracer tracer(scene, bvh, options, settings.light);

  RenderResult r;
  r.width = w;
  r.height = h;
  const size_t n = size_t(w) * size_t(h);
  r.image.assign(3 * n, 0);
  r.errors.assign(3 * n, 0);
  r.marks.assign(n, 0);
  r.primary_prim.assign(n, -1);
  const auto start = std::chrono::steady_clock::now();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const Rgb8 shaded = to_rgb8(tracer.pixel(camera.eye(), camera.direction(x, y), r.marks[i],
                                               r.primary_prim[i]));
      put(r.image, i, shaded);
      const uint8_t m = r.marks[i];
      const uint8_t g = grey_of(shaded);
      put(r.errors, i, m == (kMarkAcne | kMarkLeak) ? kBothRgb
                       : m == kMarkAcne             ? kAcneRgb
                       : m == kMarkLeak             ? kLeakRgb
                                                    : Rgb8{g, g, g});
      r.acne_pixels += (m & kMarkAcne) != 0;
      r.leak_pixels += (m & kMarkLeak) != 0;
    }
  }
  r.stats = tracer.stats();
  r.stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.unscored_rays = tracer.unscored();
  return r;
}

}  // namespace vbsim
