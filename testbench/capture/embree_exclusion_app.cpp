// An Embree 3 application for the capture tests of filter functions, tracing
// the way Blender's Cycles does: no ray offset; a child starts at its
// parent's hit point computed from the barycentrics, with tnear 0, and a
// filter function rejects candidates on the primitive the ray starts from
// (primitive-ID self-exclusion); shadow rays are intersect queries with a
// finite tfar toward a point light. The scene: a tessellated sphere above a
// ground square. 16 x 12 camera rays, each followed for up to three bounces
// (a mirror and a diffuse child, and a shadow ray, at every hit).
//
// Usage: embree_exclusion_app MODE OUT.txt, MODE one of
//   geometry     self-exclusion by geometry filter functions, rtcIntersect1
//   context      self-exclusion by the intersect context's filter function
//   packet       geometry filters; each hit's three children in one rtcIntersect4
//   transparent  geometry filters that also reject every hit on the ground's
//                second triangle (an alpha cutout): those rays' answers are
//                not the closest hit of the triangles
// Writes one line per ray call lane (geomID primID t) so that a run under
// capture can be compared with one without.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Context {
  RTCIntersectContext rtc;  // first: Embree passes its address to the filters
  unsigned self_geom[4], self_prim[4];
  bool cutout;
};

constexpr unsigned kGround = 1;  // geomID of the ground square (the sphere is 0)

void exclude_self(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const Context*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned g = RTCHitN_geomID(args->hit, args->N, i), p = RTCHitN_primID(args->hit, args->N, i);
    const unsigned lane = args->N == 1 ? 0 : i;
    if ((g == ctx->self_geom[lane] && p == ctx->self_prim[lane]) || (ctx->cutout && g == kGround && p == 1))
      args->valid[i] = 0;
  }
}

struct Mesh {
  std::vector<float> v;
  std::vector<unsigned> idx;
};

Mesh sphere(int slices, int stacks) {
  Mesh m;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i <= slices; ++i) {
      const float th = 3.14159265f * static_cast<float>(j) / static_cast<float>(stacks);
      const float ph = 6.28318531f * static_cast<float>(i) / static_cast<float>(slices);
      m.v.insert(m.v.end(), {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const unsigned a = static_cast<unsigned>(j * (slices + 1) + i), b = a + static_cast<unsigned>(slices + 1);
      m.idx.insert(m.idx.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  return m;
}

const Mesh kGroundMesh{{-4, -4, -1, 4, -4, -1, 4, 4, -1, -4, 4, -1}, {0, 1, 2, 0, 2, 3}};

RTCGeometry attach(RTCDevice device, RTCScene scene, const Mesh& m, unsigned id, bool filters) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.v.data(), 0, 12, m.v.size() / 3);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.idx.data(), 0, 12, m.idx.size() / 3);
  if (filters) {
    rtcSetGeometryIntersectFilterFunction(g, exclude_self);
    rtcSetGeometryOccludedFilterFunction(g, exclude_self);
  }
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, id);
  rtcReleaseGeometry(g);
  return g;
}

struct App {
  RTCScene scene;
  const Mesh* meshes[2];
  std::string mode;
  FILE* out;
  unsigned rng = 12345;

  float next() {  // a small LCG: the same directions every run
    rng = rng * 1664525u + 1013904223u;
    return static_cast<float>(rng >> 8) / 16777216.0f;
  }

  Context context(unsigned geom, unsigned prim) const {
    Context c;
    rtcInitIntersectContext(&c.rtc);
    if (mode == "context") c.rtc.filter = exclude_self;
    for (int k = 0; k < 4; ++k) c.self_geom[k] = geom, c.self_prim[k] = prim;
    c.cutout = mode == "transparent";
    return c;
  }

  static RTCRayHit ray(const float o[3], const float d[3], float tfar) {
    RTCRayHit rh{};
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
  }

  void record(const RTCRayHit& rh) { std::fprintf(out, "%u %u %.9g\n", rh.hit.geomID, rh.hit.primID, rh.ray.tfar); }

  /// The hit point from the barycentrics, as Cycles computes it.
  void hit_point(const RTCRayHit& rh, float p[3]) const {
    const Mesh& m = *meshes[rh.hit.geomID];
    const unsigned* t = &m.idx[3 * rh.hit.primID];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    for (int a = 0; a < 3; ++a) p[a] = w * m.v[3 * t[0] + a] + u * m.v[3 * t[1] + a] + v * m.v[3 * t[2] + a];
  }

