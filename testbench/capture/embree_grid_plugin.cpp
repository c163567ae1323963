// A plugin linked to Embree that traces the capture tests' grid
// (embree_grid.h), for a program that loads it with dlopen (RTLD_LOCAL, as
// Python loads an extension module such as Open3D's) or dlmopen: its
// libembree3 then comes along as a local library.
#include "embree_grid.h"

/// Traces the grid into `out_path`; 0 on success.
extern "C" __attribute__((visibility("default"))) int vbsim_trace_grid(const char* out_path) {
  return vbsim::test::trace_embree_grid(VBSIM_LINKED_EMBREE_GRID_API, out_path) ? 0 : 1;
}
