// The ray query functions the shim interposes, single rays, 4/8/16-wide
// packets and streams: each copies the active rays' inputs, calls the
// application's Embree with the same arguments, then copies the results and
// records one RawRay per active ray. A packet lane is active when its valid
// entry is -1; a stream ray is active when tnear <= tfar (Embree's rules).
#include <functional>
#include <type_traits>
#include <vector>

#include "capture_output.h"
#include "filter_watch.h"
#include "real_embree.h"
#include "scene_registry.h"

using namespace vbsim::shim;
using vbsim::capture::RawApi;
using vbsim::capture::RawOp;
using vbsim::capture::RawRay;

namespace {

/// Field k of lane i in an SOA block of width n (RTCRayN / RTCHitN layouts).
inline float soa_f(const void* base, unsigned n, unsigned k, unsigned i) {
  return static_cast<const float*>(base)[k * n + i];
}
inline unsigned soa_u(const void* base, unsigned n, unsigned k, unsigned i) {
  return static_cast<const unsigned*>(base)[k * n + i];
}

RawRay input(RawOp op, RawApi api, SceneStamp stamp, const float org[3], float tnear, const float dir[3], float time,
             float tfar, unsigned mask, unsigned flags) {
  RawRay r{};
  r.op = static_cast<uint16_t>(op);
  r.api = static_cast<uint16_t>(api);
  r.scene = stamp.scene;
  r.commit = stamp.commit;
  r.ray_flags = flags;
  for (int a = 0; a < 3; ++a) r.org[a] = org[a], r.dir[a] = dir[a];
  r.tnear = tnear;
  r.time = time;
  r.tfar = tfar;
  r.mask = mask;
  r.geom = r.prim = r.inst = vbsim::capture::kInvalidId;
  r.rejected_geom = r.rejected_prim = r.rejected_inst = vbsim::capture::kInvalidId;
  return r;
}

RawRay input_of(RawOp op, RawApi api, SceneStamp stamp, const RTCRay& ray) {
  const float org[3] = {ray.org_x, ray.org_y, ray.org_z}, dir[3] = {ray.dir_x, ray.dir_y, ray.dir_z};
  return input(op, api, stamp, org, ray.tnear, dir, ray.time, ray.tfar, ray.mask, ray.flags);
}

RawRay input_of_soa(RawOp op, RawApi api, SceneStamp stamp, const void* ray, unsigned n, unsigned i) {
  const float org[3] = {soa_f(ray, n, 0, i), soa_f(ray, n, 1, i), soa_f(ray, n, 2, i)};
  const float dir[3] = {soa_f(ray, n, 4, i), soa_f(ray, n, 5, i), soa_f(ray, n, 6, i)};
  return input(op, api, stamp, org, soa_f(ray, n, 3, i), dir, soa_f(ray, n, 7, i), soa_f(ray, n, 8, i),
               soa_u(ray, n, 9, i), soa_u(ray, n, 11, i));
}

void set_hit(RawRay& r, float t, float ngx, float ngy, float ngz, float u, float v, unsigned prim, unsigned geom,
             unsigned inst) {
  r.hit_t = t;
  r.ng[0] = ngx, r.ng[1] = ngy, r.ng[2] = ngz;
  r.u = u, r.v = v;
  r.prim = prim, r.geom = geom, r.inst = inst;
}

void output_of(RawRay& r, const RTCRayHit& rh) {
  set_hit(r, rh.ray.tfar, rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z, rh.hit.u, rh.hit.v, rh.hit.primID, rh.hit.geomID,
          rh.hit.instID[0]);
}

/// Results of lane i of an RTCRayHitN block of width n (hit fields after the 12 ray fields).
void output_of_soa(RawRay& r, const void* rayhit, unsigned n, unsigned i) {
  const void* hit = static_cast<const float*>(rayhit) + 12 * n;
  set_hit(r, soa_f(rayhit, n, 8, i), soa_f(hit, n, 0, i), soa_f(hit, n, 1, i), soa_f(hit, n, 2, i),
          soa_f(hit, n, 3, i), soa_f(hit, n, 4, i), soa_u(hit, n, 5, i), soa_u(hit, n, 6, i), soa_u(hit, n, 7, i));
}

template <unsigned N, class Packet, class Real>
void packet(RawOp op, RawApi api, const int* valid, RTCScene scene, RTCIntersectContext* ctx, Packet* p, Real real) {
  if (!capture_enabled()) return real(valid, scene, ctx, p);
  count_call(api, op == RawOp::Occluded);
  const SceneStamp stamp = scene_stamp(scene);
  RawRay saved[N];
  unsigned lanes[N], active = 0;
  for (unsigned i = 0; i < N; ++i)
    if (valid[i] == -1) {
      lanes[active] = i;
      saved[active++] = input_of_soa(op, api, stamp, p, N, i);
    }
  FilterWatch watch(ctx, N, true);
  real(valid, scene, ctx, p);
  for (unsigned k = 0; k < active; ++k) {
    if (op == RawOp::Intersect) output_of_soa(saved[k], p, N, lanes[k]);
    else saved[k].hit_t = soa_f(p, N, 8, lanes[k]);
    watch.describe(lanes[k], saved[k]);
    record_ray(saved[k]);
  }
}

}  // namespace

