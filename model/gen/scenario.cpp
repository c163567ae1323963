#include "gen/scenario.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "exact/expected_answers.h"
#include "gen/coplanar_scenario.h"
#include "gen/corner_scenario.h"
#include "gen/crevice_scenario.h"
#include "gen/far_instance_scenario.h"
#include "gen/grazing_scenario.h"
#include "gen/layers_scenario.h"
#include "gen/paths_scenario.h"
#include "gen/random_triangles_scenario.h"
#include "gen/refraction_scenario.h"
#include "gen/shared_edges_scenario.h"
#include "gen/terminator_scenario.h"
#include "scene/bvh.h"
#include "scene/ply_scene_writer.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim {

namespace fs = std::filesystem;

const std::string* ScenarioSettings::find(const std::string& key) const {
  read_.insert(key);
  const auto it = values_.find(key);
  return it == values_.end() ? nullptr : &it->second;
}

ScenarioSettings::ScenarioSettings(int64_t rays, uint64_t seed, std::map<std::string, std::string> values)
    : rays_(rays), seed_(seed), values_(std::move(values)) {
  if (rays_ <= 0) throw std::runtime_error("option '--rays': must be > 0");
}

double ScenarioSettings::number(const std::string& key, double fallback) const {
  const std::string* v = find(key);
  if (!v) return fallback;
  char* end = nullptr;
  errno = 0;
  const double d = std::strtod(v->c_str(), &end);
  if (v->empty() || *end != '\0' || errno != 0 || !std::isfinite(d))
    throw std::runtime_error(fmt::format("option '--set {}={}': not a finite number", key, *v));
  return d;
}

int64_t ScenarioSettings::integer(const std::string& key, int64_t fallback) const {
  const std::string* v = find(key);
  if (!v) return fallback;
  char* end = nullptr;
  errno = 0;
  const long long i = std::strtoll(v->c_str(), &end, 10);
  if (v->empty() || *end != '\0' || errno != 0)
    throw std::runtime_error(fmt::format("option '--set {}={}': not an integer", key, *v));
  return i;
}

std::string ScenarioSettings::text(const std::string& key, const std::string& fallback) const {
  const std::string* v = find(key);
  return v ? *v : fallback;
}

void ScenarioSettings::check_all_read(const std::string& scenario) const {
  for (const auto& [key, value] : values_)
    if (!read_.count(key))
      throw std::runtime_error(fmt::format("option '--set {}': scenario '{}' has no such setting", key, scenario));
}

const std::vector<Scenario>& scenarios() {
  static const std::vector<Scenario> all = {
      {"paths", "multi-bounce camera paths over a mesh (set scene=FILE, depth=N, ior=X, hitpoint=ray|barycentric|both)", generate_paths_scenario},
      {"random-triangles", "isolated random triangles, Ray Tracing Gems Figure 6-7, pbrt-v4 Reintersect with random signs, or pbrt-v4 Reintersect as pbrt-v4 runs it (set protocol=rtg|pbrt|pbrt-v4)", generate_random_triangles_scenario},
      {"grazing", "children leaving a tessellated plane, cylinder or bowl at 1e-6 rad to 10 degrees", generate_grazing_scenario},
      {"shared-edges", "spawn points ulps from shared edges of flat, convex and concave sheets, grazing children", generate_shared_edges_scenario},
      {"crevice", "concave wedges of 1 to 90 degrees, spawn points near the crease", generate_crevice_scenario},
      {"corner", "inside box corner: children spawned a tiny gap from the wall they head into", generate_corner_scenario},
      {"layers", "surfaces closer than an offset: parallel squares, nested spheres, a sphere on a plane (set separation=LIST, offset=X, z=X, shell=X, segments=N, ior=X, hitpoint=...)", generate_layers_scenario},
      {"coplanar", "duplicated, reversed and overlapping coplanar triangles: ties and in-plane rays (set z=X, hitpoint=...)", generate_coplanar_scenario},
      {"far-instance", "paths over a mesh translated 2^k away by the header's float32 transform (set k=LIST, scene=FILE, depth=N, ior=X, hitpoint=...)", generate_far_instance_scenario},
      {"refraction", "closed glass sphere and box: refraction and total-internal-reflection paths inside (set objects=sphere,box, ior=X, bounces=N, segments=N, hitpoint=...)", generate_refraction_scenario},
      {"terminator", "shadow rays from low-poly spheres with vertex normals near the terminator (set segments=LIST, band=F, hitpoint=ray|barycentric|both)", generate_terminator_scenario},
  };
  return all;
}

const Scenario* find_scenario(const std::string& name) {
  for (const Scenario& s : scenarios())
    if (name == s.name) return &s;
  return nullptr;
}

std::string write_scenario_case(const ScenarioCase& c, const std::string& dir, const std::string& generator,
                                const CaseWriteOptions& options) {
  fs::create_directories(dir);
  const std::string trace_path = (fs::path(dir) / (c.name + ".jsonl")).string();
  std::string scene_path = c.scene_file;
  if (scene_path.empty()) {
    scene_path = (fs::path(dir) / (c.name + ".ply")).string();
    write_ply_scene(scene_path, c.triangles, c.normals,
                    options.provenance.empty() ? "" : "vbsim-provenance " + options.provenance);
    if (options.written) options.written->push_back(scene_path);
  }
  // The oracle sees the scene exactly as a replay will load it.
  const Scene scene = load_scene(scene_path, c.transform);
  const Bvh bvh = build_bvh(scene);
  std::vector<TraceRay> rays = c.rays;
  ExpectationFiller filler(scene, bvh);  // parents before children, as in a replay
  uint64_t unreported = 0;
  for (TraceRay& r : rays) {
    filler.fill(r);
    if (options.on_rays && ++unreported == kOracleProgressRays) {
      options.on_rays(unreported);
      unreported = 0;
    }
  }
  if (options.on_rays && unreported) options.on_rays(unreported);

  TraceHeader h;
  h.scene = scene_relative_to(scene_path, trace_path);
  h.light = c.light;
  h.transform = c.transform;
  h.generator = generator;
  h.description = c.description;
  h.provenance = options.provenance;
  auto sink = create_trace_writer(trace_path, h);
  for (const TraceRay& r : rays) sink->write(r);
  sink->close();
  if (options.written) options.written->push_back(trace_path);
  return trace_path;
}

}  // namespace vbsim
