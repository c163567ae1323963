// read_plain_obj: reads an OBJ file whose triangles need nothing of assimp's
// importer (ObjSummary::plain: vertices, normals, texture coordinates and
// three-vertex faces, nothing to group or triangulate) straight into a Scene,
// in one pass over the bytes, holding only the vertex arrays besides the
// scene: assimp's importer keeps a face object per face and an aiScene copy of
// every corner, some 200 bytes a triangle more at its peak (docs/scene.md).
// The result is the scene assimp's path gives, bit for bit: triangles in file
// order, each number read by assimp's own conversion (fast_atof, the one its
// OBJ parser calls), corner normals only when every face names them
// (scene_loader_test.cpp holds both paths against each other).
#pragma once
#include <array>
#include <optional>
#include <string>

#include "scene/obj_validator.h"
#include "scene/scene.h"

namespace vbsim {

class WorkProgress;

/// Precondition: `summary` is validate_obj(bytes, path) and summary.plain().
/// `transform` as load_scene's. SceneError names the file and line.
/// `progress`, when given, sees a step "reading triangles" in MB.
Scene read_plain_obj(const std::string& bytes, const std::string& path, const ObjSummary& summary,
                     const std::optional<std::array<float, 16>>& transform, WorkProgress* progress = nullptr);

}  // namespace vbsim
