#include "scene/scene_builder.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace vbsim {

SceneBuilder::SceneBuilder(const std::string& path, const std::optional<std::array<float, 16>>& transform,
                           bool with_normals)
    : path_(path), with_normals_(with_normals) {
  scene_.source = path;
  if (transform) xform_.emplace(*transform, path);
  if (with_normals && xform_ && !xform_->invertible())
    throw SceneError(fmt::format("scene '{}': transform is singular, its normals cannot be transformed", path));
}

void SceneBuilder::reserve(size_t triangles) {
  scene_.triangles.reserve(triangles);
  if (with_normals_) scene_.normals.reserve(triangles);
}

void SceneBuilder::add(Vec3f v[3], Vec3f n[3], int mesh, size_t face) {
  const auto where = [&] {
    return mesh == -1   ? std::string("a PLY face")
           : mesh == -2 ? fmt::format("the face of OBJ line {}", face)
                        : fmt::format("mesh {} face {}", mesh, face);
  };
  const size_t number = scene_.triangles.size();
  if (number >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    throw SceneError(fmt::format("scene '{}': more than {} triangles", path_, std::numeric_limits<int32_t>::max()));
  std::array<Vec3f, 3> corner_normals;
  for (int k = 0; k < 3; ++k) {
    if (xform_) v[k] = xform_->point(v[k]);
    if (!is_finite(v[k]))
      throw SceneError(fmt::format("scene '{}': {} (triangle {}) has a non-finite vertex ({}, {}, {}){}", path_,
                                   where(), number, v[k].x, v[k].y, v[k].z, xform_ ? " after the transform" : ""));
    if (!(std::fabs(v[k].x) <= kMaxSceneCoordinate && std::fabs(v[k].y) <= kMaxSceneCoordinate &&
          std::fabs(v[k].z) <= kMaxSceneCoordinate))
      throw SceneError(fmt::format("scene '{}': {} (triangle {}) has the vertex ({}, {}, {}){}, beyond the "
                                   "supported coordinate range of +-2^126 (about 8.5e37; docs/scene.md)",
                                   path_, where(), number, v[k].x, v[k].y, v[k].z,
                                   xform_ ? " after the transform" : ""));
    if (with_normals_) {
      corner_normals[k] = xform_ ? xform_->normal(n[k]) : n[k];
      if (!is_finite(corner_normals[k]))
        throw SceneError(fmt::format("scene '{}': {} (triangle {}) has a non-finite normal ({}, {}, {}){}", path_,
                                     where(), number, corner_normals[k].x, corner_normals[k].y, corner_normals[k].z,
                                     xform_ ? " after the transform" : ""));
    }
  }
  scene_.triangles.push_back({v[0], v[1], v[2]});
  if (with_normals_) scene_.normals.push_back(corner_normals);
  for (int k = 0; k < 3; ++k) scene_.bounds.extend(v[k]);
}

Scene SceneBuilder::finish() {
  if (scene_.triangles.empty()) throw SceneError(fmt::format("scene '{}': contains no triangles", path_));
  return std::move(scene_);
}

}  // namespace vbsim
