// load_scene: reads a scene file and numbers its triangles as the trace spec
// requires. No file reaches a parser unchecked (docs/scene.md, docs/reliability.md):
//   - PLY (by its "ply" magic line, or a .ply name) is read by vbsim's own
//     reader (ply_reader.h), never by assimp;
//   - OBJ (a .obj name) is validated first (obj_validator.h); a plain file
//     (triangles only, nothing to group: ObjSummary::plain) is then read by
//     obj_plain_reader.h, which gives what assimp gives at a fraction of the
//     memory; any other by assimp from the validated bytes, with no access to
//     any other file, and assimp's triangle count must equal the validator's;
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

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

#include <fmt/format.h>

#include "progress/work_progress.h"
#include "scene/obj_assimp_reader.h"
#include "scene/obj_plain_reader.h"
#include "scene/obj_validator.h"
#include "scene/ply_header.h"
#include "scene/ply_reader.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace vbsim {

namespace {

/// Largest scene file read (its bytes are held while it is parsed).
constexpr uintmax_t kMaxSceneBytes = uintmax_t{4} << 30;

/// Bytes read at a time, so that a large file's reading shows its progress.
constexpr size_t kReadChunkBytes = size_t{32} << 20;

/// The file's bytes; SceneError when it is missing, not a regular file or too large.
std::string read_scene_bytes(const std::string& path, WorkProgress* progress) {
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
  if (progress) progress->begin("reading", megabytes(size), "MB");
  for (size_t at = 0; at < bytes.size(); at += kReadChunkBytes) {
    const size_t n = std::min(kReadChunkBytes, bytes.size() - at);
    if (!in || !in.read(bytes.data() + at, static_cast<std::streamsize>(n)))
      throw SceneError(fmt::format("scene '{}': cannot read it", path));
    if (progress) progress->update(megabytes(at + n));
  }
  if (!in) throw SceneError(fmt::format("scene '{}': cannot read it", path));
  return bytes;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

Scene load_ply(const std::string& bytes, const std::string& path,
               const std::optional<std::array<float, 16>>& transform, WorkProgress* progress) {
  if (progress) progress->begin("reading PLY", 0, "");
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

Scene load_obj(const std::string& bytes, const std::string& path,
               const std::optional<std::array<float, 16>>& transform, WorkProgress* progress) {
  const ObjSummary summary = validate_obj(bytes, path, progress);
  if (summary.plain()) return read_plain_obj(bytes, path, summary, transform, progress);
  if (progress) progress->begin("reading with assimp", 0, "");
  return read_obj_with_assimp(bytes, path, summary, transform);
}

}  // namespace

Scene load_scene(const std::string& path, const std::optional<std::array<float, 16>>& transform,
                 WorkProgress* progress) {
  const std::string bytes = read_scene_bytes(path, progress);
  const std::string ext = lower_extension(path);
  if (has_ply_magic(bytes) || ext == ".ply") return load_ply(bytes, path, transform, progress);
  if (ext == ".obj") return load_obj(bytes, path, transform, progress);
  throw SceneError(fmt::format("scene '{}': unsupported format '{}': vbsim reads PLY and OBJ scenes (docs/scene.md)",
                               path, ext.empty() ? "(no extension)" : ext));
}

}  // namespace vbsim
