#include "capture/captured_scene.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <fmt/format.h>

namespace vbsim::capture {

namespace {

/// Reads fixed-size items from the snapshot bytes, failing with the file's name when they run out.
struct Cursor {
  const std::string& path;
  const std::string& bytes;
  std::size_t at = 0;

  void take(void* out, std::size_t n, const char* what) {
    if (bytes.size() - at < n)
      throw std::runtime_error(fmt::format("{}: truncated scene snapshot (in {})", path, what));
    std::memcpy(out, bytes.data() + at, n);
    at += n;
  }
};

}  // namespace

namespace {

/// `p` under the row-major 3x4 transform `m`, in double, rounded once to float32.
Vec3f transformed(const float m[12], Vec3f p) {
  const double x = p.x, y = p.y, z = p.z;
  return {static_cast<float>(double(m[0]) * x + double(m[1]) * y + double(m[2]) * z + double(m[3])),
          static_cast<float>(double(m[4]) * x + double(m[5]) * y + double(m[6]) * z + double(m[7])),
          static_cast<float>(double(m[8]) * x + double(m[9]) * y + double(m[10]) * z + double(m[11]))};
}

/// The one mask of an instanced triangle whose instance has mask `instance`
/// and whose geometry has `geometry` (Embree tests both against the ray);
/// records the pair in `unheld` when one mask cannot stand for both.
uint32_t instanced_mask(uint32_t instance, uint32_t geometry, std::vector<std::pair<uint32_t, uint32_t>>& unheld) {
  if (instance == 0xffffffffu || instance == geometry) return geometry;
  if (geometry == 0xffffffffu) return instance;
  const std::pair<uint32_t, uint32_t> pair{instance, geometry};
  if (std::find(unheld.begin(), unheld.end(), pair) == unheld.end()) unheld.push_back(pair);
  return geometry;
}

}  // namespace

CapturedScene CapturedScene::read(const std::string& path, const SnapshotFinder& find) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the scene snapshot", path));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Cursor c{path, bytes};
  RawSceneHeader h;
  c.take(&h, sizeof h, "the header");
  if (std::memcmp(h.magic, kRawSceneMagic, sizeof h.magic) != 0)
    throw std::runtime_error(fmt::format("{}: not a capture scene snapshot", path));
  CapturedScene s;
  s.scene_ = h.scene;
  s.commit_ = h.commit;
  for (uint32_t g = 0; g < h.geometries; ++g) {
    RawGeometry rg;
    c.take(&rg, sizeof rg, "a geometry entry");
    CapturedGeometry cg;
    cg.geom_id = rg.geom_id;
    cg.type = rg.type;
    cg.status = static_cast<RawGeometryStatus>(rg.status);
    cg.filters = rg.filters;
    cg.mask = rg.mask;
    if (cg.status == RawGeometryStatus::Captured && rg.type == RTC_GEOMETRY_TYPE_INSTANCE) {
      RawInstance ri;
      c.take(&ri, sizeof ri, "an instance");
      const std::string child_path = find ? find(ri.scene, ri.commit) : std::string();
      if (child_path.empty()) {
        cg.status = RawGeometryStatus::MissingBuffer;
      } else {
        auto child = std::make_shared<const CapturedScene>(read(child_path, find));
        if (child->has_instances_) {
          cg.status = RawGeometryStatus::NestedInstance;
        } else {
          cg.first_triangle = static_cast<int64_t>(s.triangles_.size());
          cg.triangles = static_cast<uint32_t>(child->triangles_.size());
          for (std::size_t k = 0; k < child->triangles_.size(); ++k) {
            const Triangle& t = child->triangles_[k];
            s.triangles_.push_back({transformed(ri.xfm, t.v0), transformed(ri.xfm, t.v1), transformed(ri.xfm, t.v2)});
            s.triangle_masks_.push_back(instanced_mask(cg.mask, child->triangle_masks_[k], s.unheld_masks_));
          }
          if (s.first_by_geom_.size() <= cg.geom_id) {
            s.first_by_geom_.resize(cg.geom_id + 1, -1);
            s.count_by_geom_.resize(cg.geom_id + 1, 0);
            s.quads_by_geom_.resize(cg.geom_id + 1, false);
          }
          s.first_by_geom_[cg.geom_id] = cg.first_triangle;
          s.count_by_geom_[cg.geom_id] = 0;  // no primitive of its own: hits inside map through the instanced scene
          if (s.instanced_by_geom_.size() <= cg.geom_id) s.instanced_by_geom_.resize(cg.geom_id + 1);
          s.instanced_by_geom_[cg.geom_id] = std::move(child);
          s.has_instances_ = true;
        }
      }
    } else if (cg.status == RawGeometryStatus::Captured) {
      std::vector<Vec3f> vertices(rg.vertex_count);
      for (Vec3f& v : vertices) c.take(&v, 3 * sizeof(float), "vertices");
      const bool quads = rg.type == RTC_GEOMETRY_TYPE_QUAD;
      cg.first_triangle = static_cast<int64_t>(s.triangles_.size());
      cg.triangles = rg.triangle_count * (quads ? 2 : 1);
      cg.vertices = rg.vertex_count;
      for (uint32_t t = 0; t < rg.triangle_count; ++t) {
        std::array<uint32_t, 4> idx{};
        c.take(idx.data(), (quads ? 4 : 3) * sizeof(uint32_t), "indices");
        for (int k = 0; k < (quads ? 4 : 3); ++k)
          if (idx[k] >= rg.vertex_count)
            throw std::runtime_error(fmt::format(
                "{}: geometry {} {} {} names vertex {}, but the vertex buffer holds {}: Embree would read past it",
                path, rg.geom_id, quads ? "quad" : "triangle", t, idx[k], rg.vertex_count));
        const Vec3f v0 = vertices[idx[0]], v1 = vertices[idx[1]], v2 = vertices[idx[2]];
        if (!quads) {
          s.triangles_.push_back({v0, v1, v2});
          s.triangle_masks_.push_back(cg.mask);
          continue;
        }
        // Embree's split of quad (v0, v1, v2, v3): triangles (v0, v1, v3) and (v2, v3, v1).
        const Vec3f v3 = vertices[idx[3]];
        s.triangles_.push_back({v0, v1, v3});
        s.triangles_.push_back({v2, v3, v1});
        s.triangle_masks_.insert(s.triangle_masks_.end(), 2, cg.mask);
      }
      if (s.first_by_geom_.size() <= cg.geom_id) {
        s.first_by_geom_.resize(cg.geom_id + 1, -1);
        s.count_by_geom_.resize(cg.geom_id + 1, 0);
        s.quads_by_geom_.resize(cg.geom_id + 1, false);
      }
      s.first_by_geom_[cg.geom_id] = cg.first_triangle;
      s.count_by_geom_[cg.geom_id] = rg.triangle_count;
      s.quads_by_geom_[cg.geom_id] = quads;
    }
    s.geometries_.push_back(cg);
  }
  if (c.at != bytes.size()) throw std::runtime_error(fmt::format("{}: trailing bytes after the last geometry", path));
  return s;
}

