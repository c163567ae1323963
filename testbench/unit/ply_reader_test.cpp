// vbsim's own PLY reader: the malformed files that crashed, hung or were half
// read by assimp (each now a clear SceneError, found at once), the formats and
// layouts PLY allows, polygon numbering, and a cross-check against assimp on
// valid files, which both must read to the same triangles bit for bit.
#include <catch2/catch.hpp>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gen/seeded_random.h"
#include "scene/ply_reader.h"
#include "scene/ply_scene_writer.h"
#include "scene/scene.h"

using namespace vbsim;

namespace {

std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vbsim_ply_reader_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string write_bytes(const std::string& name, const std::string& bytes) {
  const std::string path = scratch(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The error load_scene throws for `bytes` as a .ply file, and how long it took.
std::string load_error(const std::string& bytes, double* seconds = nullptr) {
  const std::string path = write_bytes("case.ply", bytes);
  const auto start = std::chrono::steady_clock::now();
  std::string message = "(loaded)";
  try {
    load_scene(path);
  } catch (const SceneError& e) {
    message = e.what();
  }
  if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::filesystem::remove(path);
  return message;
}

/// A closed box of 12 triangles with corner normals, as `vbsim gen refraction` writes one.
std::string box_ply_bytes() {
  const float s = 1.0f;
  const Vec3f p[8] = {{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}, {-s, -s, s}, {s, -s, s}, {s, s, s}, {-s, s, s}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  std::vector<Triangle> tris;
  std::vector<std::array<Vec3f, 3>> normals;
  for (const auto& q : quads) {
    const Vec3f n = normalize(cross(p[q[1]] - p[q[0]], p[q[2]] - p[q[0]]));
    tris.push_back({p[q[0]], p[q[1]], p[q[2]]});
    tris.push_back({p[q[0]], p[q[2]], p[q[3]]});
    normals.push_back({n, n, n});
    normals.push_back({n, n, n});
  }
  const std::string path = scratch("box.ply");
  write_ply_scene(path, tris, normals);
  const std::string bytes = read_bytes(path);
  std::filesystem::remove(path);
  return bytes;
}

std::vector<Triangle> assimp_triangles(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile(path, aiProcess_Triangulate);
  REQUIRE(ai != nullptr);
  std::vector<Triangle> out;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m)
    for (unsigned f = 0; f < ai->mMeshes[m]->mNumFaces; ++f) {
      const aiFace& face = ai->mMeshes[m]->mFaces[f];
      if (face.mNumIndices != 3) continue;
      const aiVector3D* v = ai->mMeshes[m]->mVertices;
      out.push_back({{v[face.mIndices[0]].x, v[face.mIndices[0]].y, v[face.mIndices[0]].z},
                     {v[face.mIndices[1]].x, v[face.mIndices[1]].y, v[face.mIndices[1]].z},
                     {v[face.mIndices[2]].x, v[face.mIndices[2]].y, v[face.mIndices[2]].z}});
    }
  return out;
}

bool same_bits(const Triangle& a, const Triangle& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

const char* kAsciiHeader = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";

}  // namespace

TEST_CASE("PLY: the malformed files that broke assimp are clear errors", "[scene][ply]") {
  SECTION("20 bytes: 'ply', a cut format line and two NUL bytes") {
    const std::string bytes = std::string("ply\nformat binary_") + std::string(2, '\0');
    CHECK_THAT(load_error(bytes), Catch::Contains("case.ply") && Catch::Contains("header"));
  }
  const std::string box = box_ply_bytes();
  const size_t data = box.find("end_header\n") + 11;
  SECTION("a box scene cut to 415 bytes") {
    REQUIRE(box.size() > 415);
    CHECK_THAT(load_error(box.substr(0, 415)), Catch::Contains("truncated") || Catch::Contains("hold at most"));
  }
  SECTION("a box scene cut 5 bytes after end_header") {
    CHECK_THAT(load_error(box.substr(0, data + 5)), Catch::Contains("element 'vertex'"));
  }
  SECTION("a header without end_header is refused at once") {
    double seconds = 0;
    std::string bytes = box.substr(0, data - 11) + std::string(1 << 20, 'x');
    CHECK_THAT(load_error(bytes, &seconds), Catch::Contains("end_header"));
    CHECK(seconds < 5.0);  // a bound on a hang, not a speed claim: assimp took minutes
    CHECK_THAT(load_error(box.substr(0, data - 11)), Catch::Contains("no end_header"));
  }
  SECTION("ASCII: 5 vertices declared, 3 given") {
    CHECK_THAT(load_error(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
               Catch::Contains("element 'vertex'"));
  }
  SECTION("ASCII: 2 faces declared, 1 given") {
    CHECK_THAT(load_error(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 2\n3 0 1 2\n"),
               Catch::Contains("element 'face' 1 of 2") && Catch::Contains("truncated"));
  }
  SECTION("bytes after the last element") {
    CHECK_THAT(load_error(box + "x"), Catch::Contains("1 more bytes after the last element"));
  }
}

TEST_CASE("PLY: element counts, indices and values are checked", "[scene][ply]") {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  CHECK_THAT(load_error(head + "3 0 1 3\n"), Catch::Contains("face 0 refers to vertex 3") && Catch::Contains("3 vertices"));
  CHECK_THAT(load_error(head + "3 0 -1 2\n"), Catch::Contains("negative"));
  CHECK_THAT(load_error(head + "3 0 1 2.5\n"), Catch::Contains("'2.5' is not an integer"));
  CHECK_THAT(load_error(head + "256 0 1 2\n"), Catch::Contains("'256' is not an integer"));
  CHECK(load_error(head + "3 0 1 2\n") == "(loaded)");
  CHECK(load_error(head + "3 0 1 2\n\n  \n") == "(loaded)");  // trailing white space
  // A huge count is refused against the file's size, before any allocation.
  CHECK_THAT(load_error("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n0123456789ab"),
             Catch::Contains("declares 4000000000"));
  CHECK_THAT(load_error("ply\nformat ascii 1.0\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n3 0 1 2\n"),
             Catch::Contains("strips are not supported"));
  CHECK_THAT(load_error("ply\nformat ascii 2.0\nend_header\n"), Catch::Contains("line 2"));
  CHECK_THAT(load_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n"), Catch::Contains("before any element"));
  CHECK_THAT(load_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n"),
             Catch::Contains("not an integer type"));
  CHECK_THAT(load_error(std::string(kAsciiHeader).replace(std::string(kAsciiHeader).find("vertex_indices"), 14, "corners") +
                        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 2\n3 0 1 2\n3 0 2 3\n"),
             Catch::Contains("vertex_indices"));
  CHECK_THAT(load_error(head.substr(0, head.find("end_header")) + "end_header\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
             Catch::Contains("non-finite vertex"));
}

TEST_CASE("PLY: ascii, both binary byte orders, any types and element order read alike", "[scene][ply]") {
  // Two triangles over four vertices: (0,0,0) (1,0,0) (1,1,0) (0,1,0).
  const std::string ascii =
      "ply\nformat ascii 1.0\ncomment faces first\nelement face 2\nproperty uchar flags\n"
      "property list uchar uint vertex_indices\nelement vertex 4\nproperty double x\nproperty short y\n"
      "property float z\nproperty float confidence\nend_header\n7 3 0 1 2\n7 3 0 2 3\n0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n";
  std::string le = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  std::string be = le;
  be.replace(be.find("little"), 6, "big");
  const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const auto put = [](std::string& out, const void* p, size_t n, bool big) {
    const char* b = static_cast<const char*>(p);
    for (size_t i = 0; i < n; ++i) out.push_back(big ? b[n - 1 - i] : b[i]);
  };
  for (int big = 0; big < 2; ++big) {
    std::string& out = big ? be : le;
    for (const auto& v : xy) {
      const float c[3] = {v[0], v[1], 0};
      for (float f : c) put(out, &f, 4, big);
    }
    const int32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& f : faces) {
      out.push_back(3);
      for (int32_t i : f) put(out, &i, 4, big);
    }
  }
  for (const std::string* bytes : {&ascii, static_cast<const std::string*>(&le), static_cast<const std::string*>(&be)}) {
    const PlyMesh mesh = read_ply_mesh(*bytes, "t.ply");
    REQUIRE(mesh.positions.size() == 4);
    REQUIRE(mesh.triangles.size() == 2);
    CHECK(mesh.positions[2] == Vec3f{1, 1, 0});
    CHECK(mesh.triangles[1] == std::array<uint32_t, 3>{0, 2, 3});
    CHECK(mesh.normals.empty());
  }
}

TEST_CASE("PLY: polygons are split as documented", "[scene][ply]") {
  const auto mesh_of = [](const std::string& vertices, int count, const std::string& face) {
    return read_ply_mesh("ply\nformat ascii 1.0\nelement vertex " + std::to_string(count) +
                             "\nproperty float x\nproperty float y\nproperty float z\nelement face 2\n"
                             "property list uchar int vertex_indices\nend_header\n" + vertices + face + "2 0 1\n",
                         "p.ply");
  };
  // A convex quad: a b c, a c d (as assimp); the line face takes no number.
  PlyMesh m = mesh_of("0 0 0\n1 0 0\n1 1 0\n0 1 0\n", 4, "4 0 1 2 3\n");
  REQUIRE(m.triangles.size() == 2);
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{0, 1, 2});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{0, 2, 3});
  // A concave quad (vertex 2 is reflex): split from it, inside the quad.
  m = mesh_of("0 0 0\n2 0 0\n0.5 0.5 0\n0 2 0\n", 4, "4 0 1 2 3\n");
  REQUIRE(m.triangles.size() == 2);
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{2, 3, 0});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{2, 0, 1});
  // A pentagon: a fan from its first vertex.
  m = mesh_of("0 0 0\n1 0 0\n1.5 1 0\n0.5 1.5 0\n-0.5 1 0\n", 5, "5 0 1 2 3 4\n");
  REQUIRE(m.triangles.size() == 3);
  CHECK(m.triangles[2] == std::array<uint32_t, 3>{0, 3, 4});
}

TEST_CASE("PLY: vbsim's reader and assimp read valid files to the same triangles", "[scene][ply]") {
  SeededRandom rng(5);
  std::vector<Triangle> tris;
  std::vector<std::array<Vec3f, 3>> normals;
  for (int k = 0; k < 300; ++k) {
    Triangle t;
    for (Vec3f* v : {&t.v0, &t.v1, &t.v2})
      *v = {static_cast<float>(rng.uniform(-100, 100)), static_cast<float>(rng.uniform(-1e-3, 1e-3)),
            static_cast<float>(rng.uniform(-1e6, 1e6))};
    tris.push_back(t);
    normals.push_back({rng.unit_vector(), rng.unit_vector(), rng.unit_vector()});
  }
  for (const bool with_normals : {false, true}) {
    const std::string path = scratch(with_normals ? "n.ply" : "p.ply");
    write_ply_scene(path, tris, with_normals ? normals : std::vector<std::array<Vec3f, 3>>{});
    const Scene ours = load_scene(path);
    const std::vector<Triangle> theirs = assimp_triangles(path);
    REQUIRE(ours.size() == static_cast<int>(theirs.size()));
    int differ = 0;
    for (size_t k = 0; k < theirs.size(); ++k) differ += !same_bits(ours.triangles[k], theirs[k]);
    CHECK(differ == 0);
    CHECK(ours.has_normals() == with_normals);
    std::filesystem::remove(path);
  }
  // ASCII with quads and exact decimals, vertices shared between faces.
  const std::string ascii = write_bytes(
      "a.ply",
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n2 0 0\n2 2 0\n0 2 0\n0.5 0.25 4\n-0.75 0.125 -8\n4 0 1 2 3\n3 4 5 0\n4 3 2 1 0\n");
  const Scene ours = load_scene(ascii);
  const std::vector<Triangle> theirs = assimp_triangles(ascii);
  REQUIRE(ours.size() == static_cast<int>(theirs.size()));
  for (size_t k = 0; k < theirs.size(); ++k) CHECK(same_bits(ours.triangles[k], theirs[k]));
  std::filesystem::remove(ascii);
}
