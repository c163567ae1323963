// Fuzz target: the binary trace reader (.vbt) on any bytes, with a scene of 16
// triangles for the index checks; every ray it yields must pass the format's rules.
#include "fuzz_support.h"
#include "trace/binary_trace_reader.h"
#include "trace/trace_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vbsim;
  const std::string path = fuzz::input_file(data, size, ".vbt");
  try {
    BinaryTraceReader reader(path);
    reader.set_triangle_count(16);
    TraceRay ray;
    int64_t rays = 0;
    while (reader.next(ray)) {
      TraceFieldProblem problem;
      if (!check_trace_ray(ray, 16, problem)) fuzz::finding("a ray the reader yields breaks rule " + problem.field);
      ++rays;
    }
    if (reader.record_count() >= 0 && rays != reader.record_count()) fuzz::finding("fewer rays than records");
  } catch (const TraceError&) {
  }
  return 0;
}
