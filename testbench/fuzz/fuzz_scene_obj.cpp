// Fuzz target: the scene loading path for OBJ files (docs/scene.md) on any
// bytes, then the BVH build over what it loads: a scene is read whole and
// finite, or refused with a SceneError.
#include <cmath>

#include "fuzz_support.h"
#include "scene/bvh.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vbsim;
  const std::string path = fuzz::input_file(data, size, ".obj");
  try {
    const Scene scene = load_scene(path);
    if (scene.size() <= 0) vbsim::fuzz::finding("a scene without triangles was accepted");
    for (const Triangle& t : scene.triangles)
      if (!is_finite(t.v0) || !is_finite(t.v1) || !is_finite(t.v2)) vbsim::fuzz::finding("a non-finite vertex");
    const Bvh bvh = build_bvh(scene);
    if (bvh.tris.size() != static_cast<size_t>(scene.size())) vbsim::fuzz::finding("the BVH lost triangles");
  } catch (const SceneError&) {
  }
  return 0;
}
