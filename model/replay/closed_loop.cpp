#include "replay/closed_loop.h"

#include <stdexcept>

namespace vbsim {

uint64_t run_functional_closed_loop(RayShader& shader, FunctionalReplayer& replayer) {
  uint64_t rays = 0;
  TraceRay ray;
  for (;;) {
    const ShaderAnswer a = shader.next_ray(ray, 0);
    if (a == ShaderAnswer::Finished) return rays;
    if (a == ShaderAnswer::Later)
      throw std::logic_error("closed loop: the shader answered 'later' with every ray it cast answered");
    const RayOutcome out = replayer.replay(ray);
    ++rays;
    shader.on_result(ray, out, 0);
  }
}

}  // namespace vbsim
