#include "scene/ply_scene_writer.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

#include "io/atomic_output_file.h"

#include "scene/scene.h"

namespace vbsim {

namespace {

/// Appends the little-endian bytes of `value` (the build targets little-endian hosts).
template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

void put_vec(std::string& out, Vec3f v) {
  put(out, v.x);
  put(out, v.y);
  put(out, v.z);
}

// assimp skips white space right after end_header even in a binary file, so a
// first vertex coordinate whose low byte is 0x0a (say) would be misread; every
// vertex therefore starts with a `guard` byte that is not white space.
constexpr uint8_t kGuardByte = 'G';

}  // namespace

std::string ply_scene_bytes(const std::string& path, const std::vector<Triangle>& triangles,
                            const std::vector<std::array<Vec3f, 3>>& normals, const std::string& comment) {
  const bool with_normals = !normals.empty();
  if (with_normals && normals.size() != triangles.size())
    throw SceneError(fmt::format("{}: {} normal triples for {} triangles", path, normals.size(),
                                 triangles.size()));
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment written by vbsim: 3 vertices per triangle, "
      "in triangle order\nelement vertex {}\nproperty uchar guard\nproperty float x\nproperty float y\nproperty float z\n",
      3 * triangles.size());
  if (comment.find_first_of("\r\n") != std::string::npos)
    throw SceneError(fmt::format("{}: a PLY comment must be one line", path));
  if (!comment.empty()) out.insert(out.find("element vertex"), "comment " + comment + "\n");
  if (with_normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
  out += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                     triangles.size());
  for (size_t k = 0; k < triangles.size(); ++k) {
    const Triangle& t = triangles[k];
    const Vec3f corners[3] = {t.v0, t.v1, t.v2};
    for (int c = 0; c < 3; ++c) {
      put(out, kGuardByte);
      put_vec(out, corners[c]);
      if (with_normals) put_vec(out, normals[k][c]);
    }
  }
  for (size_t k = 0; k < triangles.size(); ++k) {
    put(out, static_cast<uint8_t>(3));
    for (int c = 0; c < 3; ++c) put(out, static_cast<int32_t>(3 * k + c));
  }
  return out;
}

void write_ply_scene(const std::string& path, const std::vector<Triangle>& triangles,
                     const std::vector<std::array<Vec3f, 3>>& normals, const std::string& comment) {
  const std::string out = ply_scene_bytes(path, triangles, normals, comment);
  try {
    AtomicOutputFile file(path, true);
    file.stream().write(out.data(), static_cast<std::streamsize>(out.size()));
    file.commit();
  } catch (const OutputError& e) {
    throw SceneError(fmt::format("{}: cannot write the scene file: {}", path, e.message));
  }
}

}  // namespace vbsim
