// The binary PLY scene writer round-trips float32 geometry through assimp bit
// for bit, in triangle order, with normals.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "gen/seeded_random.h"
#include "scene/ply_scene_writer.h"
#include "scene/scene.h"
#include "trace_test_support.h"

using namespace vbsim;
using vbsim::test::same_bits;
using vbsim::test::TempDir;

namespace {
float random_float(SeededRandom& rng) {
  // Magnitudes 2^-40 .. 2^40 of both signs, including values that assimp's OBJ
  // decimal reader misrounds (|x| >= 1 with long fractions).
  const double m = std::ldexp(rng.uniform(1.0, 2.0), static_cast<int>(rng.below(81)) - 40);
  return static_cast<float>(rng.uniform() < 0.5 ? -m : m);
}
}  // namespace

TEST_CASE("a binary PLY scene loads back bit for bit, in triangle order", "[scene][ply]") {
  SeededRandom rng(11);
  std::vector<Triangle> tris;
  std::vector<std::array<Vec3f, 3>> normals;
  for (int k = 0; k < 500; ++k) {
    Triangle t;
    for (Vec3f* v : {&t.v0, &t.v1, &t.v2}) *v = {random_float(rng), random_float(rng), random_float(rng)};
    tris.push_back(t);
    normals.push_back({rng.unit_vector(), rng.unit_vector(), rng.unit_vector()});
  }
  tris.push_back(Triangle{{1.1f, 2.2f, 3.3f}, {1.1f, 2.2f, 3.3f}, {1.1f, 2.2f, 3.3f}});  // degenerate: kept
  normals.push_back({Vec3f{0, 0, 1}, Vec3f{0, 0, 1}, Vec3f{0, 0, 1}});
  const TempDir dir("ply-roundtrip");
  const std::string path = dir.file("scene.ply");
  write_ply_scene(path, tris, normals);
  const Scene scene = load_scene(path);
  REQUIRE(scene.size() == static_cast<int32_t>(tris.size()));
  REQUIRE(scene.has_normals());
  for (size_t k = 0; k < tris.size(); ++k) {
    INFO("triangle " << k);
    CHECK(same_bits(scene.triangles[k].v0, tris[k].v0));
    CHECK(same_bits(scene.triangles[k].v1, tris[k].v1));
    CHECK(same_bits(scene.triangles[k].v2, tris[k].v2));
    for (int c = 0; c < 3; ++c) CHECK(same_bits(scene.normals[k][c], normals[k][c]));
  }
}

TEST_CASE("a binary PLY scene without normals loads without normals", "[scene][ply]") {
  const TempDir dir("ply-plain");
  const std::string path = dir.file("scene.ply");
  write_ply_scene(path, {Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  const Scene scene = load_scene(path);
  CHECK(scene.size() == 1);
  CHECK_FALSE(scene.has_normals());
  CHECK(geometric_normal(scene.triangles[0]).z > 0);  // winding kept
}

TEST_CASE("the PLY writer names the file it cannot write", "[scene][ply]") {
  CHECK_THROWS_WITH(write_ply_scene("/nonexistent-dir/x.ply", {Triangle{}}), Catch::Contains("/nonexistent-dir/x.ply"));
  CHECK_THROWS_WITH(write_ply_scene("/tmp/x.ply", {Triangle{}}, {{}, {}}), Catch::Contains("normal triples"));
}

TEST_CASE("a binary PLY scene whose first data byte is white space loads back bit for bit", "[scene][ply]") {
  // The first vertex's x is written first, low byte first: 0x0a (a line feed)
  // and the other white-space bytes a reader might skip after end_header.
  for (const uint32_t low_byte : {0x0au, 0x20u, 0x0du, 0x09u, 0x0bu, 0x0cu, 0x00u}) {
    const uint32_t bits = 0x3f800000u | low_byte;  // 1.0f with the low mantissa byte set
    float x;
    std::memcpy(&x, &bits, sizeof x);
    const Triangle tri{{x, 2.0f, 3.0f}, {4.0f, -5.0f, 6.0f}, {-7.0f, 8.0f, 9.5f}};
    const TempDir dir("ply-first-byte");
    const std::string path = dir.file("scene.ply");
    write_ply_scene(path, {tri});
    const Scene scene = load_scene(path);
    INFO("first data byte " << low_byte);
    REQUIRE(scene.size() == 1);
    CHECK(same_bits(scene.triangles[0].v0, tri.v0));
    CHECK(same_bits(scene.triangles[0].v1, tri.v1));
    CHECK(same_bits(scene.triangles[0].v2, tri.v2));
  }
}
