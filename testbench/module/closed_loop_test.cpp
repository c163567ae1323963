// The closed loop (replay/closed_loop.h): the accelerator asks a shader for
// rays and hands it every answer. A shader written here checks the contract
// by hand (children ready shader.latency_cycles after their parent's result,
// Later and Finished); the renderer's shader gives the same image untimed and
// on the accelerator, and the rays it cast replay, as a trace, to the same
// cycles under the same configuration.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "../unit/render_test_scene.h"
#include "hw/cycle_replay.h"
#include "render/cycle_render.h"
#include "render/renderer.h"
#include "replay/closed_loop.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"

using namespace vbsim;
using namespace vbsim::hw;

namespace {

ReplayOptions method_options(const std::string& method) {
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method(method, opt.method, err));
  return opt;
}

/// `primaries` rays straight down onto the test scene's ground; each hit gets
/// `children` shadow rays straight up from its hit point. Counts its answers.
class FanShader final : public RayShader {
 public:
  FanShader(int primaries, int children) : primaries_(primaries), children_(children) {}

  ShaderAnswer next_ray(TraceRay& out, uint64_t) override {
    ++asked_;
    if (!queue_.empty()) {
      out = queue_.front();
      queue_.erase(queue_.begin());
    } else if (made_ < primaries_) {
      out = TraceRay{};
      out.kind = RayKind::Primary;
      out.o = Vec3f{-1.5f + 0.1f * float(made_), 5.0f, 1.5f};  // beside the occluder
      out.d = Vec3f{0, -1, 0};
      ++made_;
    } else {
      ++(in_flight_ ? later_ : finished_);
      return in_flight_ ? ShaderAnswer::Later : ShaderAnswer::Finished;
    }
    out.id = next_id_++;
    ++in_flight_;
    return ShaderAnswer::Ray;
  }
  void on_result(const TraceRay& ray, const RayOutcome& outcome, uint64_t cycle) override {
    --in_flight_;
    results_[ray.id] = cycle;
    if (ray.kind != RayKind::Primary || outcome.answer < 0) return;
    for (int c = 0; c < children_; ++c) {
      TraceRay child;
      child.parent = ray.id;
      child.kind = RayKind::Shadow;
      child.set_parent_hit(outcome.hit.prim, outcome.hit.t, outcome.hit.u, outcome.hit.v);
      child.o = ray.o + outcome.hit.t * ray.d;
      child.d = Vec3f{0.01f * float(c), 1, 0};
      queue_.push_back(child);
    }
  }

  int later_ = 0, finished_ = 0, asked_ = 0;
  std::map<int64_t, uint64_t> results_;  ///< id -> cycle its answer arrived

 private:
  int primaries_, children_, made_ = 0, in_flight_ = 0;
  int64_t next_id_ = 0;
  std::vector<TraceRay> queue_;
};

}  // namespace

TEST_CASE("a closed-loop shader's children are ready the shading latency after their parent's answer",
          "[module][closed-loop]") {
  const Scene scene = make_scene(test::render_test_triangles());
  const Bvh bvh = build_bvh(scene);
  HwConfig cfg = load_preset("small", "test");
  // The latency for everything, and one for the children of primary rays (`latency_by_kind`).
  const auto [all, primary] = GENERATE(std::pair<uint32_t, uint32_t>{0, ShaderConfig::kUnset},
                                       std::pair<uint32_t, uint32_t>{37, ShaderConfig::kUnset},
                                       std::pair<uint32_t, uint32_t>{200, ShaderConfig::kUnset},
                                       std::pair<uint32_t, uint32_t>{200, 45});
  const uint32_t latency = primary == ShaderConfig::kUnset ? all : primary;  // every parent here is a primary ray
  INFO("shader latency " << all << ", after primary rays " << latency);
  cfg.shader.latency_cycles = all;
  cfg.shader.by_kind[static_cast<size_t>(RayKind::Primary)] = primary;
  FanShader shader(6, 3);
  std::map<int64_t, RayTimes> times;
  CycleRunOptions options;
  options.ray_times = [&](const RayTimes& t) { times[t.id] = t; };
  const CycleRunResult r =
      run_cycle_closed_loop(shader, scene, bvh, method_options("validity-bit"), cfg, {}, options);
  REQUIRE(times.size() == 6 + 6 * 3);  // every primary hits the ground, 3 children each
  CHECK(r.counters.rays == 24);
  CHECK(r.stats.total().rays == 24);
  size_t entered_at_answer = 0;
  uint64_t last = 0;
  for (const auto& [id, t] : times) {
    INFO("ray " << id);
    CHECK(shader.results_.at(id) == t.finished);  // the shader saw each answer at its finish cycle
    last = std::max(last, t.finished);
    if (t.parent < 0) continue;
    const RayTimes& parent = times.at(t.parent);
    // A child exists from its parent's answer on; the source reads it when a
    // lane wants a ray, and it is ready once the shading latency has passed.
    CHECK(t.entered >= parent.finished);
    entered_at_answer += t.entered == parent.finished;
    CHECK(t.ready == std::max(t.entered, parent.finished + latency));
  }
  // With a shading latency the lanes are idle when an answer arrives (Later),
  // so its children are read at once.
  if (latency > 0) CHECK(entered_at_answer == 18);
  // After the six primaries the shader had nothing until answers came back.
  CHECK(shader.later_ > 0);
  CHECK(shader.finished_ == 1);  // asked once more at the end, then never again
  CHECK(r.hw["emission"]["lane_cycles"]["idle_for_shader"].get<uint64_t>() > 0);
  CHECK(r.counters.cycles == last);
}

