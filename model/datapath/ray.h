// Ray: the record the accelerator holds for one ray in flight.
//
// Bits per ray in flight (what each method adds to the hardware's ray store):
//   origin 96 + direction 96 + tmin 32 + tmax 32 + kind 3            = 259 bits, every method
//   validity-bit / sign-only: + 1 bit (the parent sign bit)
//   primid:                   + 32 bits (the parent triangle id)
//   offsets, tmin, shading-position, reverse-shadow: + 0 (work at emission)
//   traces with ray masks: + 32 bits (the mask), every method; not priced
// method_bits_per_ray() in self_intersection_method.h computes this per method.
#pragma once
#include <cstdint>
#include <limits>

#include "datapath/vec3.h"

namespace vbsim {

enum class RayKind : uint8_t { Primary = 0, Reflect = 1, Refract = 2, Diffuse = 3, Shadow = 4 };
constexpr int kRayKindCount = 5;

/// Name as the trace format spells it ("primary", "reflect", ...).
const char* ray_kind_name(RayKind kind);
/// Parses a trace kind name; false when the name is not one of the five.
bool parse_ray_kind(const char* name, RayKind& out);

constexpr int kBaseRayBits = 96 + 96 + 32 + 32 + 3;

struct Ray {
  Vec3f o;                 ///< origin (after any emission-time offset)
  Vec3f d;                 ///< direction, not necessarily unit length, never zero
  float tmin = 0.0f;       ///< candidate hits need t > tmin (units of d)
  float tmax = std::numeric_limits<float>::infinity();  ///< and t < tmax
  RayKind kind = RayKind::Primary;
  uint8_t sign = 0;        ///< parent sign bit: 1 when dot(d, Ng(parent_prim)) < 0
  int32_t parent_prim = -1;  ///< parent triangle, held only for the primid method
  /// Ray mask (Embree's): the ray sees a triangle whose mask shares a bit with
  /// it. All bits unless the trace declares masks; held only for such traces.
  uint32_t mask = 0xffffffffu;
};

}  // namespace vbsim
