// The OBJ validation in front of assimp: the bundled meshes pass; every
// malformed statement is an error naming the line, before assimp reads it;
// assimp is given no other file (a material library is never opened).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scene/obj_validator.h"
#include "scene/scene.h"

using namespace vbsim;

namespace {

std::string validation_error(const std::string& text) {
  try {
    validate_obj(text, "m.obj");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(valid)";
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

}  // namespace

TEST_CASE("OBJ validation: the bundled meshes pass with their counts", "[scene][obj]") {
  const ObjSummary bunny = validate_obj(read(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj"), "bunny.obj");
  CHECK(bunny.vertices == 1839);
  CHECK(bunny.triangles == 3674);
  const ObjSummary wuson = validate_obj(read(std::string(VBSIM_SOURCE_DIR) + "/traces/wuson/WusonOBJ.obj"), "w.obj");
  CHECK(wuson.vertices == 2117);
  CHECK(wuson.triangles == 3732);
}

TEST_CASE("OBJ validation: malformed statements are errors naming the line", "[scene][obj]") {
  const std::string t = kTriangle;
  CHECK(validation_error(t + "f 1 2 3\n") == "(valid)");
  CHECK(validation_error(t + "vn 0 0 1\nvt 0.5 0.5\nf 1/1/1 2/1/1 -1/1/1\n") == "(valid)");
  CHECK(validation_error(t + "o a\ng b c\ns off\nusemtl m\nmtllib m.mtl\nf 1//1 2//1 3//1\n").find("normal index 1") !=
        std::string::npos);
  CHECK_THAT(validation_error(t + "f 1 2 4\n"), Catch::Contains("line 4") && Catch::Contains("vertex index 4"));
  CHECK_THAT(validation_error(t + "f 1 2 0\n"), Catch::Contains("index 0"));
  CHECK_THAT(validation_error(t + "f 1 2 -4\n"), Catch::Contains("vertex index -4"));
  CHECK_THAT(validation_error(t + "f 1 2\n"), Catch::Contains("at least 3"));
  CHECK_THAT(validation_error(t + "f 1 2/1 3\n"), Catch::Contains("texture coordinate index 1"));
  CHECK_THAT(validation_error(t + "vt 0 0\nf 1 2/1 3\n"), Catch::Contains("mix forms"));
  CHECK_THAT(validation_error(t + "f 1/ 2/ 3/\n"), Catch::Contains("empty texture coordinate"));
  CHECK_THAT(validation_error(t + "f 1///2 2 3\n"), Catch::Contains("more than two"));
  CHECK_THAT(validation_error(t + "f a b c\n"), Catch::Contains("'a' is not a vertex index"));
  CHECK_THAT(validation_error("vt 1\n"), Catch::Contains("2 or 3 numbers"));
  CHECK_THAT(validation_error("v 0 0\n"), Catch::Contains("line 1") && Catch::Contains("3 coordinates"));
  CHECK_THAT(validation_error("v 0x10 0 0\n"), Catch::Contains("'0x10' is not a decimal"));
  CHECK_THAT(validation_error("v 1e 0 0\n"), Catch::Contains("not a decimal"));
  CHECK_THAT(validation_error("v nan 0 0\n"), Catch::Contains("not a decimal"));
  CHECK_THAT(validation_error("v 0 0 0 # c\n"), Catch::Contains("3 coordinates"));
  CHECK_THAT(validation_error(t + "curv 0 1 1 2\n"), Catch::Contains("unknown statement 'curv'"));
  CHECK_THAT(validation_error(t + "f 1 2 \\\n3\n"), Catch::Contains("continued"));
  CHECK_THAT(validation_error(t + std::string("f 1 2 3\0\n", 9)), Catch::Contains("NUL"));
  CHECK_THAT(validation_error("l 1 2\n"), Catch::Contains("vertex index 1"));
  CHECK_THAT(validation_error(t + "vn 0 0 1\nl 1//1 2//1\n"), Catch::Contains("no normals"));
  CHECK_THAT(validation_error(std::string(70000, 'v')), Catch::Contains("64 KiB"));
  CHECK(validation_error("\r\n# only a comment\r\n\r\n") == "(valid)");
  CHECK(validation_error("g\n" + t + "g\r\nf 1 2 3\n") == "(valid)");
  CHECK_THAT(validation_error(t + "o\n"), Catch::Contains("line 4") && Catch::Contains("'o' needs a name"));
  CHECK_THAT(validation_error(t + "usemtl\n"), Catch::Contains("'usemtl' needs a name"));
}

TEST_CASE("OBJ loading: validated first, no material library opened", "[scene][obj]") {
  const auto dir = std::filesystem::temp_directory_path() / ("vbsim_obj_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // A material library that assimp's own parser would read: never opened.
  std::ofstream(dir / "m.mtl") << "newmtl red\nKd 1 0 0\nmap_Kd \0\0\0\n";
  std::ofstream(dir / "m.obj") << "mtllib m.mtl\n" << kTriangle << "usemtl red\nf 1 2 3\nusemtl blue\nf 3 2 1\n";
  const Scene s = load_scene((dir / "m.obj").string());
  CHECK(s.size() == 2);
  CHECK(s.triangles[1].v0 == Vec3f{0, 1, 0});
  std::ofstream(dir / "bad.obj") << kTriangle << "f 1 2 3 4\n";
  CHECK_THROWS_WITH(load_scene((dir / "bad.obj").string()),
                    Catch::Contains("bad.obj") && Catch::Contains("line 4") && Catch::Contains("vertex index 4"));
  // Every decimal form the validator passes, assimp reads to the same float32;
  // a bare leading point, which assimp refuses, the validator refuses first.
  const std::pair<const char*, float> forms[] = {{"-.5", -0.5f}, {"+.5", 0.5f}, {"+1", 1.0f},   {"5.", 5.0f},
                                                 {"1.e2", 100.0f}, {"1E+2", 100.0f}, {"00.5", 0.5f}, {"-0.25", -0.25f}};
  for (const auto& [text, value] : forms) {
    INFO(text);
    std::ofstream(dir / "d.obj", std::ios::trunc) << "v " << text << " 0 -1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    CHECK(load_scene((dir / "d.obj").string()).triangles[0].v0.x == value);
  }
  std::ofstream(dir / "d.obj", std::ios::trunc) << "v .5 0 -1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK_THROWS_WITH(load_scene((dir / "d.obj").string()),
                    Catch::Contains("line 1") && Catch::Contains("'.5' is not a decimal number assimp reads (write 0.5)"));
  // A bare `g` (an unnamed group, as 3ds Max's exporter writes it) is read.
  std::ofstream(dir / "g.obj") << "g\n" << kTriangle << "g\nf 1 2 3\ng named\nf 3 2 1\n";
  CHECK(load_scene((dir / "g.obj").string()).size() == 2);
  std::ofstream(dir / "s.stl") << "solid x\n";
  CHECK_THROWS_WITH(load_scene((dir / "s.stl").string()), Catch::Contains("unsupported format '.stl'"));
  std::filesystem::remove_all(dir);
}
