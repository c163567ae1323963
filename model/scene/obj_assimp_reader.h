// read_obj_with_assimp: reads a validated OBJ file with assimp's importer (only
// its Triangulate step), from the validated bytes and with no access to any
// other file, and numbers the triangles as docs/scene.md says: meshes in
// aiScene::mMeshes order, faces in each mesh's order, a polygon as the
// consecutive triangles Triangulate emits. The path for every OBJ file that
// is not plain (ObjSummary::plain); a plain one may take it too, and gives the
// scene read_plain_obj gives.
#pragma once
#include <array>
#include <optional>
#include <string>

#include "scene/obj_validator.h"
#include "scene/scene.h"

namespace vbsim {

/// Precondition: `summary` is validate_obj(bytes, path). SceneError when
/// assimp refuses the file or reads another triangle count than the summary's.
Scene read_obj_with_assimp(const std::string& bytes, const std::string& path, const ObjSummary& summary,
                           const std::optional<std::array<float, 16>>& transform);

}  // namespace vbsim