  /// The three children of hit `rh`: mirror, diffuse (a random direction on
  /// the side the ray came from) and a shadow ray toward the light.
  void children(const RTCRayHit& rh, float dirs[3][3], float tfar[3], const float p[3]) {
    const float n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    const float d[3] = {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
    const float dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2], nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    float r[3];
    for (int a = 0; a < 3; ++a) dirs[0][a] = d[a] - 2.0f * dn / nn * n[a], r[a] = 2.0f * next() - 1.0f;
    const float side = (r[0] * n[0] + r[1] * n[1] + r[2] * n[2]) * dn > 0.0f ? -1.0f : 1.0f;
    for (int a = 0; a < 3; ++a) dirs[1][a] = side * r[a];
    const float light[3] = {2.0f, -3.0f, 5.0f};
    float len = 0.0f;
    for (int a = 0; a < 3; ++a) dirs[2][a] = light[a] - p[a], len += dirs[2][a] * dirs[2][a];
    len = std::sqrt(len);
    for (int a = 0; a < 3; ++a) dirs[2][a] /= len;
    tfar[0] = tfar[1] = 3.40282347e38f;  // FLT_MAX, as Cycles passes for an unbounded ray
    tfar[2] = len;
  }

  void trace(RTCRayHit rh, unsigned self_geom, unsigned self_prim, int depth) {
    Context c = context(self_geom, self_prim);
    rtcIntersect1(scene, &c.rtc, &rh);
    record(rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    float p[3], dirs[3][3], tfar[3];
    hit_point(rh, p);
    children(rh, dirs, tfar, p);
    const unsigned g = rh.hit.geomID, prim = rh.hit.primID;
    if (mode == "packet") {
      RTCRayHit4 packet{};
      int valid[4] = {-1, -1, -1, 0};
      for (int k = 0; k < 4; ++k) {
        const int s = k < 3 ? k : 2;
        packet.ray.org_x[k] = p[0], packet.ray.org_y[k] = p[1], packet.ray.org_z[k] = p[2];
        packet.ray.dir_x[k] = dirs[s][0], packet.ray.dir_y[k] = dirs[s][1], packet.ray.dir_z[k] = dirs[s][2];
        packet.ray.tnear[k] = 0.0f;
        packet.ray.tfar[k] = tfar[s];
        packet.ray.mask[k] = 0xffffffffu;
        packet.hit.geomID[k] = packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      Context pc = context(g, prim);
      rtcIntersect4(valid, scene, &pc.rtc, &packet);
      for (int k = 0; k < 3; ++k)
        std::fprintf(out, "%u %u %.9g\n", packet.hit.geomID[k], packet.hit.primID[k], packet.ray.tfar[k]);
      if (depth < 3 && packet.hit.geomID[0] != RTC_INVALID_GEOMETRY_ID) trace(ray(p, dirs[0], tfar[0]), g, prim, depth + 1);
      return;
    }
    RTCRayHit shadow = ray(p, dirs[2], tfar[2]);
    Context sc = context(g, prim);  // the shadow ray leaves the new hit: its primitive is excluded
    rtcIntersect1(scene, &sc.rtc, &shadow);
    record(shadow);
    if (depth >= 3) return;
    trace(ray(p, dirs[0], tfar[0]), g, prim, depth + 1);
    trace(ray(p, dirs[1], tfar[1]), g, prim, depth + 1);
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: embree_exclusion_app geometry|context|packet|transparent OUT.txt\n"), 2;
  App app;
  app.mode = argv[1];
  if (app.mode != "geometry" && app.mode != "context" && app.mode != "packet" && app.mode != "transparent")
    return std::fprintf(stderr, "embree_exclusion_app: unknown mode %s\n", argv[1]), 2;
  app.out = std::fopen(argv[2], "w");
  if (!app.out) return std::perror(argv[2]), 1;
  RTCDevice device = rtcNewDevice(nullptr);
  app.scene = rtcNewScene(device);
  if (app.mode == "context") rtcSetSceneFlags(app.scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  const Mesh ball = sphere(16, 8);
  app.meshes[0] = &ball;
  app.meshes[1] = &kGroundMesh;
  attach(device, app.scene, ball, 0, app.mode != "context");
  attach(device, app.scene, kGroundMesh, kGround, app.mode != "context");
  rtcCommitScene(app.scene);
  const float eye[3] = {0.0f, -4.0f, 0.5f};
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x) {
      const float d[3] = {(static_cast<float>(x) - 7.5f) * 0.09f, 1.0f, (5.5f - static_cast<float>(y)) * 0.09f};
      app.trace(App::ray(eye, d, 3.40282347e38f), RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID, 0);
    }
  rtcReleaseScene(app.scene);
  rtcReleaseDevice(device);
  std::fclose(app.out);
  return 0;
}
