// ParentLinker: recovers the ray tree of one application thread from its
// Embree calls. A ray is the child of an earlier hit on the same thread when
// its origin is that hit's point (the hit ray's org + t dir in float32, as
// Embree's tutorials compute it, or the barycentric point on the triangle, as
// Cycles does: the tolerance is in ulps of the largest of |P|, |t dir| and
// the triangle's vertex coordinates, which bounds the rounding of both), optionally
// moved along the hit triangle's geometric normal (the offset renderers apply
// before spawning, e.g. Embree's own tutorials). The newest matching hit of
// the last `history` hits wins, or, for a ray whose filter functions rejected
// one primitive, the newest matching hit on that primitive; hits of shadow
// rays are never parents. Kinds: an occlusion query is a shadow ray, and
// so is an intersect child with a finite tfar below FLT_MAX (a visibility
// query toward a point, as Cycles casts its shadow rays); an
// intersect child that leaves on the far side of the surface is refract, one
// along the mirror direction about Ng is reflect, any other is diffuse; an
// unlinked intersect ray is primary (docs/capture.md states the rules).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "capture/captured_scene.h"
#include "capture/raw_capture_format.h"
#include "datapath/ray.h"

namespace vbsim::capture {

struct LinkRules {
  /// Per axis, the origin may differ from the hit point (after removing an
  /// offset along the normal) by this many ulps of the largest coordinate of
  /// the origin, the hit point, the parent's t dir and the hit triangle's
  /// vertices (either way of computing the point rounds within a few of those).
  int ulps = 16;
  /// A ray whose filter functions rejected a candidate on one primitive (the
  /// renderer's self-exclusion names its parent's primitive) and that matched
  /// no hit under `ulps` may link to a recent hit on that very primitive
  /// within this many ulps (same unit).
  int rejected_ulps = 64;
  /// A ray left without a parent starts on a surface when a triangle lies
  /// within this many ulps of the scene's largest coordinate of its origin
  /// (IncompleteRayJudge: such a ray is marked `unlinked`).
  int on_surface_ulps = 64;
  /// Largest offset along the geometric normal, as a fraction of
  /// max(|P|, |t d|) (largest coordinates); 0 links exact hit points only.
  double normal_offset = 1.0 / 1024.0;
  std::size_t history = 64;       ///< hits of the thread searched, newest first
  double mirror_radians = 1e-3;   ///< a reflect child is within this angle of the mirror direction
};

/// How a link was made: the origin at the hit point, moved along its normal,
/// or within rejected_ulps of a hit on the primitive the ray's filter rejected.
enum class LinkTier : uint8_t { None, AtHitPoint, NormalOffset, RejectedPrimitive };

struct RayLink {
  int64_t parent = -1;  ///< index of the parent record in the thread's sequence, or -1
  LinkTier tier = LinkTier::None;
  RayKind kind = RayKind::Primary;
  double offset = 0.0;  ///< |offset along Ng| / max(|P|, |t d|) for NormalOffset links
};

/// What a thread's linking found, summed over threads by the caller.
struct LinkCounts {
  int64_t at_hit_point = 0, normal_offset = 0, rejected_primitive = 0;
  int64_t unlinked_intersect = 0, unlinked_occluded = 0;
  double max_offset = 0.0;  ///< largest NormalOffset link's relative offset
  int64_t by_kind[kRayKindCount] = {};
  void add(const LinkCounts& o);
};

class ParentLinker {
 public:
  ParentLinker(const CapturedScene& scene, const LinkRules& rules) : scene_(scene), rules_(rules) {}

  /// Links `rays` (one thread's records, in call order). `eligible[i]` says
  /// whether ray i belongs to the trace (the chosen scene and commit, a valid
  /// ray); others are neither linked nor parents. Returns one link per ray.
  std::vector<RayLink> link(const RawRay* rays, std::size_t n, const std::vector<bool>& eligible,
                            LinkCounts& counts) const;

  /// Whether `child`'s origin is the hit point of `parent` (a hit on triangle
  /// `tri`) under the rules; fills tier and offset. Exposed for tests.
  bool origin_matches(const RawRay& parent, const Triangle& tri, const RawRay& child, RayLink& out) const;
  /// Kind of an intersect child of `parent` on `tri` (shadow when its tfar is
  /// finite and below FLT_MAX, else refract, reflect or diffuse).
  RayKind infer_kind(const RawRay& parent, const Triangle& tri, const RawRay& child) const;

  /// A hit as a candidate parent, with what the match needs computed once.
  struct Candidate {
    std::size_t index;  ///< of the hit's record in the thread's sequence
    int64_t triangle;
    Vec3f point;        ///< org + t dir in float32
    double normal[3];   ///< unit geometric normal of the triangle
    double size;        ///< max(|point|, |t dir|), largest coordinates
    double scale;       ///< max(size, the triangle's largest vertex coordinate): the ulps' unit
  };
  /// `tri` is triangle `triangle` of the scene.
  Candidate candidate(std::size_t index, const RawRay& hit, int64_t triangle, const Triangle& tri) const;

 private:
  bool matches(const Candidate& c, const RawRay& child, RayLink& out) const;
  /// Whether `child`'s filters rejected `c`'s primitive and its origin is
  /// within rejected_ulps of `c`'s point.
  bool matches_rejected(const Candidate& c, const RawRay& hit, const RawRay& child) const;

  const CapturedScene& scene_;
  LinkRules rules_;
};

}  // namespace vbsim::capture
