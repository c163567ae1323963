// SceneBuilder: gathers a scene's triangles one at a time, in their numbering
// order, as every scene reader hands them over: it applies the trace's
// transform (points, and normals by its inverse transpose), refuses
// non-finite values and coordinates beyond kMaxSceneCoordinate, and keeps the
// bounds. Shared by the PLY reader, the plain OBJ reader and the assimp path.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "scene/scene.h"
#include "scene/scene_transform.h"

namespace vbsim {

class SceneBuilder {
 public:
  /// `with_normals`: every triangle comes with three corner normals.
  /// SceneError when the transform is singular and normals must be transformed.
  SceneBuilder(const std::string& path, const std::optional<std::array<float, 16>>& transform, bool with_normals);

  /// Adds triangle `v` (and its corner normals `n` when the scene has normals).
  /// `mesh` and `face` name the face in messages (mesh -1: a PLY face; -2: an
  /// OBJ face, `face` its line). SceneError names the file and the face.
  void add(Vec3f v[3], Vec3f n[3], int mesh, size_t face);

  /// Triangles to come, when known: reserves their room once.
  void reserve(size_t triangles);

  /// The scene; SceneError when it has no triangle.
  Scene finish();

 private:
  const std::string& path_;
  bool with_normals_;
  std::optional<SceneTransform> xform_;
  Scene scene_;
};

}  // namespace vbsim
