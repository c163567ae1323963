// The closed-loop example (testbench/examples/closed_loop_shader.cpp): a
// user's ambient occlusion shader on the accelerator in the user's own
// sc_main gives the answers of the same shader run untimed, with the camera
// rays and occlusion rays counted by hand.
#include <catch2/catch.hpp>

#include "example_output.h"

using namespace vbsim::test;

TEST_CASE("a user's own closed-loop shader runs on the accelerator with the untimed run's answers",
          "[system][embed][closed-loop]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  for (const int ao_rays : {1, 4}) {
    INFO(ao_rays << " occlusion rays a hit");
    const ExampleFields f =
        run_example_program(VBSIM_CLOSED_LOOP_EXAMPLE, trace + " " + std::to_string(ao_rays), "cycles");
    const uint64_t rays = field_u64(f, "rays");
    CHECK(rays == field_u64(f, "untimed_rays"));
    CHECK(field_u64(f, "occluded") == field_u64(f, "untimed_occluded"));
    // 48 x 36 camera rays, and ao_rays for each that hit.
    CHECK(rays > 48 * 36);
    CHECK((rays - 48 * 36) % ao_rays == 0);
    CHECK(field_u64(f, "occluded") > 0);
    CHECK(field_u64(f, "occluded") < rays - 48 * 36);
    CHECK(field_u64(f, "cycles") > 0);
    CHECK(field_u64(f, "later") > 0);  // at the end the shader waited for answers
  }
}
