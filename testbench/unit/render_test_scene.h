// The tiny render test scene: a ground quad on the tilted plane
// y = 0.3 + 0.1 x - 0.2 z (corners at x, z = +-2; no vertex of it or point on
// it is exactly representable in general, so float32 hit points round above
// or below the plane) and a 1 x 1 occluder quad 0.8 above the plane's centre
// region, under a directional light. Triangles 0-1: ground; 2-3: occluder.
// No shading normals. Shared by the renderer's unit tests and the command's
// system tests (which write it as an OBJ file).
#pragma once
#include <fstream>
#include <string>
#include <vector>

#include "datapath/triangle.h"

namespace vbsim::test {

inline float ground_y(float x, float z) { return 0.3f + 0.1f * x - 0.2f * z; }

inline std::vector<Vec3f> render_test_vertices() {
  const auto g = [](float x, float z) { return Vec3f{x, ground_y(x, z), z}; };
  const auto q = [](float x, float z) { return Vec3f{x, ground_y(x, z) + 0.8f, z}; };
  return {g(-2, -2), g(2, -2), g(2, 2), g(-2, 2), q(-0.5f, -0.5f), q(0.5f, -0.5f), q(0.5f, 0.5f), q(-0.5f, 0.5f)};
}

/// Vertex indices of the four triangles, counter-clockwise seen from above
/// (Ng points up, +y).
inline const int kRenderTestFaces[4][3] = {{0, 3, 2}, {0, 2, 1}, {4, 7, 6}, {4, 6, 5}};

inline std::vector<Triangle> render_test_triangles() {
  const std::vector<Vec3f> v = render_test_vertices();
  std::vector<Triangle> tris;
  for (const auto& f : kRenderTestFaces) tris.push_back({v[f[0]], v[f[1]], v[f[2]]});
  return tris;
}

/// The scene as an OBJ file (positions with 9 significant digits: exact float32).
inline void write_render_test_obj(const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const Vec3f& p : render_test_vertices()) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const auto& f : kRenderTestFaces) out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
}

/// The light of the test renders: directional, from above and behind, so that the
/// occluder's shadow falls towards the camera.
constexpr const char* kRenderTestLight = "dir:-0.5,1,-0.6";

}  // namespace vbsim::test
