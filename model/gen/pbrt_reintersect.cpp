#include "gen/pbrt_reintersect.h"

#include <algorithm>
#include <cmath>

#include "datapath/pbrt_interaction.h"
#include "datapath/testers.h"

namespace vbsim {

namespace {

constexpr uint64_t kPcgMultiplier = 0x5851f42d4c957f2dULL;
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
constexpr float kPi = 3.14159265358979323846f;

/// pbrt's MixBits (a 64-bit finaliser of the seed).
uint64_t mix_bits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

/// pExp: 10^Lerp(u, -exp, exp); pbrt's std::pow(10, logu) takes the double overload.
float p_exp(PbrtRng& rng, float exp) {
  const float t = rng.uniform_float();
  const float logu = (1 - t) * -exp + t * exp;
  return static_cast<float>(std::pow(10.0, static_cast<double>(logu)));
}

Vec3f p_exp_point(PbrtRng& rng, float exp) {
  Vec3f p;
  for (int k = 0; k < 3; ++k) p[k] = p_exp(rng, exp);
  return p;
}

/// SampleUniformSphere(u): z = 1 - 2 u0, r = sqrt(max(0, 1 - z z)), phi = 2 pi u1.
Vec3f sample_uniform_sphere(float u0, float u1) {
  const float z = 1 - 2 * u0;
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  const float phi = 2 * kPi * u1;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Triangle::Sample(u)'s point: SampleUniformTriangle's barycentrics, the
/// point b0 p0 + b1 p1 + b2 p2 with the bound gamma(6) (|b0 p0| + |b1 p1| + |b2 p2|),
/// and the interval's midpoint (what intr.p() returns).
Vec3f sample_triangle_point(const Triangle& tri, float u0, float u1) {
  float b0, b1;
  if (u0 < u1) {
    b0 = u0 / 2;
    b1 = u1 - b0;
  } else {
    b1 = u1 / 2;
    b0 = u0 - b1;
  }
  const float b2 = 1 - b0 - b1;
  const Vec3f p = b0 * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
  const Vec3f abs_sum = abs(b0 * tri.v0) + abs(b1 * tri.v1) + abs((1 - b0 - b1) * tri.v2);
  return pbrt::PointInterval::from_value_and_error(p, pbrt::gamma(6) * abs_sum).point();
}

TraceRay child_ray(int64_t id, RayKind kind, Vec3f o, Vec3f d, float tmax, const Triangle& tri,
                   const PbrtTriangleHit& hit) {
  TraceRay c;
  c.id = id;
  c.parent = 0;
  c.kind = kind;
  c.o = o;
  c.d = d;
  c.tmax = tmax;
  c.set_parent_hit(0, hit.t, hit.b1, hit.b2);
  c.sign = dot(d, geometric_normal(tri)) < 0.0f ? 1 : 0;  // the trace spec's parent sign bit
  return c;
}

}  // namespace

PbrtRng::PbrtRng(uint64_t sequence_index) : PbrtRng(sequence_index, mix_bits(sequence_index)) {}

PbrtRng::PbrtRng(uint64_t sequence_index, uint64_t seed) {
  // SetSequence: state 0, odd increment, one step, add the seed, one step.
  inc_ = (sequence_index << 1u) | 1u;
  next_u32();
  state_ += seed;
  next_u32();
}

uint32_t PbrtRng::next_u32() {
  const uint64_t old = state_;
  state_ = old * kPcgMultiplier + inc_;
  const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
  const uint32_t rot = static_cast<uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
}

float PbrtRng::uniform_float() {
  return std::min(kOneMinusEpsilon, static_cast<float>(next_u32()) * 0x1p-32f);
}

PbrtReintersectTrial pbrt_reintersect_trial(uint64_t index, int64_t children, float exp) {
  PbrtReintersectTrial trial;
  trial.index = index;
  PbrtRng rng(index);
  Vec3f v[3];
  for (Vec3f& vertex : v)
    for (int k = 0; k < 3; ++k) vertex[k] = p_exp(rng, exp);
  trial.tri = {v[0], v[1], v[2]};
  const float area2 = pbrt::pbrt_length_squared(pbrt::pbrt_cross(v[1] - v[0], v[2] - v[0]));
  if (static_cast<double>(area2) < 1e-20) {  // pbrt compares the float with the double 1e-20
    trial.degenerate = true;
    return trial;
  }
  const float su0 = rng.uniform_float(), su1 = rng.uniform_float();
  const Vec3f target = sample_triangle_point(trial.tri, su0, su1);
  const Vec3f o = p_exp_point(rng, exp);

  TraceRay camera;
  camera.id = 0;
  camera.kind = RayKind::Primary;
  camera.o = o;
  camera.d = target - o;
  trial.rays.push_back(camera);
  Ray ray;
  ray.o = camera.o;
  ray.d = camera.d;
  PbrtTriangleHit hit;
  trial.camera_hit =
      PbrtWatertightTester(ray).intersect_triangle(trial.tri, std::numeric_limits<float>::infinity(), hit);
  if (!trial.camera_hit) return trial;

  // The hit's SurfaceInteraction: no vertex normals in pbrt's test mesh.
  const pbrt::SurfacePoint sp = pbrt::triangle_interaction(trial.tri, hit.b0, hit.b1, hit.b2, nullptr);
  const Vec3f p = sp.pi.point();
  const float inf = std::numeric_limits<float>::infinity();
  int64_t id = 1;
  for (int64_t j = 0; j < children; ++j) {
    const float u0 = rng.uniform_float(), u1 = rng.uniform_float();
    trial.rays.push_back(child_ray(id++, RayKind::Diffuse, p, sample_uniform_sphere(u0, u1), inf, trial.tri, hit));
    const Vec3f p2 = p_exp_point(rng, exp);
    trial.rays.push_back(
        child_ray(id++, RayKind::Shadow, p, pbrt::spawn_direction_to(sp.pi, p2), 1.0f, trial.tri, hit));
  }
  return trial;
}

}  // namespace vbsim
