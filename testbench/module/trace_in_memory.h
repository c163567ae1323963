// A trace file read whole for a test: its scene with its BVH, and its rays in
// trace order (for tests that reorder them or replay them several times).
#pragma once
#include <string>
#include <vector>

#include "replay/replay_run.h"
#include "trace/trace_file.h"

namespace vbsim::hw::test {

struct TraceInMemory {
  SceneAndBvh sb;
  std::vector<TraceRay> rays;
};

inline TraceInMemory read_trace(const std::string& path) {
  auto src = open_trace(path);
  TraceInMemory t{load_trace_scene(src->header()), {}};
  TraceRay r;
  while (src->next(r)) t.rays.push_back(r);
  return t;
}

}  // namespace vbsim::hw::test
