// load_scene: reads a scene file and numbers its triangles as the trace spec
// requires. No file reaches a parser unchecked (docs/scene.md, docs/reliability.md):
//   - PLY (by its "ply" magic line, or a .ply name) is read by vbsim's own
//     reader (ply_reader.h), never by assimp;
//   - OBJ (a .obj name) is validated first (obj_validator.h), then read by
//     assimp from the validated bytes, with no access to any other file, and
//     assimp's triangle count must equal the validator's;
//   - any other format is refused.
// Numbering contract (see docs/scene.md):
//   - triangles are numbered from 0, meshes in aiScene::mMeshes order, faces in
//     each mesh's order; assimp runs only its Triangulate step, so a polygon
//     becomes consecutive triangles in the order that step emits them;
//   - faces that are not triangles after triangulation (points, lines) are
//     skipped and take no number;
//   - vertex positions are used as the file gives them: the node hierarchy's
//     transforms are NOT applied (only the optional trace-header transform is).
#include <cmath>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

#include <fmt/format.h>

#include "scene/obj_validator.h"
#include "scene/ply_header.h"
#include "scene/ply_reader.h"
#include "scene/scene.h"
#include "scene/scene_transform.h"

namespace vbsim {

namespace {

// Only triangulation: no step that merges, sorts, splits or drops faces or meshes
// (JoinIdenticalVertices, SortByPType, OptimizeMeshes, FindDegenerates, ...).
constexpr unsigned kImportFlags = aiProcess_Triangulate;

/// Largest scene file read (its bytes are held while it is parsed).
constexpr uintmax_t kMaxSceneBytes = uintmax_t{4} << 30;

Vec3f to_vec(const aiVector3D& v) { return {v.x, v.y, v.z}; }

/// The file's bytes; SceneError when it is missing, not a regular file or too large.
std::string read_scene_bytes(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw SceneError(fmt::format("scene '{}': no such file", path));
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(fmt::format("scene '{}': not a regular file", path));
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxSceneBytes)
    throw SceneError(fmt::format("scene '{}': larger than {} bytes", path, kMaxSceneBytes));
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<size_t>(size), '\0');
  if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw SceneError(fmt::format("scene '{}': cannot read it", path));
  return bytes;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

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

/// Adds triangle `v` (and its corner normals `n` when the scene has normals)
/// after the transform, refusing non-finite values.
class SceneBuilder {
 public:
  SceneBuilder(const std::string& path, const std::optional<std::array<float, 16>>& transform, bool with_normals)
      : path_(path), with_normals_(with_normals) {
    scene_.source = path;
    if (transform) xform_.emplace(*transform, path);
    if (with_normals && xform_ && !xform_->invertible())
      throw SceneError(fmt::format("scene '{}': transform is singular, its normals cannot be transformed", path));
  }

  /// `mesh` and `face` name the face for messages (mesh -1: a PLY face).
  void add(Vec3f v[3], Vec3f n[3], int mesh, size_t face) {
    const auto where = [&] { return mesh < 0 ? std::string("a PLY face") : fmt::format("mesh {} face {}", mesh, face); };
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

  Scene finish() {
    if (scene_.triangles.empty()) throw SceneError(fmt::format("scene '{}': contains no triangles", path_));
    return std::move(scene_);
  }

 private:
  const std::string& path_;
  bool with_normals_;
  std::optional<SceneTransform> xform_;
  Scene scene_;
};

Scene load_ply(const std::string& bytes, const std::string& path,
               const std::optional<std::array<float, 16>>& transform) {
  const PlyMesh mesh = read_ply_mesh(bytes, path);
  SceneBuilder builder(path, transform, !mesh.normals.empty() && !mesh.triangles.empty());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    Vec3f v[3], n[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = mesh.positions[mesh.triangles[f][k]];
      if (!mesh.normals.empty()) n[k] = mesh.normals[mesh.triangles[f][k]];
    }
    builder.add(v, n, -1, f);
  }
  return builder.finish();
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

Scene load_obj(const std::string& bytes, const std::string& path,
               const std::optional<std::array<float, 16>>& transform) {
  const ObjSummary summary = validate_obj(bytes, path);
  Assimp::Importer importer;
  // Skeleton-only files must not gain a synthetic mesh that would shift numbering.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  importer.SetIOHandler(new SingleFileIOSystem(path, bytes));  // the importer owns it
  const aiScene* ai = importer.ReadFile(path, kImportFlags);
  if (ai == nullptr)
    throw SceneError(fmt::format("scene '{}': assimp could not read it: {}", path, importer.GetErrorString()));

  SceneBuilder builder(path, transform, all_meshes_have_normals(*ai));
  const bool with_normals = all_meshes_have_normals(*ai);
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

}  // namespace

Scene load_scene(const std::string& path, const std::optional<std::array<float, 16>>& transform) {
  const std::string bytes = read_scene_bytes(path);
  const std::string ext = lower_extension(path);
  if (has_ply_magic(bytes) || ext == ".ply") return load_ply(bytes, path, transform);
  if (ext == ".obj") return load_obj(bytes, path, transform);
  throw SceneError(fmt::format("scene '{}': unsupported format '{}': vbsim reads PLY and OBJ scenes (docs/scene.md)",
                               path, ext.empty() ? "(no extension)" : ext));
}

}  // namespace vbsim