TriangleHit CapturedScene::triangle_hit(uint32_t geom_id, uint32_t prim_id, float u, float v) const {
  TriangleHit h;
  if (geom_id >= first_by_geom_.size() || first_by_geom_[geom_id] < 0 || prim_id >= count_by_geom_[geom_id])
    return h;
  if (!quads_by_geom_[geom_id]) {
    h.triangle = first_by_geom_[geom_id] + prim_id;
    h.u = u, h.v = v;
  } else if (u + v <= 1.0f) {  // the first triangle (v0, v1, v3): Embree's u, v are its barycentrics
    h.triangle = first_by_geom_[geom_id] + 2 * int64_t{prim_id};
    h.u = u, h.v = v;
  } else {  // the second (v2, v3, v1): Embree reports 1 - u', 1 - v' of its barycentrics u', v'
    h.triangle = first_by_geom_[geom_id] + 2 * int64_t{prim_id} + 1;
    h.u = 1.0f - u, h.v = 1.0f - v;
  }
  return h;
}

TriangleHit CapturedScene::triangle_hit(const RawRay& r) const {
  if (r.op != static_cast<uint16_t>(RawOp::Intersect) || r.geom == kInvalidId) return {};
  if (r.inst == kInvalidId) return triangle_hit(r.geom, r.prim, r.u, r.v);
  if (r.inst >= instanced_by_geom_.size() || !instanced_by_geom_[r.inst]) return {};
  TriangleHit h = instanced_by_geom_[r.inst]->triangle_hit(r.geom, r.prim, r.u, r.v);
  if (h.triangle >= 0) h.triangle += first_by_geom_[r.inst];
  return h;
}

const char* embree_geometry_type_name(uint32_t type) {
  switch (type) {
    case 0: return "triangle";
    case 1: return "quad";
    case 2: return "grid";
    case 8: return "subdivision";
    case 50: case 51: case 52: return "point";
    case 120: return "user";
    case 121: return "instance";
    default: return type >= 15 && type <= 60 ? "curve" : "other";
  }
}

const char* raw_geometry_status_name(RawGeometryStatus status) {
  switch (status) {
    case RawGeometryStatus::Captured: return "captured";
    case RawGeometryStatus::NotTriangles: return "not triangles";
    case RawGeometryStatus::MotionBlur: return "motion blur";
    case RawGeometryStatus::MissingBuffer: return "no vertex or index buffer (an instance: no committed scene or transform)";
    case RawGeometryStatus::BadFormat: return "buffer format other than FLOAT3 / UINT3";
    case RawGeometryStatus::Disabled: return "disabled";
    case RawGeometryStatus::NestedInstance: return "instance of a scene with instances";
  }
  return "unknown";
}

std::string describe_geometries(const std::vector<CapturedGeometry>& geometries, bool all) {
  std::string s;
  for (const CapturedGeometry& g : geometries)
    if (all || g.status != RawGeometryStatus::Captured)
      s += fmt::format("{}geomID {} ({}: {})", s.empty() ? "" : ", ", g.geom_id, embree_geometry_type_name(g.type),
                       raw_geometry_status_name(g.status));
  return s.empty() ? "none" : s;
}

}  // namespace vbsim::capture
