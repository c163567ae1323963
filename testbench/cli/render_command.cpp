// vbsim render: a small image of a scene rendered through the replay datapath
// with one self-intersection method, and an error image marking the pixels
// whose shadow or bounce rays the method got wrong (model/render/renderer.h).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "method_options.h"
#include "render/float_list.h"
#include "render/png_file.h"
#include "render/renderer.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"

namespace vbsim::cli {

namespace {

struct RenderArgs {
  std::string scene;
  std::string out, errors, stats;
  std::string size = "160x120";
  std::string camera, light;
  float fov = 40.0f;
  bool quiet = false;
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

int run_render(const RenderArgs& a) {
  RenderSettings rs;
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
  if (is_trace_path(a.scene)) {  // a trace: its scene, transform and light
    const TraceHeader header = open_trace(a.scene)->header();
    trace_scene = header.scene_path;
    inputs.push_back(trace_scene);
    sb = load_trace_scene(header, opt.bvh);
    if (header.light) rs.light = {RenderLight::Kind::Point, *header.light};
  } else {
    sb.scene = load_scene(a.scene);
    sb.bvh = build_bvh(sb.scene, opt.bvh);
  }
  check_output_paths({{"scene", a.scene}, {"option '--config'", a.method.config},
                      {"scene of the trace", trace_scene}},
                     {{"option '--out'", a.out}, {"option '--errors'", a.errors}, {"option '--stats'", a.stats}});
  if (!a.light.empty()) {
    std::string error;
    if (!parse_render_light(a.light, rs.light, error)) throw UsageError("option '--light': " + error);
  }

  RenderResult r;
  try {
    r = render_scene(sb.scene, sb.bvh, opt, rs);
  } catch (const std::invalid_argument& e) {  // the camera or the exact judge refused a value: name the scene
    throw std::runtime_error(fmt::format("render of '{}': {}", a.scene, e.what()));
  }
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
    nlohmann::json j = r.stats.to_json(config);
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
    fmt::print("{}", r.stats.summary());
    fmt::print("render: {} rays in {:.3f} s, {:.0f} rays/s (method, exact oracle and verdict per ray)\n",
               rays, r.stats.wall_s, rays_per_s);
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
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  add_method_options(*cmd, args->method, "none");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace vbsim::cli
