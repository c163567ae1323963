#include "gen/mesh_shapes.h"

#include <cmath>

namespace vbsim {

namespace {

Vec3f unit_f(double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  return {static_cast<float>(x / n), static_cast<float>(y / n), static_cast<float>(z / n)};
}

void add_triangle(Mesh& m, Vec3f a, Vec3f b, Vec3f c, Vec3f na, Vec3f nb, Vec3f nc) {
  m.triangles.push_back({a, b, c});
  m.normals.push_back({na, nb, nc});
}

}  // namespace

void Mesh::append(const Mesh& other) {
  triangles.insert(triangles.end(), other.triangles.begin(), other.triangles.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
}

Mesh uv_sphere(Vec3f center, double radius, int segments, int rings) {
  // grid[i][j]: ring i (0 = south pole .. rings = north pole), segment j.
  std::vector<std::vector<Vec3f>> pos(rings + 1), nrm(rings + 1);
  for (int i = 0; i <= rings; ++i) {
    const double theta = M_PI * i / rings - M_PI / 2;  // latitude
    const int count = (i == 0 || i == rings) ? 1 : segments;
    for (int j = 0; j < count; ++j) {
      const double phi = 2 * M_PI * j / segments;
      double x = std::cos(theta) * std::cos(phi), y = std::cos(theta) * std::sin(phi), z = std::sin(theta);
      if (count == 1) x = y = 0, z = i == 0 ? -1 : 1;
      pos[i].push_back({static_cast<float>(center.x + radius * x), static_cast<float>(center.y + radius * y),
                        static_cast<float>(center.z + radius * z)});
      nrm[i].push_back(unit_f(x, y, z));
    }
  }
  auto at = [&](int i, int j, bool normal) {
    const auto& g = normal ? nrm[i] : pos[i];
    return g.size() == 1 ? g[0] : g[j % segments];
  };
  Mesh m;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      // Quad between rings i and i+1, counter-clockwise seen from outside.
      const int a[4][2] = {{i, j}, {i, j + 1}, {i + 1, j + 1}, {i + 1, j}};
      if (i > 0)  // below: a, b, c
        add_triangle(m, at(a[0][0], a[0][1], false), at(a[1][0], a[1][1], false), at(a[2][0], a[2][1], false),
                     at(a[0][0], a[0][1], true), at(a[1][0], a[1][1], true), at(a[2][0], a[2][1], true));
      if (i < rings - 1)  // above: a, c, d
        add_triangle(m, at(a[0][0], a[0][1], false), at(a[2][0], a[2][1], false), at(a[3][0], a[3][1], false),
                     at(a[0][0], a[0][1], true), at(a[2][0], a[2][1], true), at(a[3][0], a[3][1], true));
    }
  return m;
}

Mesh quad_mesh(Vec3f corner, Vec3f e1, Vec3f e2) {
  const Vec3f c = cross(e1, e2);
  const Vec3f n = unit_f(c.x, c.y, c.z);
  const Vec3f p1 = corner + e1, p2 = corner + e1 + e2, p3 = corner + e2;
  Mesh m;
  add_triangle(m, corner, p1, p2, n, n, n);
  add_triangle(m, corner, p2, p3, n, n, n);
  return m;
}

Mesh box_mesh(Vec3f lo, Vec3f hi) {
  // The eight corners, bit i of the index selecting hi on axis i.
  Vec3f c[8];
  for (int k = 0; k < 8; ++k) c[k] = {(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
  // Faces as corner quads, counter-clockwise seen from outside, with their normals.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  const Vec3f normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  Mesh m;
  for (int f = 0; f < 6; ++f) {
    const Vec3f n = normals[f];
    const int* q = faces[f];
    add_triangle(m, c[q[0]], c[q[1]], c[q[2]], n, n, n);
    add_triangle(m, c[q[0]], c[q[2]], c[q[3]], n, n, n);
  }
  return m;
}

}  // namespace vbsim
