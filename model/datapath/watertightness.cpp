#include "datapath/watertightness.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

namespace vbsim {

namespace {

/// A point to aim at and the triangles that contain it.
struct Target {
  Vec3f p;
  bool on_feature_exactly = false;  ///< p lies exactly on its edge or vertex
  int first_incident = 0;           ///< range in MeshTargets::incident
  int incident_count = 0;
};

struct MeshTargets {
  std::vector<Target> targets;
  std::vector<int> incident;  ///< triangle indices, ranges named by Target
};

/// True when fl(a + b) == s is the exact sum (Knuth's two-sum error is zero).
bool sum_is_exact(float a, float b, float s) {
  const float b_virtual = s - a;
  const float a_virtual = s - b_virtual;
  return (a - a_virtual) + (b - b_virtual) == 0.0f;
}

/// a + s (b - a) in float32 for a power-of-two s in (0, 1); `exact` when no step rounded.
Vec3f lerp_on_edge(Vec3f a, Vec3f b, float s, bool& exact) {
  Vec3f p;
  exact = true;
  for (int i = 0; i < 3; ++i) {
    const float diff = b[i] - a[i];
    const float scaled = s * diff;
    p[i] = a[i] + scaled;
    exact = exact && sum_is_exact(b[i], -a[i], diff) && scaled / s == diff &&
            sum_is_exact(a[i], scaled, p[i]);
  }
  return p;
}

/// 0.5 (a + b) in float32; `exact` when no step rounded.
Vec3f midpoint_of_edge(Vec3f a, Vec3f b, bool& exact) {
  Vec3f p;
  exact = true;
  for (int i = 0; i < 3; ++i) {
    const float sum = a[i] + b[i];
    p[i] = 0.5f * sum;
    exact = exact && sum_is_exact(a[i], b[i], sum) && p[i] * 2.0f == sum;
  }
  return p;
}

using VertexKey = std::array<uint32_t, 3>;
VertexKey key_of(Vec3f p) {
  VertexKey key;
  for (int i = 0; i < 3; ++i) {
    const float c = p[i] + 0.0f;  // -0 and +0 are the same position
    std::memcpy(&key[i], &c, sizeof c);
  }
  return key;
}

std::string describe(Vec3f p) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z); }

