// Binary PLY scene writer: the form vbsim's generators write scenes in, because
// float32 values round-trip through it bit for bit (a decimal OBJ does not:
// assimp's OBJ reader misrounds some decimals, docs/scene.md).
//
// Layout: binary_little_endian 1.0; one `vertex` element per triangle corner
// (uchar guard = 'G', float x y z, and float nx ny nz when normals are given;
// the guard keeps the first data byte from being white space, which assimp
// would skip), three per triangle
// in triangle order; one `face` element per triangle (uchar count = 3, int
// indices 3k, 3k+1, 3k+2). Loading it gives triangle k = the k-th triangle
// written, with the same vertices and normals.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "datapath/triangle.h"

namespace vbsim {

/// Writes `triangles` (and per-corner `normals`, empty or one per triangle) to
/// `path`, with `comment` (one line, may be empty) as a header comment. Throws
/// SceneError naming the file when it cannot be written or the normals do not
/// match the triangles.
void write_ply_scene(const std::string& path, const std::vector<Triangle>& triangles,
                     const std::vector<std::array<Vec3f, 3>>& normals = {}, const std::string& comment = "");

/// The bytes write_ply_scene writes, for a caller that writes the file itself
/// (`path` only names it in errors). Throws SceneError as write_ply_scene does.
std::string ply_scene_bytes(const std::string& path, const std::vector<Triangle>& triangles,
                            const std::vector<std::array<Vec3f, 3>>& normals = {}, const std::string& comment = "");

}  // namespace vbsim
