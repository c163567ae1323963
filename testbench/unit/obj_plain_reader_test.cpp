// The plain OBJ reader against assimp's importer: on the bundled bunny and on
// random plain files whose numbers take every form the validator passes
// (long mantissas, exponents, signs, "1.", "-.5"), negative indices, the four
// reference forms, tabs, CRLF line ends, texture coordinates and comments,
// both paths give the same triangles, normals and bounds bit for bit; files
// with anything for assimp to group, split or triangulate are not plain.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "scene/obj_assimp_reader.h"
#include "scene/obj_plain_reader.h"
#include "scene/obj_validator.h"
#include "scene/scene.h"

using namespace vbsim;

namespace {

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool same_bits(const Vec3f& a, const Vec3f& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Both readers on `text`; every triangle, normal and bound bit for bit.
void check_both_readers_agree(const std::string& text,
                              const std::optional<std::array<float, 16>>& transform = std::nullopt) {
  const ObjSummary summary = validate_obj(text, "m.obj");
  REQUIRE(summary.plain());
  const Scene plain = read_plain_obj(text, "m.obj", summary, transform);
  const Scene assimp = read_obj_with_assimp(text, "m.obj", summary, transform);
  REQUIRE(plain.size() == assimp.size());
  REQUIRE(plain.has_normals() == assimp.has_normals());
  for (int32_t i = 0; i < plain.size(); ++i) {
    INFO("triangle " << i);
    CHECK(same_bits(plain.triangles[i].v0, assimp.triangles[i].v0));
    CHECK(same_bits(plain.triangles[i].v1, assimp.triangles[i].v1));
    CHECK(same_bits(plain.triangles[i].v2, assimp.triangles[i].v2));
    if (plain.has_normals())
      for (int k = 0; k < 3; ++k) CHECK(same_bits(plain.normals[i][k], assimp.normals[i][k]));
  }
  CHECK(same_bits(plain.bounds.lo, assimp.bounds.lo));
  CHECK(same_bits(plain.bounds.hi, assimp.bounds.hi));
}

/// A decimal in one of the forms the validator passes, from `rng`.
std::string random_number(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> form(0, 7), exponent(-30, 30), digits(1, 60);
  const double x = unit(rng);
  switch (form(rng)) {
    case 0: return fmt::format("{:.17g}", x * std::pow(10.0, exponent(rng)));
    case 1: return fmt::format("{:.6f}", x * 100);
    case 2: {  // a long mantissa: past the 15 decimals assimp reads, up to 60 digits
      std::string s = x < 0 ? "-" : "";
      const int n = digits(rng);
      for (int i = 0; i < n; ++i) s += static_cast<char>('0' + rng() % 10);
      if (n > 1) s.insert(s.size() - static_cast<size_t>(rng() % static_cast<uint64_t>(n)), ".");
      return s;
    }
    case 3: return fmt::format("{}{}e{}{}", x < 0 ? "-" : "+", rng() % 1000, rng() % 2 ? "-" : "+", rng() % 30);
    case 4: return fmt::format("{}.", static_cast<int>(x * 50));
    case 5: return fmt::format("{}.{}", x < 0 ? "-" : "+", rng() % 100000);
    case 6: return rng() % 2 ? "-0" : "0.000";
    default: return fmt::format("{:.9g}E{}", x, exponent(rng) / 3);
  }
}

/// A random plain OBJ file: `vertices` vertices and normals, `faces` faces of
/// one reference form, negative indices now and then, tabs and CRLF.
std::string random_plain_obj(uint64_t seed, int vertices, int faces, int form) {
  std::mt19937_64 rng(seed);
  const char* eol = seed % 2 ? "\r\n" : "\n";
  std::string s = fmt::format("# random plain file {}{}", seed, eol);
  for (int i = 0; i < vertices; ++i) {
    s += fmt::format("v {}{}{} {}{}", random_number(rng), rng() % 3 ? " " : "\t ", random_number(rng),
                     random_number(rng), eol);
    s += fmt::format("vn {} {} {}{}", random_number(rng), random_number(rng), random_number(rng), eol);
    s += fmt::format("vt 0.{} 0.5{}", rng() % 10, eol);
    if (i % 17 == 0) s += fmt::format("s {}{}{}", i % 2 ? "off" : "1", eol, eol);
  }
  for (int f = 0; f < faces; ++f) {
    s += "f";
    for (int k = 0; k < 3; ++k) {
      const int v = static_cast<int>(rng() % static_cast<uint64_t>(vertices)) + 1;
      const std::string i = rng() % 4 ? std::to_string(v) : std::to_string(v - vertices - 1);  // negative: from the end
      const std::string forms[4] = {i, i + "/" + i, i + "//" + i, i + "/" + i + "/" + i};
      s += (k == 1 && rng() % 2 ? "\t" : " ") + forms[form];
    }
    s += eol;
  }
  return s;
}

}  // namespace

TEST_CASE("plain OBJ reader: the bundled bunny as assimp reads it", "[scene][obj]") {
  check_both_readers_agree(read(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj"));
  const std::array<float, 16> transform = {2, 0, 0, 1e3f, 0, 0.5f, 0.25f, 0, 0, 0, 3, -7, 0, 0, 0, 1};
  check_both_readers_agree(read(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj"), transform);
}

TEST_CASE("plain OBJ reader: random files in every number and reference form", "[scene][obj]") {
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    INFO("seed " << seed);
    const int form = static_cast<int>(seed % 4);
    const std::string text = random_plain_obj(seed, 40, 120, form);
    check_both_readers_agree(text);
    const Scene scene = read_plain_obj(text, "m.obj", validate_obj(text, "m.obj"), std::nullopt);
    CHECK(scene.size() == 120);
    CHECK(scene.has_normals() == (form >= 2));
  }
}

TEST_CASE("plain OBJ reader: what assimp would group, split or triangulate is not plain", "[scene][obj]") {
  const std::string t = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n";
  CHECK(validate_obj(t + "f 1 2 3\nf 2 4 3\n", "m.obj").plain());
  CHECK(validate_obj(t + "f 1//1 2//1 3//1\n", "m.obj").plain());
  CHECK(!validate_obj(t + "f 1 2 4 3\n", "m.obj").plain());                  // a quad: triangulated
  CHECK(!validate_obj(t + "o a\nf 1 2 3\n", "m.obj").plain());               // objects and groups: meshes
  CHECK(!validate_obj(t + "g a\nf 1 2 3\n", "m.obj").plain());
  CHECK(!validate_obj(t + "usemtl m\nf 1 2 3\n", "m.obj").plain());
  CHECK(!validate_obj(t + "l 1 2\nf 1 2 3\n", "m.obj").plain());
  CHECK(!validate_obj(t + " f 1 2 3\n", "m.obj").plain());                   // a statement not at its line's start
  CHECK(!validate_obj(t + "f 1//1 2//1 3//1\nf 1 2 3\n", "m.obj").plain());  // normals on some faces only
  CHECK(!validate_obj("v 1 0 0 1\nv 1 1 0\nv 0 1 0\nf 1 2 3\n", "m.obj").plain());  // a homogeneous vertex
  CHECK(!validate_obj("v " + std::string(70, '1') + " 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\n", "m.obj").plain());
}

TEST_CASE("plain OBJ reader: a non-finite or huge vertex is refused, naming the line", "[scene][obj]") {
  const std::string text = "v 0 0 0\nv 1 0 0\nv 1e39 1 0\nf 1 2 3\n";
  const ObjSummary summary = validate_obj(text, "m.obj");
  REQUIRE(summary.plain());
  CHECK_THROWS_WITH(read_plain_obj(text, "m.obj", summary, std::nullopt),
                    Catch::Contains("m.obj") && Catch::Contains("OBJ line 4") && Catch::Contains("non-finite"));
  CHECK_THROWS_AS(read_obj_with_assimp(text, "m.obj", summary, std::nullopt), SceneError);
}
