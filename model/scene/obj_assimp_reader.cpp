#include "scene/obj_assimp_reader.h"

#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "scene/scene_builder.h"

namespace vbsim {

namespace {

// Only triangulation: no step that merges, sorts, splits or drops faces or meshes
// (JoinIdenticalVertices, SortByPType, OptimizeMeshes, FindDegenerates, ...).
constexpr unsigned kImportFlags = aiProcess_Triangulate;

Vec3f to_vec(const aiVector3D& v) { return {v.x, v.y, v.z}; }

/// assimp's file system while it reads one OBJ: that file's validated bytes, and nothing else.
class SingleFileIOSystem final : public Assimp::IOSystem {
 public:
  SingleFileIOSystem(std::string name, const std::string& bytes) : name_(std::move(name)), bytes_(bytes) {}
  bool Exists(const char* file) const override { return file && name_ == file; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!file || name_ != file || !mode || mode[0] != 'r') return nullptr;
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes_.data()), bytes_.size());
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string name_;
  const std::string& bytes_;
};

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

Scene read_obj_with_assimp(const std::string& bytes, const std::string& path, const ObjSummary& summary,
                           const std::optional<std::array<float, 16>>& transform) {
  Assimp::Importer importer;
  // Skeleton-only files must not gain a synthetic mesh that would shift numbering.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  importer.SetIOHandler(new SingleFileIOSystem(path, bytes));  // the importer owns it
  const aiScene* ai = importer.ReadFile(path, kImportFlags);
  if (ai == nullptr)
    throw SceneError(fmt::format("scene '{}': assimp could not read it: {}", path, importer.GetErrorString()));

  const bool with_normals = all_meshes_have_normals(*ai);
  SceneBuilder builder(path, transform, with_normals);
  builder.reserve(summary.triangles);
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh& mesh = *ai->mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // point or line: not a triangle, not numbered
      Vec3f v[3], n[3];
      for (int k = 0; k < 3; ++k) {
        const unsigned index = face.mIndices[k];
        if (index >= mesh.mNumVertices)
          throw SceneError(fmt::format("scene '{}': mesh {} face {} refers to vertex {} of {}", path, m, f, index,
                                       mesh.mNumVertices));
        v[k] = to_vec(mesh.mVertices[index]);
        if (with_normals) n[k] = to_vec(mesh.mNormals[index]);
      }
      builder.add(v, n, static_cast<int>(m), f);
    }
  }
  Scene scene = builder.finish();
  if (static_cast<uint64_t>(scene.size()) != summary.triangles)
    throw SceneError(fmt::format("scene '{}': assimp read {} triangles where the file's faces give {}; refusing a "
                                 "scene read in part",
                                 path, scene.size(), summary.triangles));
  return scene;
}

}  // namespace vbsim
