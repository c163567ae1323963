// The capture tests' Embree grid (embree_grid.h) traced by a program that is
// not linked to Embree but loads it at run time, one way per MODE:
//   local           dlopen("libembree3.so.3", RTLD_LOCAL | RTLD_NOW), functions by dlsym
//   plugin PLUGIN   dlopen(PLUGIN, RTLD_LOCAL | RTLD_NOW): a library linked to Embree
//   dlmopen         dlmopen(LM_ID_NEWLM, "libembree3.so.3"), functions by dlsym
//   dlmopen-plugin PLUGIN   dlmopen(LM_ID_NEWLM, PLUGIN)
//
// Usage: embree_dlopen_app OUT.txt MODE [PLUGIN]
#include <dlfcn.h>

#include <cstring>

#include "embree_grid.h"

namespace {

template <class F>
void look_up(void* library, const char* name, F& f) {
  f = reinterpret_cast<F>(dlsym(library, name));
}

int trace_with(void* library, const char* out) {
  vbsim::test::EmbreeGridApi e{};
  look_up(library, "rtcNewDevice", e.new_device);
  look_up(library, "rtcNewScene", e.new_scene);
  look_up(library, "rtcNewGeometry", e.new_geometry);
  look_up(library, "rtcSetSharedGeometryBuffer", e.set_shared_buffer);
  look_up(library, "rtcCommitGeometry", e.commit_geometry);
  look_up(library, "rtcAttachGeometry", e.attach_geometry);
  look_up(library, "rtcReleaseGeometry", e.release_geometry);
  look_up(library, "rtcCommitScene", e.commit_scene);
  look_up(library, "rtcIntersect1", e.intersect1);
  look_up(library, "rtcOccluded1", e.occluded1);
  look_up(library, "rtcReleaseScene", e.release_scene);
  look_up(library, "rtcReleaseDevice", e.release_device);
  return vbsim::test::trace_embree_grid(e, out) ? 0 : 1;
}

int trace_in_plugin(void* plugin, const char* out) {
  using Trace = int (*)(const char*);
  const auto trace = reinterpret_cast<Trace>(dlsym(plugin, "vbsim_trace_grid"));
  if (!trace) return std::fprintf(stderr, "embree_dlopen_app: %s\n", dlerror()), 1;
  return trace(out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return std::fprintf(stderr, "usage: embree_dlopen_app OUT.txt MODE [PLUGIN]\n"), 2;
  const char* out = argv[1];
  const char* mode = argv[2];
  const char* plugin = argc > 3 ? argv[3] : "";
  void* library = nullptr;
  if (!std::strcmp(mode, "local")) library = dlopen("libembree3.so.3", RTLD_LOCAL | RTLD_NOW);
  else if (!std::strcmp(mode, "plugin")) library = dlopen(plugin, RTLD_LOCAL | RTLD_NOW);
  else if (!std::strcmp(mode, "dlmopen")) library = dlmopen(LM_ID_NEWLM, "libembree3.so.3", RTLD_NOW);
  else if (!std::strcmp(mode, "dlmopen-plugin")) library = dlmopen(LM_ID_NEWLM, plugin, RTLD_NOW);
  else return std::fprintf(stderr, "embree_dlopen_app: unknown mode %s\n", mode), 2;
  if (!library) return std::fprintf(stderr, "embree_dlopen_app: %s\n", dlerror()), 1;
  return std::strstr(mode, "plugin") ? trace_in_plugin(library, out) : trace_with(library, out);
}
