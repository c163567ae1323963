// An Embree 3 application for the capture tests: it traces through every ray
// query entry point (1, 4, 8, 16-wide, 1M, 1Mp, NM, Np; intersect and
// occluded) on a scene built every way Embree allows (shared, new and
// RTCBuffer buffers, a strided vertex buffer, a geomID set by the caller, a
// quad mesh, captured as the two triangles Embree splits each quad into, and
// a disabled mesh, which cannot be captured), spawns children
// from hits (shadow, reflect, refract, diffuse; at the hit point or offset
// along the normal), and writes its own record of every ray, Embree's answer
// and the intended parent and kind, so the tests can hold the capture against
// an account kept independently of the shim.
//
// Usage: embree_calls_app THREADS OUT.txt
// Thread t of THREADS runs items t, t + THREADS, ..., so every thread traces
// and each item's rays come from a different thread than with one thread;
// OUT.txt lists items in order, so it is the same for any thread count.
#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kItems = 97;  // item 96 aims at the quad mesh
std::atomic<long> g_calls[2][8];
const char* const kApi[8] = {"1", "4", "8", "16", "1M", "1Mp", "NM", "Np"};

struct V {
  float x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(float s, V a) { return {s * a.x, s * a.y, s * a.z}; }
float dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V unit(V a) { return (1.0f / std::sqrt(dot(a, a))) * a; }

struct Ray {
  bool occluded;
  int api;
  V o, d;
  float tnear, tfar;
  unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = RTC_INVALID_GEOMETRY_ID;
  float t = 0, u = 0, v = 0;
  V ng{};
  int parent = -1;  // index in the item's list
  const char* kind = "primary";
};

std::string text(const Ray& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "ray %c %s %a %a %a %a %a %a %a %a hit %d %d %a %a %a %a %a %a parent %d %s\n",
                r.occluded ? 'O' : 'I', kApi[r.api], r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tnear, r.tfar,
                static_cast<int>(r.geom), static_cast<int>(r.prim), r.t, r.u, r.v, r.ng.x, r.ng.y, r.ng.z, r.parent,
                r.kind);
  return buf;
}

RTCRayHit make_rayhit(const Ray& r) {
  RTCRayHit h{};
  h.ray.org_x = r.o.x, h.ray.org_y = r.o.y, h.ray.org_z = r.o.z;
  h.ray.dir_x = r.d.x, h.ray.dir_y = r.d.y, h.ray.dir_z = r.d.z;
  h.ray.tnear = r.tnear, h.ray.tfar = r.tfar, h.ray.mask = 0xffffffffu;
  h.hit.geomID = h.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return h;
}

void take_hit(Ray& r, const RTCRayHit& h) {
  r.geom = h.hit.geomID, r.prim = h.hit.primID, r.t = h.ray.tfar, r.u = h.hit.u, r.v = h.hit.v;
  r.ng = {h.hit.Ng_x, h.hit.Ng_y, h.hit.Ng_z};
}

/// Copies the results of an SOA layout back into `rays`; field(k, i) is field
/// k (RTCRayN then RTCHitN order) of lane i.
template <class Field>
void read_back(std::vector<Ray>& rays, bool occluded, Field field) {
  for (unsigned i = 0; i < rays.size(); ++i) {
    Ray& r = rays[i];
    r.t = field(8, i);
    if (occluded) continue;
    r.ng = {field(12, i), field(13, i), field(14, i)}, r.u = field(15, i), r.v = field(16, i);
    r.prim = reinterpret_cast<unsigned&>(field(17, i)), r.geom = reinterpret_cast<unsigned&>(field(18, i));
  }
}