/// Edges and vertices of a consistently wound mesh, as aiming targets. A closed
/// mesh must have every edge in two triangles; an open one (`allow_open`) has
/// its boundary edges and their vertices left out and counted.
MeshTargets build_targets(const std::vector<Triangle>& mesh, bool allow_open, int64_t* open_edges = nullptr) {
  std::map<VertexKey, int> vertex_id;
  std::vector<Vec3f> positions;
  std::vector<std::vector<int>> triangles_at_vertex;
  // Directed edge (from, to) -> triangle; a closed, consistently wound mesh has
  // every undirected edge once in each direction.
  std::map<std::pair<int, int>, int> directed_edge;

  for (size_t k = 0; k < mesh.size(); ++k) {
    const Vec3f corners[3] = {mesh[k].v0, mesh[k].v1, mesh[k].v2};
    int ids[3];
    for (int c = 0; c < 3; ++c) {
      auto inserted = vertex_id.emplace(key_of(corners[c]), static_cast<int>(positions.size()));
      if (inserted.second) {
        positions.push_back(corners[c]);
        triangles_at_vertex.emplace_back();
      }
      ids[c] = inserted.first->second;
    }
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0])
      throw std::invalid_argument(
          fmt::format("watertightness: triangle {} has two equal vertices", k));
    for (int c = 0; c < 3; ++c) {
      triangles_at_vertex[ids[c]].push_back(static_cast<int>(k));
      const std::pair<int, int> edge{ids[c], ids[(c + 1) % 3]};
      if (!directed_edge.emplace(edge, static_cast<int>(k)).second)
        throw std::invalid_argument(fmt::format(
            "watertightness: edge {} -> {} is used in the same direction by triangles {} and {}; "
            "the mesh is not consistently wound or not a closed 2-manifold",
            describe(positions[edge.first]), describe(positions[edge.second]),
            directed_edge[edge], k));
    }
  }

  MeshTargets out;
  auto add_target = [&out](Vec3f p, bool exact, std::initializer_list<int> tris) {
    out.targets.push_back({p, exact, static_cast<int>(out.incident.size()),
                           static_cast<int>(tris.size())});
    out.incident.insert(out.incident.end(), tris);
  };
  std::vector<bool> on_boundary(positions.size(), false);
  for (const auto& [edge, tri] : directed_edge) {
    auto twin = directed_edge.find({edge.second, edge.first});
    if (twin == directed_edge.end()) {
      if (!allow_open)
        throw std::invalid_argument(fmt::format(
            "watertightness: edge {} -> {} of triangle {} has no neighbour; the mesh is not closed",
            describe(positions[edge.first]), describe(positions[edge.second]), tri));
      on_boundary[edge.first] = on_boundary[edge.second] = true;
      if (open_edges) ++*open_edges;
      continue;
    }
    if (edge.first > edge.second) continue;  // each undirected edge once, from its lower id
    const Vec3f a = positions[edge.first], b = positions[edge.second];
    bool exact = false;
    Vec3f p = lerp_on_edge(a, b, 0.25f, exact);
    add_target(p, exact, {tri, twin->second});
    p = midpoint_of_edge(a, b, exact);
    add_target(p, exact, {tri, twin->second});
    p = lerp_on_edge(a, b, 0.75f, exact);
    add_target(p, exact, {tri, twin->second});
  }
  for (size_t v = 0; v < positions.size(); ++v) {
    if (on_boundary[v]) continue;
    out.targets.push_back({positions[v], true, static_cast<int>(out.incident.size()),
                           static_cast<int>(triangles_at_vertex[v].size())});
    out.incident.insert(out.incident.end(), triangles_at_vertex[v].begin(),
                        triangles_at_vertex[v].end());
  }
  return out;
}

/// True when d crosses every incident triangle's plane at |cos| > 0.01, all from the same side.
bool crosses_transversally(const std::vector<Triangle>& mesh, const int* incident, int count,
                           Vec3f d) {
  const double dx = d.x, dy = d.y, dz = d.z;
  const double d_len = std::sqrt(dx * dx + dy * dy + dz * dz);
  int positive = 0, negative = 0;
  for (int i = 0; i < count; ++i) {
    const Triangle& tri = mesh[incident[i]];
    const double e1[3] = {double(tri.v1.x) - tri.v0.x, double(tri.v1.y) - tri.v0.y,
                          double(tri.v1.z) - tri.v0.z};
    const double e2[3] = {double(tri.v2.x) - tri.v0.x, double(tri.v2.y) - tri.v0.y,
                          double(tri.v2.z) - tri.v0.z};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    const double n_len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double cosine = (dx * n[0] + dy * n[1] + dz * n[2]) / (d_len * n_len);
    if (cosine > 0.01) ++positive;
    else if (cosine < -0.01) ++negative;
  }
  return positive == count || negative == count;
}

/// Shoots one ray at every triangle and updates the counts.
template <class Tester>
void shoot(const Tester& tester, const std::vector<Triangle>& mesh, const int* incident,
           int incident_count, WatertightnessCounts& counts) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  float nearest = kInf;
  int at_nearest = 0;
  bool any_hit = false, incident_hit = false;
  for (size_t k = 0; k < mesh.size(); ++k) {
    Hit hit;
    if (!tester.intersect(mesh[k], kInf, hit)) continue;
    any_hit = true;
    if (hit.t < nearest) {
      nearest = hit.t;
      at_nearest = 1;
    } else if (hit.t == nearest) {
      ++at_nearest;
    }
    if (!incident_hit)
      incident_hit = std::find(incident, incident + incident_count, static_cast<int>(k)) !=
                     incident + incident_count;
  }
  ++counts.rays;
  if (any_hit) ++counts.hit;
  else ++counts.lost;
  if (!incident_hit) ++counts.holes;
  if (at_nearest > 1) ++counts.double_hits;
}

}  // namespace

