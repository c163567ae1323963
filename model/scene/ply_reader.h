// vbsim's own PLY reader: every PLY scene is read here, not by assimp, so that
// no PLY file can crash or hang a run or be half-read. It reads what the
// polygon file format defines (ascii and both binary forms, any element
// order, any scalar type) and checks everything before it is used:
//   - the header (ply_header.h), and every element count against the bytes
//     the file has left, before anything is allocated;
//   - every value: integers within their type, list counts >= 0, face indices
//     naming a vertex of the file, ascii tokens that are whole numbers;
//   - the end: the file must end exactly after the last element (ascii:
//     white space may follow), so a truncated or padded file is an error.
// Elements other than `vertex` and `face` are read over and ignored, except
// `tristrips`, which is refused (its triangles would be left out).
//
// Numbering: a face of three vertices is one triangle; a quad is split along
// the diagonal from its reflex vertex when it has one (a concave quad), else
// from its first vertex: a b c d gives a b c, a c d, as assimp does for a
// convex quad; a face of more than four vertices is fanned from its first
// vertex (assumed convex); faces of fewer than three vertices are points or
// lines, skipped without a number (docs/scene.md).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "datapath/vec3.h"

namespace vbsim {

struct PlyMesh {
  std::vector<Vec3f> positions;                  ///< x y z of every vertex, rounded to float32
  std::vector<Vec3f> normals;                    ///< nx ny nz per vertex, or empty when the file has none
  std::vector<std::array<uint32_t, 3>> triangles;  ///< vertex indices, in the numbering above
};

/// Reads the PLY file whose bytes are `bytes`. Throws SceneError
/// "scene 'PATH': PLY ...: what is wrong, and where".
PlyMesh read_ply_mesh(std::string_view bytes, const std::string& path);

}  // namespace vbsim