/// Traces `rays` (all intersect or all occluded) through entry point `api`.
/// Lane 1 of every packet or stream is inactive: it is dropped from `rays`.
void trace(RTCScene scene, int api, std::vector<Ray>& rays) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  const bool occ = rays[0].occluded;
  const unsigned n = static_cast<unsigned>(rays.size());
  g_calls[occ][api]++;
  if (api == 0) {
    RTCRayHit h = make_rayhit(rays[0]);
    if (occ) rtcOccluded1(scene, &ctx, &h.ray), rays[0].t = h.ray.tfar;
    else rtcIntersect1(scene, &ctx, &h), take_hit(rays[0], h);
    rays.resize(1);  // callers pass a placeholder second ray, like an inactive lane
    return;
  }
  if (api <= 3) {  // an SOA packet of width w, as float blocks: 12 ray fields then the hit fields
    const unsigned w = api == 1 ? 4 : api == 2 ? 8 : 16;
    alignas(64) float block[(12 + 8) * 16] = {};
    alignas(64) int valid[16] = {};
    auto f = [&](unsigned k, unsigned i) -> float& { return block[k * w + i]; };
    for (unsigned i = 0; i < n; ++i) {
      const RTCRayHit h = make_rayhit(rays[i]);
      // The 12 ray fields as 4-byte words, copied as bytes: mask, id and flags
      // are integers (read through a float they can lose their bits).
      for (unsigned k = 0; k < 12; ++k) std::memcpy(&f(k, i), reinterpret_cast<const char*>(&h.ray) + 4 * k, 4);
      reinterpret_cast<unsigned&>(f(12 + 6, i)) = RTC_INVALID_GEOMETRY_ID;
      valid[i] = i == 1 ? 0 : -1;
    }
    if (occ) {
      if (w == 4) rtcOccluded4(valid, scene, &ctx, reinterpret_cast<RTCRay4*>(block));
      if (w == 8) rtcOccluded8(valid, scene, &ctx, reinterpret_cast<RTCRay8*>(block));
      if (w == 16) rtcOccluded16(valid, scene, &ctx, reinterpret_cast<RTCRay16*>(block));
    } else {
      if (w == 4) rtcIntersect4(valid, scene, &ctx, reinterpret_cast<RTCRayHit4*>(block));
      if (w == 8) rtcIntersect8(valid, scene, &ctx, reinterpret_cast<RTCRayHit8*>(block));
      if (w == 16) rtcIntersect16(valid, scene, &ctx, reinterpret_cast<RTCRayHit16*>(block));
    }
    read_back(rays, occ, f);
  } else if (api == 4 || api == 5) {  // 1M (an array) or 1Mp (pointers)
    std::vector<RTCRayHit> hs(n);
    std::vector<RTCRayHit*> ps(n);
    for (unsigned i = 0; i < n; ++i) hs[i] = make_rayhit(rays[i]), ps[i] = &hs[i];
    hs[1].ray.tnear = 1, hs[1].ray.tfar = 0;  // inactive: tnear > tfar
    std::vector<RTCRay*> rps(n);
    for (unsigned i = 0; i < n; ++i) rps[i] = &hs[i].ray;
    if (occ && api == 4) rtcOccluded1M(scene, &ctx, &hs[0].ray, n, sizeof(RTCRayHit));
    if (occ && api == 5) rtcOccluded1Mp(scene, &ctx, rps.data(), n);
    if (!occ && api == 4) rtcIntersect1M(scene, &ctx, hs.data(), n, sizeof(RTCRayHit));
    if (!occ && api == 5) rtcIntersect1Mp(scene, &ctx, ps.data(), n);
    for (unsigned i = 0; i < n; ++i) occ ? void(rays[i].t = hs[i].ray.tfar) : take_hit(rays[i], hs[i]);
  } else {  // NM: M = 2 packets of width 4 (lanes beyond n inactive); Np: one array per field
    const unsigned w = 4, m = (n + w - 1) / w;
    std::vector<float> blocks((12 + 8) * w * m, 0.0f);
    std::vector<float> soa(20 * n, 0.0f);
    auto at = [&](unsigned k, unsigned i) -> float& {
      return api == 6 ? blocks[(i / w) * 20 * w + k * w + i % w] : soa[k * n + i];
    };
    for (unsigned i = n; api == 6 && i < w * m; ++i)  // padding lanes of the last packet: inactive
      blocks[(i / w) * 20 * w + 3 * w + i % w] = 1, blocks[(i / w) * 20 * w + 8 * w + i % w] = 0;
    for (unsigned i = 0; i < n; ++i) {
      const RTCRayHit h = make_rayhit(rays[i]);
      for (unsigned k = 0; k < 12; ++k) std::memcpy(&at(k, i), reinterpret_cast<const char*>(&h.ray) + 4 * k, 4);
      reinterpret_cast<unsigned&>(at(18, i)) = RTC_INVALID_GEOMETRY_ID;
    }
    at(3, 1) = 1, at(8, 1) = 0;  // lane 1 inactive: tnear > tfar
    RTCRayHitNp np;
    float* p[20];
    for (unsigned k = 0; k < 20; ++k) p[k] = &soa[k * n];
    np.ray = {p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], reinterpret_cast<unsigned*>(p[9]),
              reinterpret_cast<unsigned*>(p[10]), reinterpret_cast<unsigned*>(p[11])};
    np.hit = {p[12], p[13], p[14], p[15], p[16], reinterpret_cast<unsigned*>(p[17]),
              reinterpret_cast<unsigned*>(p[18]), {reinterpret_cast<unsigned*>(p[19])}};
    if (api == 6 && occ) rtcOccludedNM(scene, &ctx, reinterpret_cast<RTCRayN*>(blocks.data()), w, m, 20 * w * 4);
    if (api == 6 && !occ) rtcIntersectNM(scene, &ctx, reinterpret_cast<RTCRayHitN*>(blocks.data()), w, m, 20 * w * 4);
    if (api == 7 && occ) rtcOccludedNp(scene, &ctx, &np.ray, n);
    if (api == 7 && !occ) rtcIntersectNp(scene, &ctx, &np, n);
    read_back(rays, occ, at);
  }
  rays.erase(rays.begin() + 1);  // the inactive lane was never traced
}

