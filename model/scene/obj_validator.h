// OBJ validation before assimp reads a file: a strict check of the Wavefront
// OBJ statements vbsim's scenes use, so that assimp only ever sees files it
// reads whole and in the meaning the file states. A line is blank, a comment
// ('#' first), or one of:
//   v X Y Z [W | R G B]   vn X Y Z   vt U V [W]
//   f R R R ...  (R = i, i/t, i//n or i/t/n, the same form throughout a face)
//   l R R ...    p R ...   o NAME   g NAME...   s off|on|N   usemtl NAME   mtllib FILE...
// Numbers are plain decimals ([+-]digits[.digits][e[+-]digits]); indices are
// non-zero integers naming an element defined before (negative: counted back
// from the last one). Anything else (other statements, NUL bytes, a line
// continued with '\', a line over 64 KiB) is an error naming the line.
// assimp reads no other file: material libraries are not opened (materials
// only name the meshes they start, which numbering keeps; docs/scene.md).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace vbsim {

struct ObjSummary {
  uint64_t vertices = 0;
  uint64_t faces = 0;      ///< `f` statements
  uint64_t triangles = 0;  ///< what the faces give after triangulation (n - 2 per face of n >= 3)
  uint64_t faces_with_normals = 0;  ///< `f` statements whose references name normals (i//n, i/t/n)
  /// Whether the file's triangles are numbered as it lists them, with nothing
  /// for assimp's OBJ importer to group, split or triangulate, so that
  /// read_plain_obj (obj_plain_reader.h) may read it: every statement is `v`
  /// with three numbers, `vn`, `vt`, `f` with three references, `s` or a
  /// comment, starting its line; no number is longer than 64 characters; and
  /// either every face names normals or none does.
  bool plain() const { return plain_statements && (faces_with_normals == 0 || every_face_names_normals()); }
  /// Whether the file's triangles carry corner normals: every face names them.
  bool every_face_names_normals() const { return faces > 0 && faces_with_normals == faces; }
  bool plain_statements = true;  ///< the statements' part of plain()
};

class WorkProgress;

/// Validates the OBJ text `bytes`; throws SceneError "scene 'PATH': OBJ line
/// N: what is wrong". `progress`, when given, sees a step "checking" in MB.
ObjSummary validate_obj(std::string_view bytes, const std::string& path, WorkProgress* progress = nullptr);

}  // namespace vbsim
