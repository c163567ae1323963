// vbsim render: a small image of a scene rendered through the replay datapath
// with one self-intersection method, and an error image marking the pixels
// whose shadow or bounce rays the method got wrong (model/render/renderer.h);
// with --mode cycle on the cycle-level model, in a closed loop
// (model/render/cycle_render.h), with the frame's hardware statistics.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <array>
#include <memory>

#include "commands.h"
#include "progress/work_progress.h"
#include "energy/operation_energy.h"
#include "hw/hw_config.h"
#include "render/cycle_render.h"
#include "systemc_messages.h"
#include "tech_option.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "method_options.h"
#include "render/float_list.h"
#include "render/png_file.h"
#include "render/renderer.h"
#include "render_progress.h"
#include "replay/replay_config.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim::cli {

namespace {

struct RenderArgs {
  std::string scene;
  std::string out, errors, stats;
  std::string size = "160x120";
  std::string camera, light;
  float fov = 40.0f;
  bool quiet = false;
  std::string mode = "functional";
  std::string preset, tech;  // cycle mode
  std::string integrator = "mirror";
  int samples = 1, bounces = 2;
  float ao_radius = 0.1f;
  bool ao_radius_given = false;
  uint64_t seed = 1;
  std::string trace_out;  // the rays cast, as a trace
  std::string children_from = "method";
  MethodOptions method;
};

/// "WxH" with both in 1..8192.
void parse_size(const std::string& s, RenderSettings& rs) {
  const auto x = s.find('x');
  int w = 0, h = 0;
  size_t used_w = 0, used_h = 0;
  try {
    if (x != std::string::npos) {
      w = std::stoi(s.substr(0, x), &used_w);
      h = std::stoi(s.substr(x + 1), &used_h);
    }
  } catch (const std::exception&) {
    used_w = 0;
  }
  if (x == std::string::npos || used_w != x || used_h != s.size() - x - 1 || w < 1 || h < 1 ||
      w > 8192 || h > 8192)
    throw UsageError(fmt::format("option '--size': '{}' is not WxH with width and height from 1 to 8192", s));
  rs.width = w;
  rs.height = h;
}

bool is_trace_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".jsonl" || ext == ".vbt";
}

void check_render_options(const RenderArgs& a, RenderSettings& rs) {
  if (a.mode != "functional" && a.mode != "cycle")
    throw UsageError(fmt::format("option '--mode': '{}' is not available; modes: functional, cycle", a.mode));
  if (a.mode != "cycle" && (!a.preset.empty() || !a.tech.empty()))
    throw UsageError("options '--preset' and '--tech' need '--mode cycle'");
  check_preset_name(a.preset);
  if (!parse_render_integrator(a.integrator, rs.integrator))
    throw UsageError(fmt::format("option '--integrator': '{}' is not available; integrators: mirror, path, ao, glass",
                                 a.integrator));
  if (rs.integrator != RenderIntegrator::Ao && a.ao_radius_given)
    throw UsageError("option '--ao-radius' needs '--integrator ao'");
  if (rs.integrator == RenderIntegrator::Ao && !(a.ao_radius > 0.0f && std::isfinite(a.ao_radius)))
    throw UsageError(fmt::format("option '--ao-radius': {} is not a positive finite fraction of the scene's "
                                 "bounding-box diagonal", a.ao_radius));
  if ((rs.integrator == RenderIntegrator::Mirror || rs.integrator == RenderIntegrator::Glass) && a.samples != 1)
    throw UsageError(fmt::format("option '--spp': the {} integrator traces one camera ray a pixel (use "
                                 "'--integrator path' or 'ao')",
                                 a.integrator));
  if (a.samples < 1 || a.samples > kMaxRenderSamples)
    throw UsageError(fmt::format("option '--spp': {} is not 1 to {}", a.samples, kMaxRenderSamples));
  if (a.bounces < 0 || a.bounces > kMaxRenderBounces)
    throw UsageError(fmt::format("option '--bounces': {} is not 0 to {}", a.bounces, kMaxRenderBounces));
  if (a.children_from != "method" && a.children_from != "exact")
    throw UsageError(fmt::format("option '--children-from': '{}' is not method or exact", a.children_from));
  rs.children_from_exact = a.children_from == "exact";
  rs.samples = a.samples;
  rs.ao_radius = a.ao_radius;
  rs.max_bounces = a.bounces;
  rs.seed = a.seed;
}