namespace {

/// Answers Later at once, with nothing cast: it would wait for ever.
struct StuckShader final : RayShader {
  ShaderAnswer next_ray(TraceRay&, uint64_t) override { return ShaderAnswer::Later; }
  void on_result(const TraceRay&, const RayOutcome&, uint64_t) override {}
};

}  // namespace

TEST_CASE("a shader that waits with nothing in flight is reported, untimed and on the accelerator",
          "[module][closed-loop]") {
  const Scene scene = make_scene(test::render_test_triangles());
  const Bvh bvh = build_bvh(scene);
  StuckShader stuck;
  FunctionalReplayer replayer(scene, bvh, method_options("none"));
  CHECK_THROWS_WITH(run_functional_closed_loop(stuck, replayer), Catch::Contains("'later'"));
  CHECK_THROWS_WITH(
      run_cycle_closed_loop(stuck, scene, bvh, method_options("none"), load_preset("small", "test"), {}, {}),
      Catch::Contains("the shader has no ray until a result arrives"));
}

namespace {

RenderSettings small_render(RenderIntegrator integrator, int samples) {
  RenderSettings rs;
  rs.width = 40;
  rs.height = 30;
  rs.integrator = integrator;
  rs.samples = samples;
  return rs;
}

struct BunnyScene {
  SceneAndBvh sb = load_trace_scene(open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl")->header());
};

const BunnyScene& bunny() {
  static const BunnyScene b;
  return b;
}

}  // namespace

TEST_CASE("the closed-loop render on the accelerator draws the untimed render's image", "[module][closed-loop][render]") {
  const SceneAndBvh& sb = bunny().sb;
  const std::string method = GENERATE("none", "validity-bit", "offset-normal");
  const RenderIntegrator integrator = GENERATE(RenderIntegrator::Mirror, RenderIntegrator::Path, RenderIntegrator::Ao,
                                               RenderIntegrator::Glass);
  INFO(method << " " << render_integrator_name(integrator));
  const bool one_ray = integrator == RenderIntegrator::Mirror || integrator == RenderIntegrator::Glass;
  const RenderSettings rs = small_render(integrator, one_ray ? 1 : 3);
  const ReplayOptions opt = method_options(method);
  const RenderResult functional = render_scene(sb.scene, sb.bvh, opt, rs);
  const CycleRenderResult cycle = render_scene_cycle(sb.scene, sb.bvh, opt, rs, load_preset("small", "test"), {});
  CHECK(cycle.render.image == functional.image);
  CHECK(cycle.render.errors == functional.errors);
  CHECK(cycle.render.marks == functional.marks);
  CHECK(cycle.render.primary_prim == functional.primary_prim);
  CHECK(cycle.render.stats.total().rays == functional.stats.total().rays);
  for (int k = 0; k < kRayKindCount; ++k) {
    INFO("kind " << k);
    const KindStats& a = functional.stats.by_kind[k];
    const KindStats& b = cycle.render.stats.by_kind[k];
    CHECK(a.rays == b.rays);
    CHECK(a.hits == b.hits);
    CHECK(a.verdicts == b.verdicts);
    CHECK(a.candidates.rejected == b.candidates.rejected);
  }
  CHECK(cycle.run.counters.cycles > 0);
  CHECK(cycle.run.hw["rays"].get<uint64_t>() == functional.stats.total().rays);
  if (method == std::string("none")) CHECK(functional.acne_pixels > 0);  // errors that feed back are there to see
}

TEST_CASE("a closed-loop render on the accelerator is deterministic", "[module][closed-loop][render]") {
  const SceneAndBvh& sb = bunny().sb;
  const RenderSettings rs = small_render(RenderIntegrator::Path, 2);
  const ReplayOptions opt = method_options("none");
  const HwConfig cfg = load_preset("large", "test");
  const CycleRenderResult a = render_scene_cycle(sb.scene, sb.bvh, opt, rs, cfg, {});
  const CycleRenderResult b = render_scene_cycle(sb.scene, sb.bvh, opt, rs, cfg, {});
  CHECK(a.render.image == b.render.image);
  CHECK(a.render.errors == b.render.errors);
  CHECK(a.run.hw == b.run.hw);  // every figure of the frame, the SystemC time included
}

TEST_CASE("the rays a closed-loop render cast replay, as a trace, to the same cycles", "[module][closed-loop][render]") {
  const SceneAndBvh& sb = bunny().sb;
  struct Setup {
    const char* name;
    const char* preset;
    uint32_t window, latency, lanes;
  };
  const Setup setup = GENERATE(Setup{"small", "small", 0, 0, 0}, Setup{"large", "large", 0, 0, 0},
                               Setup{"small, window 16, shader 60", "small", 16, 60, 0},
                               Setup{"small, 2 lanes, window 3", "small", 3, 0, 2});
  INFO(setup.name);
  HwConfig cfg = load_preset(setup.preset, "test");
  if (setup.window) cfg.source.window = setup.window;
  if (setup.latency) cfg.shader.latency_cycles = setup.latency;
  if (setup.lanes) cfg.source.rays_per_cycle = setup.lanes;
  const ReplayOptions opt = method_options("validity-bit");
  std::vector<TraceRay> cast;
  const CycleRenderResult loop =
      render_scene_cycle(sb.scene, sb.bvh, opt, small_render(RenderIntegrator::Path, 2), cfg, {},
                         [&cast](const TraceRay& tr) { cast.push_back(tr); });
  REQUIRE(cast.size() == loop.render.stats.total().rays);
  size_t next = 0;
  const CycleRunResult replay = run_cycle_replay(
      [&](TraceRay& tr) {
        if (next == cast.size()) return false;
        tr = cast[next++];
        return true;
      },
      sb.scene, sb.bvh, opt, cfg,
      {}, {});
  CHECK(replay.counters.cycles == loop.run.counters.cycles);
  CHECK(replay.stats.total().rays == cast.size());
  CHECK(replay.stats.total().verdicts == loop.render.stats.total().verdicts);
  CHECK(replay.hw["latency_distribution"] == loop.run.hw["latency_distribution"]);
}

TEST_CASE("the path tracer's image is a function of its seed", "[unit][render]") {
  const SceneAndBvh& sb = bunny().sb;
  const ReplayOptions opt = method_options("validity-bit");
  RenderSettings rs = small_render(RenderIntegrator::Path, 2);
  const RenderResult a = render_scene(sb.scene, sb.bvh, opt, rs);
  const RenderResult b = render_scene(sb.scene, sb.bvh, opt, rs);
  CHECK(a.image == b.image);
  rs.seed = 2;
  const RenderResult c = render_scene(sb.scene, sb.bvh, opt, rs);
  CHECK(c.image != a.image);
  CHECK(c.primary_prim.size() == a.primary_prim.size());
  rs.integrator = RenderIntegrator::Mirror;
  CHECK_THROWS_WITH(render_scene(sb.scene, sb.bvh, opt, rs), Catch::Contains("mirror integrator"));
}

TEST_CASE("the reference renderer casts the same rays whatever the method, and scores the method on them",
          "[module][closed-loop][render]") {
  const SceneAndBvh& sb = bunny().sb;
  RenderSettings rs = small_render(RenderIntegrator::Path, 2);
  rs.children_from_exact = true;
  std::vector<TraceRay> none_rays, vb_rays;
  const RenderResult none = render_scene(sb.scene, sb.bvh, method_options("none"), rs,
                                         [&](const TraceRay& tr) { none_rays.push_back(tr); });
  const RenderResult vb = render_scene(sb.scene, sb.bvh, method_options("validity-bit"), rs,
                                       [&](const TraceRay& tr) { vb_rays.push_back(tr); });
  REQUIRE(none_rays.size() == vb_rays.size());
  size_t differ = 0;
  for (size_t i = 0; i < none_rays.size(); ++i)
    differ += none_rays[i].o != vb_rays[i].o || none_rays[i].d != vb_rays[i].d ||
              none_rays[i].parent != vb_rays[i].parent || none_rays[i].expect_prim != vb_rays[i].expect_prim;
  CHECK(differ == 0);
  CHECK(none.image == vb.image);  // the exact image
  CHECK(none.acne_pixels > 100);  // the method is still scored: none re-hits its surfaces
  CHECK(vb.acne_pixels < none.acne_pixels / 10);
  // The method's own loop: its self-hits end or bend paths, so other rays follow.
  rs.children_from_exact = false;
  const RenderResult loop = render_scene(sb.scene, sb.bvh, method_options("none"), rs);
  CHECK(loop.stats.total().rays != none.stats.total().rays);
  CHECK(loop.image != none.image);
}
