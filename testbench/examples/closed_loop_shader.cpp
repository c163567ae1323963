// A closed-loop workload of the user's own on the accelerator: an ambient
// occlusion shader (a RayShader, replay/closed_loop.h). It casts one camera
// ray a pixel; at each hit it casts AO_RAYS short occlusion rays about the
// geometric normal, on the side the camera ray came from; a pixel's
// occlusion is the share of them that hit something within RADIUS (a tenth
// of the scene's diagonal). The accelerator asks the shader for rays and
// hands it every answer (Accelerator::set_shader); the same shader runs
// untimed too (run_functional_closed_loop), and both runs must give the same
// answers: they print their occlusion sums.
//
//   closed_loop_shader TRACE [AO_RAYS]   (the trace's scene; 4 rays a hit by default)
//
// prints "key value" lines: rays, occluded (both runs), cycles, later (the
// times the shader had nothing until an answer arrived).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <systemc>

#include "datapath/hit_point.h"
#include "datapath/self_intersection_method.h"
#include "hw/accelerator.h"
#include "render/camera.h"
#include "replay/closed_loop.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

#include "example_main.h"

namespace {

constexpr int kWidth = 48, kHeight = 36;

class AmbientOcclusion final : public vbsim::RayShader {
 public:
  AmbientOcclusion(const vbsim::Scene& scene, int ao_rays)
      : scene_(scene), camera_(vbsim::CameraSpec{}, scene.bounds, kWidth, kHeight), ao_rays_(ao_rays),
        radius_(0.1f * vbsim::length(scene.bounds.hi - scene.bounds.lo)) {}

  vbsim::ShaderAnswer next_ray(vbsim::TraceRay& out, uint64_t) override {
    if (queue_.empty() && pixel_ < kWidth * kHeight) {  // the next camera ray
      vbsim::TraceRay camera;
      camera.kind = vbsim::RayKind::Primary;
      camera.o = camera_.eye();
      camera.d = camera_.direction(pixel_ % kWidth, pixel_ / kWidth);
      queue_.push_back(camera);
      ++pixel_;
    }
    if (queue_.empty()) return outstanding_ ? vbsim::ShaderAnswer::Later : vbsim::ShaderAnswer::Finished;
    out = queue_.front();
    queue_.pop_front();
    out.id = next_id_++;
    ++outstanding_;
    return vbsim::ShaderAnswer::Ray;
  }

  void on_result(const vbsim::TraceRay& ray, const vbsim::RayOutcome& outcome, uint64_t) override {
    --outstanding_;
    if (ray.kind == vbsim::RayKind::Shadow) {
      occluded += outcome.answer >= 0;
      return;
    }
    if (outcome.answer < 0) return;
    const vbsim::Triangle& tri = scene_.triangles[static_cast<size_t>(outcome.hit.prim)];
    vbsim::Vec3f n = vbsim::normalize(vbsim::geometric_normal(tri));
    if (vbsim::dot(n, ray.d) > 0.0f) n = -n;  // the side the camera ray came from
    // A fixed set of directions about n: tilted 45 degrees towards each of ao_rays_ azimuths.
    const vbsim::Vec3f helper = std::fabs(n.x) < 0.9f ? vbsim::Vec3f{1, 0, 0} : vbsim::Vec3f{0, 1, 0};
    const vbsim::Vec3f t1 = vbsim::normalize(vbsim::cross(helper, n)), t2 = vbsim::cross(n, t1);
    for (int k = 0; k < ao_rays_; ++k) {
      const float phi = 6.2831853f * static_cast<float>(k) / static_cast<float>(ao_rays_);
      vbsim::TraceRay ao;
      ao.kind = vbsim::RayKind::Shadow;
      ao.parent = ray.id;
      ao.set_parent_hit(outcome.hit.prim, outcome.hit.t, outcome.hit.u, outcome.hit.v);
      ao.o = vbsim::hit_point_barycentric(tri, outcome.hit.u, outcome.hit.v);
      ao.d = n + std::cos(phi) * t1 + std::sin(phi) * t2;
      ao.tmax = radius_ / vbsim::length(ao.d);
      queue_.push_back(ao);
    }
  }

  uint64_t occluded = 0;

 private:
  const vbsim::Scene& scene_;
  vbsim::PinholeCamera camera_;
  int ao_rays_;
  float radius_;
  int pixel_ = 0;
  int64_t next_id_ = 0;
  uint64_t outstanding_ = 0;
  std::deque<vbsim::TraceRay> queue_;
};

/// Counts the Later answers of the shader it wraps.
class CountingLater final : public vbsim::RayShader {
 public:
  explicit CountingLater(vbsim::RayShader& inner) : inner_(inner) {}
  vbsim::ShaderAnswer next_ray(vbsim::TraceRay& out, uint64_t cycle) override {
    const vbsim::ShaderAnswer a = inner_.next_ray(out, cycle);
    later += a == vbsim::ShaderAnswer::Later;
    return a;
  }
  void on_result(const vbsim::TraceRay& ray, const vbsim::RayOutcome& out, uint64_t cycle) override {
    inner_.on_result(ray, out, cycle);
  }
  uint64_t later = 0;

 private:
  vbsim::RayShader& inner_;
};

int run(int argc, char** argv) {
  if (argc < 2) throw std::invalid_argument("usage: closed_loop_shader TRACE [AO_RAYS]");
  const std::string trace = argv[1];
  const int ao_rays = argc > 2 ? std::stoi(argv[2]) : 4;
  if (ao_rays < 1 || ao_rays > 64) throw std::invalid_argument("AO_RAYS must be 1 to 64");
  const vbsim::SceneAndBvh sb = vbsim::load_trace_scene(vbsim::open_trace(trace)->header());
  vbsim::ReplayOptions options;
  std::string error;
  if (!vbsim::parse_method("validity-bit", options.method, error)) throw std::runtime_error(error);

  // Untimed: each answer at once.
  AmbientOcclusion untimed(sb.scene, ao_rays);
  vbsim::FunctionalReplayer replayer(sb.scene, sb.bvh, options);
  const uint64_t untimed_rays = vbsim::run_functional_closed_loop(untimed, replayer);

  // On the accelerator: the source asks the shader, the result sink answers it.
  AmbientOcclusion shader(sb.scene, ao_rays);
  CountingLater counted(shader);
  vbsim::hw::Accelerator accelerator("accelerator", vbsim::hw::load_preset("small", "closed_loop_shader"), sb.scene,
                                     sb.bvh, options);
  accelerator.set_shader(counted);
  sc_core::sc_start();
  accelerator.check();  // an error inside the model, a stuck shader: thrown here

  const vbsim::hw::HwCounters c = accelerator.chip_counters();
  std::printf("rays %llu\n", static_cast<unsigned long long>(c.rays));
  std::printf("untimed_rays %llu\n", static_cast<unsigned long long>(untimed_rays));
  std::printf("occluded %llu\n", static_cast<unsigned long long>(shader.occluded));
  std::printf("untimed_occluded %llu\n", static_cast<unsigned long long>(untimed.occluded));
  std::printf("cycles %llu\n", static_cast<unsigned long long>(c.cycles));
  std::printf("later %llu\n", static_cast<unsigned long long>(counted.later));
  return 0;
}

}  // namespace

int sc_main(int argc, char** argv) { return vbsim_examples::run_example("closed_loop_shader", run, argc, argv); }