/// One work item: a packet (or single ray) of camera rays, then children of each hit.
std::string run_item(RTCScene scene, int k, bool native16) {
  int api = k % 8;
  if (api == 3 && !native16) api = 2;  // no 16-wide packets on this machine
  const bool occ = (k / 8) % 2 == 1;
  const unsigned lanes = api == 0 ? 1 : api == 1 ? 4 : api == 2 ? 8 : api == 3 ? 16 : 5;
  std::vector<Ray> cams;
  for (unsigned i = 0; i < lanes; ++i) {
    Ray r{};
    r.occluded = occ, r.api = api;
    r.o = k == kItems - 1 ? V{25.0f, 0.0f, 5.0f} : V{-7.0f + 0.14f * k + 0.05f * i, -6.0f + 0.11f * k, 9.0f};
    r.d = k == kItems - 1 ? V{0.0f, 0.01f, -1.0f} : unit(V{0.05f * (k % 5) - 0.1f, 0.03f * i, -1.0f});
    r.tnear = 0.0f, r.tfar = INFINITY;
    r.kind = occ ? "shadow" : "primary";
    r.geom = r.prim = RTC_INVALID_GEOMETRY_ID;
    cams.push_back(r);
  }
  if (api == 0) cams.push_back(cams[0]);  // keeps the lane-1 removal uniform
  trace(scene, api, cams);
  std::vector<Ray> all = cams;
  const V light{0.0f, 0.0f, 20.0f};
  for (std::size_t c = 0; c < all.size() && c < 64; ++c) {
    const Ray parent = all[c];
    if (parent.occluded || parent.geom == RTC_INVALID_GEOMETRY_ID || parent.geom == 2 || k == kItems - 1) continue;
    if (std::string(parent.kind) != "primary" && std::string(parent.kind) != "reflect") continue;
    const V p = parent.o + parent.t * parent.d;  // the hit point, as Embree applications compute it
    V n = unit(parent.ng);
    const V nf = dot(n, parent.d) < 0 ? n : -1.0f * n;  // facing the incoming ray
    const int pi = static_cast<int>(c);
    std::vector<Ray> kids;
    auto child = [&](bool occluded, V o, V d, float tnear, float tfar, const char* kind) {
      Ray r{};
      r.occluded = occluded, r.api = 0, r.o = o, r.d = d, r.tnear = tnear, r.tfar = tfar, r.parent = pi, r.kind = kind;
      r.geom = r.prim = RTC_INVALID_GEOMETRY_ID;
      std::vector<Ray> one = {r, r};
      trace(scene, 0, one);
      all.push_back(one[0]);
    };
    child(true, p, light - p, 1e-4f, 1.0f, "shadow");
    if (std::string(parent.kind) == "reflect") continue;  // depth 2: only the shadow ray
    child(false, p + 1e-4f * nf, parent.d - (2.0f * dot(parent.d, n)) * n, 0.0f, INFINITY, "reflect");
    child(false, p - 1e-4f * nf, parent.d, 0.0f, INFINITY, "refract");
    child(false, p, unit(nf + V{0.3f, 0.2f, 0.0f}), 1e-4f, INFINITY, "diffuse");
  }
  std::string out = "item " + std::to_string(k) + "\n";
  for (const Ray& r : all) out += text(r);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: embree_calls_app THREADS OUT.txt\n"), 2;
  const int threads = std::atoi(argv[1]);
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  // geomID 0: the floor z = 0, a shared vertex buffer with a 16-byte stride (x y z pad).
  static const float floor_v[] = {-10, -10, 0, 0, 10, -10, 0, 0, 10, 10, 0, 0, -10, 10, 0, 0};
  static const unsigned floor_i[] = {0, 1, 2, 0, 2, 3};
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, floor_v, 0, 16, 4);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, floor_i, 0, 12, 2);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  // geomID 1: a slanted triangle above the floor, in a buffer Embree allocates.
  g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  float* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 3));
  const float tri_v[] = {-3, -3, 4, 3, -3, 4, 0, 3, 6};
  for (int i = 0; i < 9; ++i) v[i] = tri_v[i];
  unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, 1));
  idx[0] = 0, idx[1] = 1, idx[2] = 2;
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  // geomID 2: a quad mesh at x in [20, 30] (captured as two triangles).
  g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
  float* qv = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 4));
  const float quad_v[] = {20, -5, 1, 30, -5, 1, 30, 5, 1, 20, 5, 1};
  for (int i = 0; i < 12; ++i) qv[i] = quad_v[i];
  unsigned* qi = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 16, 1));
  qi[0] = 0, qi[1] = 1, qi[2] = 2, qi[3] = 3;
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  // geomID 3: a triangle at z = 2, disabled (Embree does not trace it).
  g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  static const float dis_v[] = {-9, -9, 2, -5, -9, 2, -9, 9, 2};
  static const unsigned dis_i[] = {0, 1, 2};
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, dis_v, 0, 12, 3);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, dis_i, 0, 12, 1);
  rtcDisableGeometry(g);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  // geomID 7 (chosen): a wall at x = 8 in an RTCBuffer, the vertices 16 bytes into it.
  g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  RTCBuffer buf = rtcNewBuffer(device, 16 + 4 * 12 + 2 * 12);
  char* base = static_cast<char*>(rtcGetBufferData(buf));
  const float wall_v[] = {8, -10, 0, 8, 10, 0, 8, 10, 10, 8, -10, 10};
  const unsigned wall_i[] = {0, 1, 2, 0, 2, 3};
  std::memcpy(base + 16, wall_v, sizeof wall_v);
  std::memcpy(base + 16 + sizeof wall_v, wall_i, sizeof wall_i);
  rtcSetGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, buf, 16, 12, 4);
  rtcSetGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, buf, 16 + sizeof wall_v, 12, 2);
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, 7);
  rtcReleaseGeometry(g);
  rtcReleaseBuffer(buf);
  rtcCommitScene(scene);
  rtcCommitScene(scene);  // unchanged: the same snapshot

  const bool native16 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  std::vector<std::string> results(kItems);
  auto work = [&](int first) {
    for (int k = first; k < kItems; k += threads) results[k] = run_item(scene, k, native16);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();

  FILE* out = std::fopen(argv[2], "w");
  if (!out) return std::perror(argv[2]), 1;
  for (int occ = 0; occ < 2; ++occ)
    for (int api = 0; api < 8; ++api)
      if (g_calls[occ][api] > 0)
        std::fprintf(out, "calls %s%s %ld\n", occ ? "rtcOccluded" : "rtcIntersect", kApi[api], g_calls[occ][api].load());
  for (const std::string& s : results) std::fputs(s.c_str(), out);
  std::fclose(out);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return 0;
}
