// What the writers record besides their data: a trace header's provenance
// (text and binary), a PLY comment line, a PNG iTXt chunk; and the ray count
// a progress display reads off a trace file.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <nlohmann/json.hpp>

#include <memory>

#include "render/png_file.h"
#include "scene/ply_scene_writer.h"
#include "scene/scene.h"
#include "trace/trace_file.h"
#include "trace/trace_ray_count.h"
#include "trace_test_support.h"

namespace vbsim {
namespace {

using test::TempDir;

TraceRay camera_ray(int64_t id) {
  TraceRay r;
  r.id = id;
  r.o = {0, 0, 5};
  r.d = {0, 0, -1};
  return r;
}

void write_trace(const std::string& path, const TraceHeader& h, int rays) {
  auto sink = create_trace_writer(path, h);
  for (int i = 0; i < rays; ++i) sink->write(camera_ray(i));
  sink->close();
}

TEST_CASE("a trace header keeps its provenance object in both forms", "[trace][provenance]") {
  TempDir dir("header_provenance");
  TraceHeader h;
  h.scene = "scene.ply";
  h.provenance = R"({"program":"vbsim","command":["vbsim","oracle"],"inputs":[]})";
  for (const char* name : {"t.jsonl", "t.vbt"}) {
    write_trace(dir.file(name), h, 3);
    const auto back = open_trace(dir.file(name));
    CHECK(nlohmann::json::parse(back->header().provenance) == nlohmann::json::parse(h.provenance));
    CHECK(count_trace_rays(dir.file(name)) == 3);
  }
  h.provenance = "[1, 2]";
  CHECK_THROWS(create_trace_writer(dir.file("bad.jsonl"), h));  // an object or nothing
}

TEST_CASE("the ray count skips the header, blank lines and comments", "[trace][progress]") {
  TempDir dir("ray_count");
  test::write_file(dir.file("t.jsonl"),
                   "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.obj\"}\n\n  # note\n"
                   "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n   \t\n{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1]}");
  CHECK(count_trace_rays(dir.file("t.jsonl")) == 2);  // the last line has no newline
  CHECK(count_trace_rays(dir.file("missing.jsonl")) == 0);
}

TEST_CASE("a PLY scene carries its comment line and loads the same", "[scene][provenance]") {
  TempDir dir("ply_comment");
  const std::vector<Triangle> tris = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  write_ply_scene(dir.file("a.ply"), tris, {}, "vbsim-provenance {\"program\":\"vbsim\"}");
  const std::string bytes = test::read_file(dir.file("a.ply"));
  CHECK(bytes.find("\ncomment vbsim-provenance {\"program\":\"vbsim\"}\n") < bytes.find("end_header"));
  const Scene s = load_scene(dir.file("a.ply"));
  REQUIRE(s.size() == 1);
  CHECK(s.triangles[0].v1.x == 1.0f);
  CHECK_THROWS(write_ply_scene(dir.file("b.ply"), tris, {}, "two\nlines"));
}

TEST_CASE("a PNG note is an iTXt chunk with a valid CRC and the image is unchanged", "[render][provenance]") {
  // CRC-32 of the IEND chunk type, as every PNG ends with it: AE 42 60 82.
  CHECK(png_crc32(reinterpret_cast<const uint8_t*>("IEND"), 4) == 0xae426082u);
  TempDir dir("png_note");
  const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9};
  write_png_rgb(dir.file("a.png"), 2, 2, rgb, "{\"program\":\"vbsim\"}");
  const std::string bytes = test::read_file(dir.file("a.png"));
  // Signature (8) + IHDR (25), then the chunk: length, type, keyword\0, 0, 0, \0, \0, text, CRC.
  const std::string text = "{\"program\":\"vbsim\"}";
  const std::string body = std::string("iTXtvbsim-provenance") + std::string(5, '\0') + text;
  REQUIRE(bytes.size() > 33 + 8 + body.size());
  CHECK(bytes.substr(33 + 4, body.size()) == body);
  const auto u8 = [&](size_t i) { return static_cast<uint32_t>(static_cast<uint8_t>(bytes[i])); };
  CHECK((u8(33) << 24 | u8(34) << 16 | u8(35) << 8 | u8(36)) == body.size() - 4);
  const size_t crc_at = 33 + 4 + body.size();
  CHECK((u8(crc_at) << 24 | u8(crc_at + 1) << 16 | u8(crc_at + 2) << 8 | u8(crc_at + 3)) ==
        png_crc32(reinterpret_cast<const uint8_t*>(body.data()), body.size()));
  int w = 0, h = 0, n = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(dir.file("a.png").c_str(), &w, &h, &n, 3),
                                                           stbi_image_free);
  REQUIRE(pixels);
  CHECK((w == 2 && h == 2));
  CHECK(std::vector<uint8_t>(pixels.get(), pixels.get() + 12) == rgb);
}

}  // namespace
}  // namespace vbsim
