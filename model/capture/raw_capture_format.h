// The files the Embree capture shim (model/capture_shim/) writes and `vbsim capture` reads:
// plain structs, little-endian as the host (the capture runs and is merged on
// the same machine), shared by both sides; standard library only, since the
// shim is loaded into applications that know nothing of vbsim.
//
// In the directory named by VBSIM_CAPTURE_DIR, per process image <image>,
// named <pid>.<g>: the process's pid and the first g from 0 whose summary
// file did not exist yet when the image first wrote (claimed with O_EXCL), so
// an image that a process exec()s under the same pid, a forked child and a
// later process with a reused pid each write files of their own:
//   rays-<image>-<k>.bin        RawRay records of the k-th thread that traced
//                               a ray, in the order that thread made its calls
//   scene-<image>-<s>-<c>.bin   scene s (0-based, in rtcNewScene order) at its
//                               c-th rtcCommitScene (from 1): RawSceneHeader,
//                               then per attached geometry a RawGeometry and,
//                               when captured, its vertices and indices
//   process-<image>.txt         created empty when the image claims its name;
//                               written when the process exits normally or
//                               just before it exec()s another program:
//                               "key value" lines (calls and rays per API,
//                               threads, scenes, commits, whether a shared
//                               libembree3 was loaded, filter functions the
//                               shim could not watch, whether Embree
//                               honours ray masks, ended_by_exec) ending
//                               with "complete 1"; without that line the
//                               image did not finish
//   refused-<image>.txt         why the shim refused to capture the image
//                               (one line of text): Embree out of its reach
//                               (dlmopen, Embree 4). Written when the image
//                               tried to use such an Embree, after which the
//                               shim ended it with kShimRefusedStatus, or at
//                               its exit; `vbsim capture` then writes no trace
#pragma once
#include <cstdint>