int64_t watertightness_target_count(const std::vector<Triangle>& mesh, bool allow_open) {
  return static_cast<int64_t>(build_targets(mesh, allow_open).targets.size());
}

WatertightnessCounts measure_watertightness(const std::vector<Triangle>& mesh, TesterKind kind,
                                            const std::vector<Vec3f>& origins, bool allow_open) {
  WatertightnessCounts counts;
  const MeshTargets targets = build_targets(mesh, allow_open, &counts.open_edges);
  for (const Vec3f& o : origins) {
    for (const Target& target : targets.targets) {
      Ray ray;
      ray.o = o;
      ray.d = target.p - o;
      const int* incident = targets.incident.data() + target.first_incident;
      if (!is_finite(ray.d) || ray.d == Vec3f{} ||
          !crosses_transversally(mesh, incident, target.incident_count, ray.d)) {
        ++counts.skipped;
        continue;
      }
      const bool d_exact = sum_is_exact(target.p.x, -o.x, ray.d.x) &&
                           sum_is_exact(target.p.y, -o.y, ray.d.y) &&
                           sum_is_exact(target.p.z, -o.z, ray.d.z);
      if (d_exact && target.on_feature_exactly) ++counts.exact_aim;
      if (kind == TesterKind::ThreeHalfPlane)
        shoot(ThreeHalfPlaneTester(ray), mesh, incident, target.incident_count, counts);
      else if (kind == TesterKind::PbrtWatertight)
        shoot(PbrtWatertightTester(ray), mesh, incident, target.incident_count, counts);
      else
        shoot(MollerTrumboreTester(ray), mesh, incident, target.incident_count, counts);
    }
  }
  return counts;
}

std::vector<Vec3f> watertightness_origins(const std::vector<Triangle>& mesh, int outside,
                                          int inside, uint32_t seed) {
  if (mesh.empty()) throw std::invalid_argument("watertightness_origins: empty mesh");
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const Triangle& tri : mesh) {
    for (const Vec3f& p : {tri.v0, tri.v1, tri.v2}) {
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], double(p[i]));
        hi[i] = std::max(hi[i], double(p[i]));
      }
    }
  }
  double centre[3], half[3];
  for (int i = 0; i < 3; ++i) {
    centre[i] = 0.5 * (lo[i] + hi[i]);
    half[i] = 0.5 * (hi[i] - lo[i]);
  }
  const double half_diagonal = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
  const double smallest_half = std::min({half[0], half[1], half[2]});

  // mt19937's output sequence is fixed by the standard; the distributions of
  // <random> are not, so uniform numbers are made here from its raw bits.
  std::mt19937 gen(seed);
  auto uniform_in_ball = [&gen](double out[3]) {
    for (;;) {
      double r2 = 0.0;
      for (int i = 0; i < 3; ++i) {
        out[i] = 2.0 * (gen() >> 8) * (1.0 / 16777216.0) - 1.0;
        r2 += out[i] * out[i];
      }
      if (r2 <= 1.0 && r2 > 1e-6) return r2;
    }
  };
  std::vector<Vec3f> origins;
  for (int n = 0; n < outside + inside; ++n) {
    double q[3];
    const double r2 = uniform_in_ball(q);
    const double radius = n < outside ? 2.5 * half_diagonal / std::sqrt(r2) : 0.3 * smallest_half;
    origins.push_back({static_cast<float>(centre[0] + radius * q[0]),
                       static_cast<float>(centre[1] + radius * q[1]),
                       static_cast<float>(centre[2] + radius * q[2])});
  }
  return origins;
}

}  // namespace vbsim
