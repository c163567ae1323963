#include "scene/scene.h"

namespace vbsim {

Vec3f Scene::shading_normal(int32_t prim, float u, float v) const {
  const auto& n = normals[static_cast<size_t>(prim)];
  return (1.0f - u - v) * n[0] + u * n[1] + v * n[2];
}

Scene make_scene(std::vector<Triangle> triangles, std::vector<std::array<Vec3f, 3>> normals) {
  Scene scene;
  scene.source = "<memory>";
  scene.triangles = std::move(triangles);
  scene.normals = std::move(normals);
  for (const Triangle& t : scene.triangles) {
    scene.bounds.extend(t.v0);
    scene.bounds.extend(t.v1);
    scene.bounds.extend(t.v2);
  }
  return scene;
}

}  // namespace vbsim