void rtcIntersect1(RTCScene scene, RTCIntersectContext* ctx, RTCRayHit* rh) {
  VBSIM_REAL(rtcIntersect1);
  if (!capture_enabled()) return real(scene, ctx, rh);
  count_call(RawApi::One, false);
  RawRay r = input_of(RawOp::Intersect, RawApi::One, scene_stamp(scene), rh->ray);
  {
    FilterWatch watch(ctx, 1, true);
    real(scene, ctx, rh);
    watch.describe(0, r);
  }
  output_of(r, *rh);
  record_ray(r);
}

void rtcOccluded1(RTCScene scene, RTCIntersectContext* ctx, RTCRay* ray) {
  VBSIM_REAL(rtcOccluded1);
  if (!capture_enabled()) return real(scene, ctx, ray);
  count_call(RawApi::One, true);
  RawRay r = input_of(RawOp::Occluded, RawApi::One, scene_stamp(scene), *ray);
  {
    FilterWatch watch(ctx, 1, true);
    real(scene, ctx, ray);
    watch.describe(0, r);
  }
  r.hit_t = ray->tfar;
  record_ray(r);
}

// The six packet functions: rtcIntersectW(valid, scene, ctx, RTCRayHitW*) and
// rtcOccludedW(valid, scene, ctx, RTCRayW*) for W = 4, 8, 16.
#define VBSIM_PACKET_HOOK(name, Packet, width, op, api)                                   \
  void name(const int* valid, RTCScene scene, RTCIntersectContext* ctx, Packet* p) {     \
    VBSIM_REAL(name);                                                                     \
    packet<width>(op, api, valid, scene, ctx, p, real);                                   \
  }
VBSIM_PACKET_HOOK(rtcIntersect4, RTCRayHit4, 4, RawOp::Intersect, RawApi::Four)
VBSIM_PACKET_HOOK(rtcIntersect8, RTCRayHit8, 8, RawOp::Intersect, RawApi::Eight)
VBSIM_PACKET_HOOK(rtcIntersect16, RTCRayHit16, 16, RawOp::Intersect, RawApi::Sixteen)
VBSIM_PACKET_HOOK(rtcOccluded4, RTCRay4, 4, RawOp::Occluded, RawApi::Four)
VBSIM_PACKET_HOOK(rtcOccluded8, RTCRay8, 8, RawOp::Occluded, RawApi::Eight)
VBSIM_PACKET_HOOK(rtcOccluded16, RTCRay16, 16, RawOp::Occluded, RawApi::Sixteen)
#undef VBSIM_PACKET_HOOK

