// Tests of load_scene: triangle numbering, normals, the trace-header transform,
// errors, and the bundled bunny.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace vbsim;

namespace {

// A fresh directory under the system temp dir, removed with the object.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("vbsim_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path file = path / name;
    std::ofstream(file) << text;
    return file.string();
  }
};

const std::string kBunnyPath = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj";
constexpr int kBunnyCells = 3674;  // cells in the npm package `bunny` 1.0.1

bool same(const Triangle& a, const Triangle& b) { return a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2; }

// A quad, a line element, then a triangle in a second object.
const char* kTwoObjects =
    "o first\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 0.5 0.25 2\nv 0.75 0.5 2\nv 0.25 0.75 2\n"
    "f 1 2 3 4\n"
    "l 1 3\n"
    "o second\n"
    "f 5 6 7\n";

}  // namespace

TEST_CASE("OBJ triangles are numbered in file order, a quad giving two", "[scene]") {
  TempDir dir;
  const Scene scene = load_scene(dir.write("two_objects.obj", kTwoObjects));
  REQUIRE(scene.size() == 3);
  CHECK(same(scene.triangles[0], Triangle{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
  CHECK(same(scene.triangles[1], Triangle{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  CHECK(same(scene.triangles[2], Triangle{{0.5f, 0.25f, 2}, {0.75f, 0.5f, 2}, {0.25f, 0.75f, 2}}));
  CHECK_FALSE(scene.has_normals());
  CHECK(scene.bounds.lo == Vec3f{0, 0, 0});
  CHECK(scene.bounds.hi == Vec3f{1, 1, 2});
}

TEST_CASE("OBJ normals are kept per corner when every mesh has them", "[scene]") {
  TempDir dir;
  const Scene with = load_scene(dir.write("normals.obj",
                                          "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                          "vn 0 0 1\nvn 0 0.6 0.8\nvn 1 0 0\n"
                                          "f 1//2 2//3 3//1\n"));
  REQUIRE(with.has_normals());
  REQUIRE(with.normals.size() == 1);
  CHECK(with.normals[0][0] == Vec3f{0, 0.6f, 0.8f});
  CHECK(with.normals[0][1] == Vec3f{1, 0, 0});
  CHECK(with.normals[0][2] == Vec3f{0, 0, 1});
  CHECK(with.shading_normal(0, 0.5f, 0.5f) == Vec3f{0.5f, 0, 0.5f});

  // The second object has no normals, so the scene has none.
  const Scene mixed = load_scene(dir.write("mixed.obj",
                                           "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                                           "f 1//1 2//1 3//1\n"
                                           "o b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n"));
  CHECK(mixed.size() == 2);
  CHECK_FALSE(mixed.has_normals());
}

TEST_CASE("the trace transform is applied in float32, left to right", "[scene]") {
  TempDir dir;
  const std::string path = dir.write("transform.obj",
                                     "v 0.3 0.05 0.75\nv 0 0 0\nv 1 0 0\n"
                                     "vn 1 0 0\nvn 0 1 0\nvn 0 0 1\n"
                                     "f 1//1 2//2 3//3\n");
  const float big = 1048576.0f;  // 2^20: float spacing there is 2^-3 above, 2^-4 below
  const std::array<float, 16> m = {3, 1, 0, big,  0, 0.5f, 0, -big,  0, 0, -2, big,  0, 0, 0, 1};
  const Scene scene = load_scene(path, m);
  REQUIRE(scene.size() == 1);
  const Triangle& t = scene.triangles[0];
  // x' = ((3*0.3f + 1*0.05f) + 0*0.75f) + 2^20: 0.95000005 + 2^20 rounds up to 2^20 + 1.
  // (Adding 2^20 to 0.05f first would give 2^20 + 0.875.)
  CHECK(t.v0.x == 1048577.0f);
  // y' = 0.025000001 - 2^20 = -1048575.975 rounds to -2^20 (spacing 2^-4).
  CHECK(t.v0.y == -1048576.0f);
  CHECK(t.v0.z == 1048574.5f);  // -1.5 + 2^20, exact
  CHECK(t.v1 == Vec3f{big, -big, big});
  CHECK(t.v2 == Vec3f{big + 3, -big, big});

  // Normals: inverse transpose of A = [[3,1,0],[0,0.5,0],[0,0,-2]] is
  // [[1/3,0,0],[-2/3,2,0],[0,0,-1/2]], applied in double, rounded once.
  REQUIRE(scene.has_normals());
  CHECK(scene.normals[0][0] == Vec3f{static_cast<float>(1.0 / 3.0), static_cast<float>(-2.0 / 3.0), 0});
  CHECK(scene.normals[0][1] == Vec3f{0, 2, 0});
  CHECK(scene.normals[0][2] == Vec3f{0, 0, -0.5f});
  // Independent check: n' . (A e) == n . e for the normal (1,0,0) and any edge e.
  const double e[3] = {0.25, -1.5, 3.0};
  const double ae[3] = {3 * e[0] + e[1], 0.5 * e[1], -2 * e[2]};
  const Vec3f n = scene.normals[0][0];
  CHECK(n.x * ae[0] + n.y * ae[1] + n.z * ae[2] == Approx(e[0]).epsilon(1e-6));
}

TEST_CASE("scene errors name the file", "[scene]") {
  TempDir dir;
  const std::string missing = (dir.path / "missing.obj").string();
  CHECK_THROWS_WITH(load_scene(missing), Catch::Contains(missing) && Catch::Contains("no such file"));

  const std::string lines = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\np 1\n");
  CHECK_THROWS_WITH(load_scene(lines), Catch::Contains(lines) && Catch::Contains("no triangles"));

  const std::string empty = dir.write("empty.obj", "# nothing\n");
  CHECK_THROWS_WITH(load_scene(empty), Catch::Contains(empty) && Catch::Contains("no triangles"));
  const std::string empty_group = dir.write("empty_group.obj", "g nothing\n");  // not plain: assimp's refusal
  CHECK_THROWS_WITH(load_scene(empty_group), Catch::Contains(empty_group) && Catch::Contains("assimp"));

  const std::string huge = dir.write("huge.obj", "v 1e39 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  CHECK_THROWS_WITH(load_scene(huge), Catch::Contains(huge) && Catch::Contains("non-finite"));

  const std::string fine = dir.write("fine.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  const std::array<float, 16> projective = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  CHECK_THROWS_WITH(load_scene(fine, projective), Catch::Contains(fine) && Catch::Contains("row 3"));
  const std::array<float, 16> overflow = {1e30f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const std::string far = dir.write("far.obj", "v 1e9 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  CHECK_THROWS_WITH(load_scene(far, overflow), Catch::Contains("after the transform"));
}

TEST_CASE("the bundled bunny loads with one triangle per cell and normals", "[scene]") {
  const Scene bunny = load_scene(kBunnyPath);
  REQUIRE(bunny.size() == kBunnyCells);
  REQUIRE(bunny.has_normals());

  // Every coordinate equals the correctly rounded float32 of its decimal in the
  // file (strtof), so any OBJ reader sees the same triangles as vbsim.
  std::ifstream in(kBunnyPath);
  std::vector<Vec3f> v, vn;
  std::vector<int> corner_v, corner_n;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag, a, b, c;
    fields >> tag;
    if (tag == "v" || tag == "vn") {
      fields >> a >> b >> c;
      (tag == "v" ? v : vn).push_back({std::strtof(a.c_str(), nullptr), std::strtof(b.c_str(), nullptr),
                                       std::strtof(c.c_str(), nullptr)});
    } else if (tag == "f") {
      for (int k = 0; k < 3; ++k) {
        fields >> a;  // "i//n"
        corner_v.push_back(std::atoi(a.c_str()) - 1);
        corner_n.push_back(std::atoi(a.c_str() + a.find("//") + 2) - 1);
      }
    }
  }
  REQUIRE(corner_v.size() == 3u * kBunnyCells);
  int vertex_mismatches = 0, normal_mismatches = 0, non_unit_normals = 0;
  for (int i = 0; i < bunny.size(); ++i) {
    const Vec3f corners[3] = {bunny.triangles[i].v0, bunny.triangles[i].v1, bunny.triangles[i].v2};
    for (int k = 0; k < 3; ++k) {
      vertex_mismatches += corners[k] != v[corner_v[3 * i + k]];
      normal_mismatches += bunny.normals[i][k] != vn[corner_n[3 * i + k]];
      non_unit_normals += std::fabs(length(bunny.normals[i][k]) - 1.0f) > 1e-6f;
    }
  }
  CHECK(vertex_mismatches == 0);
  CHECK(normal_mismatches == 0);
  CHECK(non_unit_normals == 0);
}
