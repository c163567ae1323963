#include "datapath/closed_meshes.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace vbsim {

namespace {

struct Vec3d {
  double x, y, z;
};
Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d cross(Vec3d a, Vec3d b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d on_unit_sphere(Vec3d a) {
  const double inv = 1.0 / std::sqrt(dot(a, a));
  return {a.x * inv, a.y * inv, a.z * inv};
}

using Face = std::array<int, 3>;

/// Rounds each vertex once and emits the faces as float triangles.
std::vector<Triangle> to_triangles(const std::vector<Vec3d>& vertices,
                                   const std::vector<Face>& faces, const MeshPlacement& place) {
  std::vector<Vec3f> rounded;
  rounded.reserve(vertices.size());
  for (const Vec3d& p : vertices) {
    rounded.push_back({static_cast<float>(place.scale * p.x + place.tx),
                       static_cast<float>(place.scale * p.y + place.ty),
                       static_cast<float>(place.scale * p.z + place.tz)});
  }
  std::vector<Triangle> out;
  out.reserve(faces.size());
  for (const Face& f : faces) out.push_back({rounded[f[0]], rounded[f[1]], rounded[f[2]]});
  return out;
}

}  // namespace

std::vector<Triangle> make_icosphere(int subdivisions, const MeshPlacement& placement) {
  if (subdivisions < 0 || subdivisions > 6)
    throw std::invalid_argument("make_icosphere: subdivisions must be in 0..6");
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;  // golden ratio
  std::vector<Vec3d> vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                 {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                 {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3d& p : vertices) p = on_unit_sphere(p);
  std::vector<Face> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  // Outward winding: the centre of the solid is the origin.
  for (Face& f : faces) {
    const Vec3d n = cross(vertices[f[1]] - vertices[f[0]], vertices[f[2]] - vertices[f[0]]);
    if (dot(n, vertices[f[0]]) < 0.0) std::swap(f[1], f[2]);
  }

  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint_of;
    auto midpoint = [&](int i, int j) {
      const std::pair<int, int> key{std::min(i, j), std::max(i, j)};
      auto found = midpoint_of.find(key);
      if (found != midpoint_of.end()) return found->second;
      const Vec3d a = vertices[i], b = vertices[j];
      vertices.push_back(on_unit_sphere({a.x + b.x, a.y + b.y, a.z + b.z}));
      const int index = static_cast<int>(vertices.size()) - 1;
      midpoint_of.emplace(key, index);
      return index;
    };
    std::vector<Face> finer;
    finer.reserve(faces.size() * 4);
    for (const Face& f : faces) {
      const int ab = midpoint(f[0], f[1]);
      const int bc = midpoint(f[1], f[2]);
      const int ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  return to_triangles(vertices, faces, placement);
}

std::vector<Triangle> make_tessellated_box(int cells, const MeshPlacement& placement) {
  if (cells < 1 || cells > 1024)
    throw std::invalid_argument("make_tessellated_box: cells must be in 1..1024");
  // Vertices are the lattice points (i, j, k) in 0..cells that lie on the surface.
  std::map<std::array<int, 3>, int> index_of;
  std::vector<Vec3d> vertices;
  auto vertex = [&](std::array<int, 3> lattice) {
    auto found = index_of.find(lattice);
    if (found != index_of.end()) return found->second;
    const auto coordinate = [cells](int i) { return -1.0 + 2.0 * i / cells; };
    vertices.push_back({coordinate(lattice[0]), coordinate(lattice[1]), coordinate(lattice[2])});
    const int index = static_cast<int>(vertices.size()) - 1;
    index_of.emplace(lattice, index);
    return index;
  };

  std::vector<Face> faces;
  for (int axis = 0; axis < 3; ++axis) {
    // (axis, u, v) is a cyclic order, so e_u x e_v = +e_axis.
    const int u_axis = (axis + 1) % 3;
    const int v_axis = (axis + 2) % 3;
    for (int side = 0; side <= cells; side += cells) {
      const bool outward_is_plus = side == cells;
      for (int p = 0; p < cells; ++p) {
        for (int q = 0; q < cells; ++q) {
          auto corner = [&](int du, int dv) {
            std::array<int, 3> lattice{};
            lattice[axis] = side;
            lattice[u_axis] = p + du;
            lattice[v_axis] = q + dv;
            return vertex(lattice);
          };
          const int c00 = corner(0, 0), c10 = corner(1, 0), c11 = corner(1, 1),
                    c01 = corner(0, 1);
          // Counter-clockwise in (u, v) is the +axis side.
          Face first, second;
          if ((p + q) % 2 == 0) {
            first = {c00, c10, c11};
            second = {c00, c11, c01};
          } else {
            first = {c00, c10, c01};
            second = {c10, c11, c01};
          }
          if (!outward_is_plus) {
            std::swap(first[1], first[2]);
            std::swap(second[1], second[2]);
          }
          faces.push_back(first);
          faces.push_back(second);
        }
      }
    }
  }
  return to_triangles(vertices, faces, placement);
}

}  // namespace vbsim
