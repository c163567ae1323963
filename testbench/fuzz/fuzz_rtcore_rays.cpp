// Fuzz target: the rtcore-systemc ray import on any bytes; every ray it
// yields must pass the trace format's rules.
#include "fuzz_support.h"
#include "trace/rtcore_ray_import.h"
#include "trace/trace_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vbsim;
  const std::string path = fuzz::input_file(data, size, ".bin");
  try {
    RtcoreRayReader reader(path, "mesh.ply");
    TraceRay ray;
    while (reader.next(ray)) {
      TraceFieldProblem problem;
      if (!check_trace_ray(ray, -1, problem)) fuzz::finding("an imported ray breaks rule " + problem.field);
    }
  } catch (const TraceError&) {
  }
  return 0;
}