int run_render(const RenderArgs& a) {
  RenderSettings rs;
  check_render_options(a, rs);
  parse_size(a.size, rs);
  if (!a.camera.empty()) {
    std::vector<float> v;
    if (!parse_float_list(a.camera, 6, v))
      throw UsageError(fmt::format("option '--camera': '{}' is not EX,EY,EZ,TX,TY,TZ (eye and target)", a.camera));
    for (float x : v)
      if (!(std::fabs(x) <= kMaxSceneCoordinate))
        throw UsageError(fmt::format("option '--camera': {} is beyond the supported coordinate range of +-2^126", x));
    rs.camera.eye = Vec3f{v[0], v[1], v[2]};
    rs.camera.target = Vec3f{v[3], v[4], v[5]};
    if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5])
      throw UsageError(fmt::format("option '--camera': eye and target coincide in '{}'", a.camera));
  }
  if (!(a.fov > 0.0f && a.fov < 180.0f))
    throw UsageError(fmt::format("option '--fov': {} is not in (0, 180) degrees", a.fov));
  rs.camera.vertical_fov_deg = a.fov;
  const ReplayOptions opt = resolve_method_options(a.method);
  if (!std::filesystem::exists(a.scene))
    throw std::runtime_error(fmt::format("scene '{}': no such file", a.scene));

  SceneAndBvh sb;
  std::vector<std::string> inputs = {a.scene, a.method.config};
  std::string trace_scene;  // the scene a trace names, when the input is a trace
  std::optional<std::array<float, 16>> transform;  // and its transform
  MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
  if (is_trace_path(a.scene)) {  // a trace: its scene, transform and light
    const TraceHeader header = open_trace(a.scene)->header();
    trace_scene = header.scene_path;
    inputs.push_back(trace_scene);
    sb = load_trace_scene(header, opt.bvh, &loading);
    transform = header.transform;
    if (header.light) rs.light = {RenderLight::Kind::Point, *header.light};
  } else {
    sb.scene = load_scene(a.scene, std::nullopt, &loading);
    sb.bvh = build_bvh(sb.scene, opt.bvh, &loading);
  }
  loading.finish();
  check_output_paths({{"scene", a.scene}, {"option '--config'", a.method.config},
                      {"scene of the trace", trace_scene}, {"option '--tech'", a.tech}},
                     {{"option '--out'", a.out}, {"option '--errors'", a.errors}, {"option '--stats'", a.stats},
                      {"option '--trace-out'", a.trace_out}});
  if (!a.light.empty()) {
    std::string error;
    if (!parse_render_light(a.light, rs.light, error)) throw UsageError("option '--light': " + error);
  }

  // The rays cast, as a trace that replays the frame (written whole at the end, or not at all).
  std::unique_ptr<TraceSink> cast_trace;
  if (!a.trace_out.empty()) {
    TraceHeader header;
    header.scene = scene_relative_to(trace_scene.empty() ? a.scene : trace_scene, a.trace_out);
    if (rs.light.kind == RenderLight::Kind::Point) header.light = rs.light.value;
    header.transform = transform;
    header.generator = "vbsim render";
    header.description =
        rs.children_from_exact
            ? fmt::format("reference render (children from the exact answers): {} integrator, {}x{}",
                          render_integrator_name(rs.integrator), rs.width, rs.height)
            : fmt::format("closed-loop render: {} integrator, {}x{}, method {}", render_integrator_name(rs.integrator),
                          rs.width, rs.height, opt.method.name());
    header.provenance = provenance_line(inputs);
    cast_trace = create_trace_writer(a.trace_out, header);
  }
  const std::function<void(const TraceRay&)> on_cast =
      cast_trace ? std::function<void(const TraceRay&)>([&cast_trace](const TraceRay& tr) { cast_trace->write(tr); })
                 : nullptr;

  RenderProgress progress(uint64_t(rs.width) * uint64_t(rs.height), a.quiet);
  const std::function<void(uint64_t)> on_pixel = [&progress](uint64_t finished) { progress.update(finished); };
  RenderResult r;
  nlohmann::json hw;  // cycle mode: the hw section
  std::string table;
  hw::HwConfig cfg;
  const TechFile tech = resolve_tech(a.tech);
  try {
    if (a.mode == "cycle") {
      set_systemc_quiet(a.quiet);
      cfg = hw::resolve_hw_config(a.method.config, a.preset);
      try {
        check_closed_loop_config(cfg);
      } catch (const std::invalid_argument& e) {  // a field of the config file
        throw ConfigError(fmt::format("{}: {}", a.method.config, e.what()));
      }
      hw::CycleRunOptions run;
      run.tech = &tech;
      CycleRenderResult c = render_scene_cycle(sb.scene, sb.bvh, opt, rs, cfg, run, on_cast, on_pixel);
      r = std::move(c.render);
      hw = std::move(c.run.hw);
      table = std::move(c.run.table);
    } else {
      r = render_scene(sb.scene, sb.bvh, opt, rs, on_cast, on_pixel);
    }
    progress.finish();
  } catch (const std::invalid_argument& e) {  // the camera or the exact judge refused a value: name the scene
    throw std::runtime_error(fmt::format("render of '{}': {}", a.scene, e.what()));
  }
  if (cast_trace) cast_trace->close();
  const nlohmann::json provenance = provenance_json(inputs);
  write_png_rgb(a.out, r.width, r.height, r.image, provenance.dump());
  if (!a.errors.empty()) write_png_rgb(a.errors, r.width, r.height, r.errors, provenance.dump());

  const uint64_t rays = r.stats.total().rays;
  const double rays_per_s = r.stats.wall_s > 0 ? rays / r.stats.wall_s : 0.0;
  if (!a.stats.empty()) {
    nlohmann::json config = replay_config_json(opt);
    config["scene"] = a.scene;
    config["triangles"] = sb.scene.size();
    config["size"] = {r.width, r.height};
    config["light"] = render_light_name(rs.light);
    config["integrator"] = render_integrator_name(rs.integrator);
    config["children_from"] = a.children_from;
    if (rs.integrator == RenderIntegrator::Path) {
      config["samples"] = rs.samples;
      config["bounces"] = rs.max_bounces;
      config["seed"] = rs.seed;
    }
    if (rs.integrator == RenderIntegrator::Glass) config["bounces"] = rs.max_bounces;
    if (rs.integrator == RenderIntegrator::Ao) {
      config["samples"] = rs.samples;  // occlusion rays a hit
      config["ao_radius"] = rs.ao_radius;
      config["seed"] = rs.seed;
    }
    if (a.mode == "cycle") config["hw"] = hw::hw_config_json(hw::for_tester(cfg, opt.tester));
    nlohmann::json j = r.stats.to_json(config);
    j["energy"] = operation_energy_json(tech, operation_energy(tech, opt.method, opt.tester, r.stats), rays);
    if (!hw.is_null()) j["hw"] = hw;
    j["pixels"] = {{"total", uint64_t(r.width) * uint64_t(r.height)},
                   {"acne", r.acne_pixels},
                   {"leak", r.leak_pixels}};
    j["provenance"] = provenance;
    write_output_file(a.stats, j.dump(2) + "\n", "stats file");
  }
  if (!a.quiet) {
    fmt::print("vbsim render {}  method {}  tester {}  {}x{}  light {}  ({} triangles)\n", a.scene,
               opt.method.name(), tester_name(opt.tester), r.width, r.height,
               render_light_name(rs.light), sb.scene.size());
    fmt::print("pixels: acne {}  leak {}  of {}\n", r.acne_pixels, r.leak_pixels,
               uint64_t(r.width) * uint64_t(r.height));
    fmt::print("{}{}", r.stats.summary(), table);
    fmt::print("render ({}): {} rays in {:.3f} s, {:.0f} rays/s (method, exact oracle and verdict per ray{})\n",
               a.mode, rays, r.stats.wall_s, rays_per_s, a.mode == "cycle" ? ", cycle-level model" : "");
    if (r.unscored_rays) fmt::print(stderr, "vbsim render: warning: {} rays could not be scored\n", r.unscored_rays);
  }
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "render a small image with one method, and an error image of its acne and leaks");
  cmd->add_option("scene", args->scene,
                  "scene file (ply, obj, ...) or trace (.jsonl, .vbt) whose header gives scene, "
                  "transform and light")
      ->required();
  cmd->add_option("-o,--out", args->out, "shaded image (PNG)")->required();
  cmd->add_option("--errors", args->errors, "error image (PNG): acne red, leaks blue, both yellow");
  cmd->add_option("--size", args->size, "image size WxH")->capture_default_str();
  cmd->add_option("--camera", args->camera, "eye and target EX,EY,EZ,TX,TY,TZ [frames the scene]");
  cmd->add_option("--fov", args->fov, "vertical field of view, degrees")->capture_default_str();
  cmd->add_option("--light", args->light,
                  "point:X,Y,Z or dir:X,Y,Z (towards the light) [the trace's light, else dir:-0.6,1,0.4]");
  cmd->add_option("--stats", args->stats, "write the replay statistics and pixel counts (JSON) here");
  cmd->add_option("--mode", args->mode,
                  "functional (untimed) or cycle (the rays cast by the SystemC model, in a closed loop)")
      ->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset, small, large or rtcore [the config's, else small]");
  add_tech_option(*cmd, args->tech);
  cmd->add_option("--integrator", args->integrator,
                  "mirror (a shadow ray and one mirror bounce a pixel), path (diffuse path tracing) or ao "
                  "(ambient occlusion: --spp occlusion rays at each camera hit) or glass (every surface a "
                  "dielectric: refraction and total internal reflection, up to --bounces)")
      ->capture_default_str();
  cmd->add_option("--spp", args->samples, "path: samples (paths) a pixel; ao: occlusion rays a hit; 1 to 4096")
      ->capture_default_str();
  cmd->add_option_function<float>(
         "--ao-radius",
         [args](float r) {
           args->ao_radius = r;
           args->ao_radius_given = true;
         },
         "ao: an occlusion ray's length, times the scene's bounding-box diagonal [0.1]");
  cmd->add_option("--bounces", args->bounces,
                  "path: diffuse bounces a path takes at most; glass: refractions and reflections; 0 to 16")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "path, ao: seed of the random numbers")->capture_default_str();
  cmd->add_option("--children-from", args->children_from,
                  "method (the method's answers make the next rays: a closed loop) or exact (the exact answers "
                  "do: the reference renderer, the same rays for every method)")
      ->capture_default_str();
  cmd->add_option("--trace-out", args->trace_out,
                  "write the rays the render cast, with their parents and exact answers, as a trace (.jsonl, .vbt)");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  add_method_options(*cmd, args->method, "none");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace vbsim::cli