// Streams of single rays: M RTCRayHit (or RTCRay) `stride` bytes apart, or M pointers to them.
namespace {

template <class Ray, class At, class Call>
void stream(RawOp op, RawApi api, RTCScene scene, RTCIntersectContext* ctx, unsigned m, At at, Call call) {
  count_call(api, op == RawOp::Occluded);
  const SceneStamp stamp = scene_stamp(scene);
  std::vector<RawRay> saved;  // inputs saved across the call (local: a filter function may trace too)
  std::vector<unsigned> lanes;
  for (unsigned i = 0; i < m; ++i) {
    const Ray& r = *at(i);
    const RTCRay& ray = reinterpret_cast<const RTCRay&>(r);
    if (ray.tnear <= ray.tfar) {
      lanes.push_back(i);
      saved.push_back(input_of(op, api, stamp, ray));
    }
  }
  FilterWatch watch(ctx, m, false);  // Embree regroups a stream: filter lanes are not its rays
  call();
  for (std::size_t k = 0; k < saved.size(); ++k) {
    const Ray& r = *at(lanes[k]);
    if constexpr (std::is_same_v<Ray, RTCRayHit>) output_of(saved[k], r);
    else saved[k].hit_t = reinterpret_cast<const RTCRay&>(r).tfar;
    watch.describe(FilterWatch::kMaxLanes, saved[k]);
    record_ray(saved[k]);
  }
}

}  // namespace

void rtcIntersect1M(RTCScene scene, RTCIntersectContext* ctx, RTCRayHit* rh, unsigned int m, size_t stride) {
  VBSIM_REAL(rtcIntersect1M);
  if (!capture_enabled()) return real(scene, ctx, rh, m, stride);
  auto at = [&](unsigned i) { return reinterpret_cast<const RTCRayHit*>(reinterpret_cast<const char*>(rh) + i * stride); };
  stream<RTCRayHit>(RawOp::Intersect, RawApi::OneM, scene, ctx, m, at, [&] { real(scene, ctx, rh, m, stride); });
}
void rtcOccluded1M(RTCScene scene, RTCIntersectContext* ctx, RTCRay* ray, unsigned int m, size_t stride) {
  VBSIM_REAL(rtcOccluded1M);
  if (!capture_enabled()) return real(scene, ctx, ray, m, stride);
  auto at = [&](unsigned i) { return reinterpret_cast<const RTCRay*>(reinterpret_cast<const char*>(ray) + i * stride); };
  stream<RTCRay>(RawOp::Occluded, RawApi::OneM, scene, ctx, m, at, [&] { real(scene, ctx, ray, m, stride); });
}
void rtcIntersect1Mp(RTCScene scene, RTCIntersectContext* ctx, RTCRayHit** rh, unsigned int m) {
  VBSIM_REAL(rtcIntersect1Mp);
  if (!capture_enabled()) return real(scene, ctx, rh, m);
  stream<RTCRayHit>(RawOp::Intersect, RawApi::OneMp, scene, ctx, m, [&](unsigned i) { return rh[i]; },
                    [&] { real(scene, ctx, rh, m); });
}
void rtcOccluded1Mp(RTCScene scene, RTCIntersectContext* ctx, RTCRay** ray, unsigned int m) {
  VBSIM_REAL(rtcOccluded1Mp);
  if (!capture_enabled()) return real(scene, ctx, ray, m);
  stream<RTCRay>(RawOp::Occluded, RawApi::OneMp, scene, ctx, m, [&](unsigned i) { return ray[i]; },
                 [&] { real(scene, ctx, ray, m); });
}

