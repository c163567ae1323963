// The capture tests' Embree grid (embree_grid.h) traced by a program linked to
// Embree: the trace every other way of loading Embree must reproduce.
//
// Usage: embree_grid_direct_app OUT.txt
#include "embree_grid.h"

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: embree_grid_direct_app OUT.txt\n"), 2;
  return vbsim::test::trace_embree_grid(VBSIM_LINKED_EMBREE_GRID_API, argv[1]) ? 0 : 1;
}
