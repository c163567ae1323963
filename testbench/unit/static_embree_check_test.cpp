// The pre-run check of vbsim capture: which programs define Embree's functions themselves.
#include <catch2/catch.hpp>

#include <filesystem>

#include "capture/static_embree_check.h"

using namespace vbsim::capture;

TEST_CASE("static Embree check: a program with its own rtcIntersect1 is refused, programs linked to libembree3 pass",
          "[capture]") {
  const auto dir = std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path();
  const std::string own = (dir / "vbsim_capture_own_rtc_app").string();
  CHECK(elf_defines_function(own, "rtcIntersect1"));
  CHECK_FALSE(elf_defines_function(own, "rtcIntersect16"));  // it has no stand-in for that one
  CHECK_THAT(embree_defined_by_program({own}), Catch::Contains("defines Embree's functions itself"));
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