// Streams of M packets of width N, `stride` bytes apart (RTCRayHitN / RTCRayN blocks).
namespace {

void packet_stream(RawOp op, RTCScene scene, RTCIntersectContext* ctx, const void* base, unsigned n,
                   unsigned m, size_t stride, const std::function<void()>& call) {
  count_call(RawApi::NM, op == RawOp::Occluded);
  const SceneStamp stamp = scene_stamp(scene);
  auto block = [&](unsigned j) { return static_cast<const char*>(base) + j * stride; };
  std::vector<RawRay> saved;  // inputs saved across the call (local: a filter function may trace too)
  std::vector<unsigned> lanes;
  for (unsigned j = 0; j < m; ++j)
    for (unsigned i = 0; i < n; ++i)
      if (soa_f(block(j), n, 3, i) <= soa_f(block(j), n, 8, i)) {
        lanes.push_back(j * n + i);
        saved.push_back(input_of_soa(op, RawApi::NM, stamp, block(j), n, i));
      }
  FilterWatch watch(ctx, n * m, false);
  call();
  for (std::size_t k = 0; k < saved.size(); ++k) {
    const unsigned j = lanes[k] / n, i = lanes[k] % n;
    if (op == RawOp::Intersect) output_of_soa(saved[k], block(j), n, i);
    else saved[k].hit_t = soa_f(block(j), n, 8, i);
    watch.describe(FilterWatch::kMaxLanes, saved[k]);
    record_ray(saved[k]);
  }
}

/// Lane i of a pointer-SOA stream (RTCRayNp: one array per field).
RawRay input_of_np(RawOp op, SceneStamp stamp, const RTCRayNp& r, unsigned i) {
  const float org[3] = {r.org_x[i], r.org_y[i], r.org_z[i]}, dir[3] = {r.dir_x[i], r.dir_y[i], r.dir_z[i]};
  return input(op, RawApi::Np, stamp, org, r.tnear[i], dir, r.time[i], r.tfar[i], r.mask[i], r.flags[i]);
}

/// Counts the call and saves the inputs of the active rays of a pointer-SOA stream.
void save_np(RawOp op, RTCScene scene, const RTCRayNp& r, unsigned n, std::vector<RawRay>& saved,
             std::vector<unsigned>& lanes) {
  count_call(RawApi::Np, op == RawOp::Occluded);
  const SceneStamp stamp = scene_stamp(scene);
  for (unsigned i = 0; i < n; ++i)
    if (r.tnear[i] <= r.tfar[i]) {
      lanes.push_back(i);
      saved.push_back(input_of_np(op, stamp, r, i));
    }
}

}  // namespace

void rtcIntersectNM(RTCScene scene, RTCIntersectContext* ctx, RTCRayHitN* rh, unsigned int n, unsigned int m,
                    size_t stride) {
  VBSIM_REAL(rtcIntersectNM);
  if (!capture_enabled()) return real(scene, ctx, rh, n, m, stride);
  packet_stream(RawOp::Intersect, scene, ctx, rh, n, m, stride, [&] { real(scene, ctx, rh, n, m, stride); });
}
void rtcOccludedNM(RTCScene scene, RTCIntersectContext* ctx, RTCRayN* ray, unsigned int n, unsigned int m,
                   size_t stride) {
  VBSIM_REAL(rtcOccludedNM);
  if (!capture_enabled()) return real(scene, ctx, ray, n, m, stride);
  packet_stream(RawOp::Occluded, scene, ctx, ray, n, m, stride, [&] { real(scene, ctx, ray, n, m, stride); });
}

void rtcIntersectNp(RTCScene scene, RTCIntersectContext* ctx, const RTCRayHitNp* rh, unsigned int n) {
  VBSIM_REAL(rtcIntersectNp);
  if (!capture_enabled()) return real(scene, ctx, rh, n);
  std::vector<RawRay> saved;  // inputs saved across the call (local: a filter function may trace too)
  std::vector<unsigned> lanes;
  save_np(RawOp::Intersect, scene, rh->ray, n, saved, lanes);
  FilterWatch watch(ctx, n, false);
  real(scene, ctx, rh, n);
  for (std::size_t k = 0; k < saved.size(); ++k) {
    watch.describe(FilterWatch::kMaxLanes, saved[k]);
    const unsigned i = lanes[k];
    const RTCHitNp& h = rh->hit;
    set_hit(saved[k], rh->ray.tfar[i], h.Ng_x[i], h.Ng_y[i], h.Ng_z[i], h.u[i], h.v[i], h.primID[i], h.geomID[i],
            h.instID[0][i]);
    record_ray(saved[k]);
  }
}
void rtcOccludedNp(RTCScene scene, RTCIntersectContext* ctx, const RTCRayNp* ray, unsigned int n) {
  VBSIM_REAL(rtcOccludedNp);
  if (!capture_enabled()) return real(scene, ctx, ray, n);
  std::vector<RawRay> saved;
  std::vector<unsigned> lanes;
  save_np(RawOp::Occluded, scene, *ray, n, saved, lanes);
  FilterWatch watch(ctx, n, false);
  real(scene, ctx, ray, n);
  for (std::size_t k = 0; k < saved.size(); ++k) {
    watch.describe(FilterWatch::kMaxLanes, saved[k]);
    saved[k].hit_t = ray->tfar[lanes[k]];
    record_ray(saved[k]);
  }
}