namespace vbsim::capture {

constexpr const char* kCaptureDirEnv = "VBSIM_CAPTURE_DIR";

/// The exit status the shim ends a process with when it refuses to capture it
/// (after writing refused-<image>.txt and the reason on stderr).
constexpr int kShimRefusedStatus = 70;

enum class RawOp : uint16_t { Intersect = 1, Occluded = 2 };

/// The Embree entry point a ray came through.
enum class RawApi : uint16_t { One = 0, Four, Eight, Sixteen, OneM, OneMp, NM, Np };
constexpr int kRawApiCount = 8;
/// Name of the intersect (or occluded) function of `api`, e.g. "rtcIntersect4".
inline const char* raw_api_name(RawApi api, bool occluded) {
  static const char* const intersect[] = {"rtcIntersect1",  "rtcIntersect4",   "rtcIntersect8",  "rtcIntersect16",
                                          "rtcIntersect1M", "rtcIntersect1Mp", "rtcIntersectNM", "rtcIntersectNp"};
  static const char* const occlude[] = {"rtcOccluded1",  "rtcOccluded4",   "rtcOccluded8",  "rtcOccluded16",
                                        "rtcOccluded1M", "rtcOccluded1Mp", "rtcOccludedNM", "rtcOccludedNp"};
  const int k = static_cast<int>(api);
  return k < kRawApiCount ? (occluded ? occlude[k] : intersect[k]) : "unknown";
}

constexpr uint32_t kInvalidId = 0xffffffffu;  ///< RTC_INVALID_GEOMETRY_ID

/// One traced ray: what the application passed and what Embree returned.
struct RawRay {
  uint16_t op;       ///< RawOp
  uint16_t api;      ///< RawApi
  uint32_t scene;    ///< scene ordinal in the process
  uint32_t commit;   ///< that scene's commits so far (0: traced before any commit)
  uint32_t ray_flags;
  float org[3];
  float tnear;
  float dir[3];
  float time;
  float tfar;        ///< as passed in
  uint32_t mask;
  float hit_t;       ///< tfar after the call: the hit distance; unchanged on a miss; -inf when occluded
  float ng[3];       ///< Embree's unnormalised geometric normal (intersect hits)
  float u, v;
  uint32_t geom;     ///< geomID of the hit, kInvalidId for a miss or an occlusion query
  uint32_t prim;
  uint32_t inst;     ///< instID[0]: kInvalidId unless the hit is inside an instance
  uint32_t flags;    ///< RawRayFlag bits
  /// The candidate hit the application's filter functions rejected for this
  /// ray (kRawFilterRejected): geomID, primID and instID[0] as Embree passed
  /// them to the filter; kInvalidId when none was rejected.
  uint32_t rejected_geom;
  uint32_t rejected_prim;
  uint32_t rejected_inst;
  uint32_t rejections;  ///< how many times a filter rejected a candidate for this ray
};

/// What else took part in a ray's call (RawRay::flags).
enum RawRayFlag : uint32_t {
  /// A filter function changed the answer in a way the record does not
  /// describe: it changed a candidate hit or the ray's tfar, rejected
  /// candidates on more than one primitive, or ran where the shim cannot tell
  /// which ray it filtered (a stream call, a one-ray call inside a packet).
  kRawFilterChanged = 1u << 0,
  /// The call's intersect context carried a filter function the shim could
  /// not watch (every trampoline taken): what it decided is unknown.
  kRawContextFilter = 1u << 1,
  /// Filter functions (geometry or context) rejected candidate hits of this
  /// ray, every one on the primitive named by rejected_geom/prim/inst.
  kRawFilterRejected = 1u << 2,
};
static_assert(sizeof(RawRay) == 112, "RawRay is a 112-byte record");

/// Whether the filter functions of `ray` rejected candidates on the primitive
/// `hit` hit, and on no other (kRawFilterRejected naming hit's geom, prim, inst).
inline bool filters_rejected_hit(const RawRay& ray, const RawRay& hit) {
  return (ray.flags & kRawFilterRejected) && hit.geom != kInvalidId && ray.rejected_geom == hit.geom &&
         ray.rejected_prim == hit.prim && ray.rejected_inst == hit.inst;
}

constexpr char kRawSceneMagic[8] = {'V', 'B', 'C', 'A', 'P', 'S', 'C', '1'};

struct RawSceneHeader {
  char magic[8];
  uint32_t scene;
  uint32_t commit;
  uint32_t geometries;  ///< RawGeometry entries that follow
  uint32_t reserved;
};
static_assert(sizeof(RawSceneHeader) == 24, "RawSceneHeader is 24 bytes");

/// Why a geometry's triangles are (not) in the snapshot.
enum class RawGeometryStatus : uint32_t {
  Captured = 0,       ///< vertex_count float3, then triangle_count primitives: uint3 (triangles) or uint4
                      ///< (quads); for an instance a RawInstance instead
  NotTriangles = 1,   ///< another geometry type than triangles and quads (curves, instances, user, ...)
  MotionBlur = 2,     ///< more than one time step
  MissingBuffer = 3,  ///< no vertex or index buffer set
  BadFormat = 4,      ///< a buffer format other than FLOAT3 vertices and UINT3 (quads: UINT4) indices
  Disabled = 5,       ///< rtcDisableGeometry: Embree does not trace it
  NestedInstance = 6, ///< (vbsim's reading only) an instance of a scene that holds instances
};

struct RawGeometry {
  uint32_t geom_id;
  uint32_t type;            ///< RTCGeometryType
  uint32_t status;          ///< RawGeometryStatus
  uint32_t vertex_count;    ///< 0 unless captured
  uint32_t triangle_count;  ///< primitives (triangles or quads); 0 unless captured
  uint32_t filters;         ///< RawGeometryFilter bits: filter functions set on the geometry
  uint32_t mask;            ///< rtcSetGeometryMask's mask (0xffffffff unless the application set one)
  uint32_t reserved;        ///< 0
};

/// What follows a captured instance's RawGeometry: the scene it instances and its transform.
struct RawInstance {
  uint32_t scene;    ///< ordinal of the instanced scene in the process
  uint32_t commit;   ///< that scene's snapshot when the instancing scene was committed
  float xfm[12];     ///< row-major 3x4: world = M object (instance_transform.h)
};
static_assert(sizeof(RawInstance) == 56, "RawInstance is 56 bytes");

enum RawGeometryFilter : uint32_t { kRawIntersectFilter = 1u << 0, kRawOccludedFilter = 1u << 1 };
static_assert(sizeof(RawGeometry) == 32, "RawGeometry is 32 bytes");

}  // namespace vbsim::capture
