// The pre-run check of vbsim capture: which programs define Embree's functions themselves.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "capture/static_embree_check.h"

using namespace vbsim::capture;

TEST_CASE("static Embree check: a program with its own rtcIntersect1 is refused, programs linked to libembree3 pass",
          "[capture]") {
  const auto dir = std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path();
  const std::string own = (dir / "vbsim_capture_own_rtc_app").string();
  CHECK(elf_defines_function(own, "rtcIntersect1"));
  CHECK_FALSE(elf_defines_function(own, "rtcIntersect16"));  // it has no stand-in for that one
  CHECK_THAT(embree_defined_by_program({own}), Catch::Contains("defines Embree's functions itself"));
  // Stripped, it names no function: its bytes hold Embree's device class, and it imports no rtcIntersect1.
  const std::string stripped = own + "_stripped";
  REQUIRE(std::filesystem::exists(stripped));
  CHECK_FALSE(elf_defines_function(stripped, "rtcIntersect1"));
  CHECK_FALSE(elf_imports(stripped, "rtcIntersect1"));
  CHECK(file_contains(stripped, kEmbreeCodeMarker));
  CHECK_THAT(embree_defined_by_program({stripped}), Catch::Contains("holds Embree's code"));
  // The shared library itself holds the same marker (it is Embree's code); the
  // programs that link it import rtcIntersect1 and pass.
  CHECK(file_contains(VBSIM_EMBREE_LIBRARY, kEmbreeCodeMarker));
  CHECK(elf_imports(VBSIM_CAPTURE_TEST_APP, "rtcIntersect1"));
  CHECK_FALSE(file_contains(VBSIM_CAPTURE_TEST_APP, kEmbreeCodeMarker));
  // Linked to the shared library: the symbol is undefined in the program.
  CHECK_FALSE(elf_defines_function(VBSIM_CAPTURE_TEST_APP, "rtcIntersect1"));
  CHECK(embree_defined_by_program({VBSIM_CAPTURE_TEST_APP}).empty());
  // Not an ELF file, a missing file, an unknown command: left to the run.
  CHECK_FALSE(elf_defines_function(std::string(VBSIM_SOURCE_DIR) + "/scripts/setup.sh", "rtcIntersect1"));
  CHECK_FALSE(elf_defines_function("/nonexistent/program", "rtcIntersect1"));
  CHECK(embree_defined_by_program({"no-such-command-anywhere"}).empty());
  CHECK(resolve_on_path("sh").find("/sh") != std::string::npos);
  CHECK(resolve_on_path("./x") == "./x");
}

TEST_CASE("static Embree check: a marker across the reader's 1 MiB chunks is found", "[capture]") {
  const auto path = std::filesystem::temp_directory_path() / "vbsim_file_contains_test.bin";
  for (const std::size_t at : {std::size_t{0}, (std::size_t{1} << 20) - 5, (std::size_t{1} << 20), (std::size_t{3} << 20) + 7}) {
    INFO("marker at byte " << at);
    {
      std::ofstream out(path, std::ios::binary);
      out << std::string(at, 'x') << kEmbreeCodeMarker << std::string(100, 'y');
    }
    CHECK(file_contains(path.string(), kEmbreeCodeMarker));
    CHECK_FALSE(file_contains(path.string(), std::string(kEmbreeCodeMarker) + "z"));
  }
  std::filesystem::remove(path);
}
