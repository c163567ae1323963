// load_scene: reads a scene file with assimp and numbers its triangles as the
// trace spec requires. Numbering contract (see docs/scene.md):
//   - triangles are numbered from 0, meshes in aiScene::mMeshes order, faces in
//     each mesh's order; assimp runs only its Triangulate step, so a polygon
//     becomes consecutive triangles in the order that step emits them;
//   - faces that are not triangles after triangulation (points, lines) are
//     skipped and take no number;
//   - vertex positions are used as the file gives them: the node hierarchy's
//     transforms are NOT applied (only the optional trace-header transform is).
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "scene/scene.h"
#include "scene/scene_transform.h"

namespace vbsim {

namespace {

// Only triangulation: no step that merges, sorts, splits or drops faces or meshes
// (JoinIdenticalVertices, SortByPType, OptimizeMeshes, FindDegenerates, ...).
constexpr unsigned kImportFlags = aiProcess_Triangulate;

Vec3f to_vec(const aiVector3D& v) { return {v.x, v.y, v.z}; }

void check_readable_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw SceneError(fmt::format("scene '{}': no such file", path));
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(fmt::format("scene '{}': not a regular file", path));
}

// True when every mesh that contributes a triangle carries per-vertex normals.
bool all_meshes_have_normals(const aiScene& ai) {
  bool any_triangle = false;
  for (unsigned m = 0; m < ai.mNumMeshes; ++m) {
    const aiMesh& mesh = *ai.mMeshes[m];
    bool has_triangle = false;
    for (unsigned f = 0; f < mesh.mNumFaces && !has_triangle; ++f) has_triangle = mesh.mFaces[f].mNumIndices == 3;
    if (!has_triangle) continue;
    any_triangle = true;
    if (!mesh.HasNormals()) return false;
  }
  return any_triangle;
}

}  // namespace

Scene load_scene(const std::string& path, const std::optional<std::array<float, 16>>& transform) {
  check_readable_file(path);
  std::optional<SceneTransform> xform;
  if (transform) xform.emplace(*transform, path);

  Assimp::Importer importer;
  // Skeleton-only files must not gain a synthetic mesh that would shift numbering.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* ai = importer.ReadFile(path, kImportFlags);
  if (ai == nullptr)
    throw SceneError(fmt::format("scene '{}': assimp could not read it: {}", path, importer.GetErrorString()));

  const bool with_normals = all_meshes_have_normals(*ai);
  if (with_normals && xform && !xform->invertible())
    throw SceneError(fmt::format("scene '{}': transform is singular, its normals cannot be transformed", path));

  Scene scene;
  scene.source = path;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh& mesh = *ai->mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // point or line: not a triangle, not numbered
      Vec3f v[3];
      std::array<Vec3f, 3> n;
      for (int k = 0; k < 3; ++k) {
        const unsigned index = face.mIndices[k];
        if (index >= mesh.mNumVertices)
          throw SceneError(fmt::format("scene '{}': mesh {} face {} refers to vertex {} of {}", path, m, f,
                                       index, mesh.mNumVertices));
        v[k] = to_vec(mesh.mVertices[index]);
        if (xform) v[k] = xform->point(v[k]);
        if (!is_finite(v[k]))
          throw SceneError(fmt::format(
              "scene '{}': mesh {} face {} (triangle {}) has a non-finite vertex ({}, {}, {}){}", path, m, f,
              scene.triangles.size(), v[k].x, v[k].y, v[k].z, xform ? " after the transform" : ""));
        if (with_normals) {
          n[k] = to_vec(mesh.mNormals[index]);
          if (xform) n[k] = xform->normal(n[k]);
        }
      }
      scene.triangles.push_back({v[0], v[1], v[2]});
      if (with_normals) scene.normals.push_back(n);
      for (const Vec3f& p : v) scene.bounds.extend(p);
    }
  }
  if (scene.triangles.empty()) throw SceneError(fmt::format("scene '{}': contains no triangles", path));
  return scene;
}

}  // namespace vbsim
