#include "scene/surface_proximity.h"

#include <algorithm>
#include <cmath>

namespace vbsim {

namespace {

struct D3 {
  double x, y, z;
};
D3 d3(const Vec3f& v) { return {v.x, v.y, v.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(D3 a) { return std::sqrt(dot(a, a)); }

/// Distance from p to the segment a-b.
double segment_distance(D3 p, D3 a, D3 b) {
  const D3 ab = b - a;
  const double len2 = dot(ab, ab);
  const double s = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(p - (a + s * ab));
}

struct QueryState {
  const std::vector<Triangle>* triangles;
  double best;
  int64_t nearest;
};

bool on_candidate(RTCPointQueryFunctionArguments* args) {
  auto* st = static_cast<QueryState*>(args->userPtr);
  const Vec3f p{args->query->x, args->query->y, args->query->z};
  const double d = point_triangle_distance(p, (*st->triangles)[args->primID]);
  if (d < st->best) {
    st->best = d;
    st->nearest = args->primID;
  }
  return false;  // the query radius stays: the caller asks "any within", not "nearest"
}

}  // namespace

double point_triangle_distance(const Vec3f& pf, const Triangle& t) {
  const D3 p = d3(pf), a = d3(t.v0), b = d3(t.v1), c = d3(t.v2);
  const D3 ab = b - a, ac = c - a;
  const D3 n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
  const double n2 = dot(n, n);
  if (n2 > 0.0) {
    // Barycentrics of p's projection onto the plane; inside: the plane distance.
    const D3 ap = p - a;
    const double dist = dot(ap, n) / std::sqrt(n2);
    const D3 q = ap - (dist / std::sqrt(n2)) * n;
    const D3 c1{ab.y * q.z - ab.z * q.y, ab.z * q.x - ab.x * q.z, ab.x * q.y - ab.y * q.x};
    const D3 c2{q.y * ac.z - q.z * ac.y, q.z * ac.x - q.x * ac.z, q.x * ac.y - q.y * ac.x};
    const double v = dot(c1, n) / n2, u = dot(c2, n) / n2;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) return std::fabs(dist);
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

SurfaceProximity::SurfaceProximity(const std::vector<Triangle>& triangles)
    : triangles_(triangles), device_(std::make_unique<EmbreeDevice>()) {
  scene_ = rtcNewScene(device_->get());
  device_->check("rtcNewScene");
  RTCGeometry g = rtcNewGeometry(device_->get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = triangles_.size();
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t k = 0; k < n; ++k) {
    const Vec3f c[3] = {triangles_[k].v0, triangles_[k].v1, triangles_[k].v2};
    for (int j = 0; j < 3; ++j) {
      for (int a = 0; a < 3; ++a) v[9 * k + 3 * j + a] = c[j][a];
      idx[3 * k + j] = static_cast<unsigned>(3 * k + j);
    }
  }
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene_, g, 0);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene_);
  device_->check("point query scene build");
}

SurfaceProximity::~SurfaceProximity() { rtcReleaseScene(scene_); }

bool SurfaceProximity::within(const Vec3f& p, float radius, int64_t* nearest) const {
  if (triangles_.empty()) return false;
  RTCPointQuery q;
  q.x = p.x, q.y = p.y, q.z = p.z;
  q.time = 0.0f;
  q.radius = radius;
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  QueryState st{&triangles_, static_cast<double>(radius), -1};
  st.best = std::nextafter(static_cast<double>(radius), INFINITY);  // a triangle at exactly `radius` counts
  rtcPointQuery(scene_, &q, &ctx, on_candidate, &st);
  if (nearest) *nearest = st.nearest;
  return st.nearest >= 0;
}

}  // namespace vbsim
