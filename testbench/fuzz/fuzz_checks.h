// The checks of every fuzz target, on a file: shared by the libFuzzer
// programs (fuzz_*.cpp, which write each input to a file first) and by the
// suite's replay of the seed corpora and of every input a fuzzer ever broke
// (testbench/unit/fuzz_regressions_test.cpp).
// Contract: an input is either read or refused with the reader's own error
// type (TraceError, ConfigError, SceneError); any other exception escapes
// (libFuzzer reports it as a crash, the suite as a failed test), and a broken
// invariant calls fuzz_finding(), which aborts.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hw/hw_config.h"
#include "replay/replay_config.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/binary_trace_reader.h"
#include "trace/rtcore_ray_import.h"
#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace/trace_validation.h"

namespace vbsim::fuzz {

/// A broken invariant: prints `what` and aborts.
[[noreturn]] inline void fuzz_finding(const std::string& what) {
  std::fprintf(stderr, "vbsim fuzz finding: %s\n", what.c_str());
  std::abort();
}

/// Every ray a reader yields passes the format's rules again (scene of `triangles`, -1: unknown).
inline void check_ray(const TraceRay& ray, int32_t triangles) {
  TraceFieldProblem problem;
  if (!check_trace_ray(ray, triangles, problem)) fuzz_finding("a ray the reader yields breaks rule " + problem.field);
}

/// The text trace reader, with a scene of 16 triangles for the index checks;
/// every ray it yields also writes as a line.
inline void check_text_trace(const std::string& path) {
  try {
    TextTraceReader reader(path);
    reader.set_triangle_count(16);
    TraceRay ray;
    while (reader.next(ray)) {
      check_ray(ray, 16);
      fmt::memory_buffer line;
      append_trace_ray_json(line, ray);
      if (line.size() == 0) fuzz_finding("an empty ray line");
    }
  } catch (const TraceError&) {
  }
}

/// The binary trace reader: every record read, as many rays as records.
inline void check_binary_trace(const std::string& path) {
  try {
    BinaryTraceReader reader(path);
    reader.set_triangle_count(16);
    TraceRay ray;
    int64_t rays = 0;
    while (reader.next(ray)) {
      check_ray(ray, 16);
      ++rays;
    }
    if (reader.record_count() >= 0 && rays != reader.record_count()) fuzz_finding("fewer rays than records");
  } catch (const TraceError&) {
  }
}

/// The rtcore-systemc ray import.
inline void check_rtcore_rays(const std::string& path) {
  try {
    RtcoreRayReader reader(path, "mesh.ply");
    TraceRay ray;
    while (reader.next(ray)) check_ray(ray, -1);
  } catch (const TraceError&) {
  }
}

/// The configuration reader (replay fields and the `hw` object). An accepted
/// configuration echoes as JSON that it accepts again with the same result:
/// no value may wrap, overflow or turn into null on the way.
inline void check_config(const std::string& path) {
  nlohmann::json j;
  try {
    j = read_config_json(path);
  } catch (const ConfigError&) {
    return;
  }
  try {
    ReplayOptions opt;
    apply_replay_config(j, path, opt);
    const nlohmann::json echo = replay_config_json(opt);
    ReplayOptions again;
    try {
      apply_replay_config(echo, "echo", again);
    } catch (const ConfigError& e) {
      fuzz_finding(std::string("the echoed configuration is refused: ") + e.what());
    }
    if (replay_config_json(again) != echo) fuzz_finding("the echoed configuration reads back differently");
    if (j.is_object() && j.contains("hw")) {
      hw::HwConfig cfg = hw::load_preset("small", "fuzz");
      hw::apply_hw_config(j["hw"], path, cfg);
      const nlohmann::json hw_echo = hw::hw_config_json(cfg);
      hw::HwConfig cfg_again = hw::load_preset("small", "fuzz");
      try {
        hw::apply_hw_config(hw_echo, "echo", cfg_again);
      } catch (const ConfigError& e) {
        fuzz_finding(std::string("the echoed hw configuration is refused: ") + e.what());
      }
      if (hw::hw_config_json(cfg_again) != hw_echo) fuzz_finding("the echoed hw configuration reads back differently");
    }
  } catch (const ConfigError&) {
  }
}

/// The scene loading path (the format from the file name: .ply or .obj), then
/// the BVH build: a scene is read whole and finite, or refused.
inline void check_scene(const std::string& path) {
  try {
    const Scene scene = load_scene(path);
    if (scene.size() <= 0) fuzz_finding("a scene without triangles was accepted");
    for (const Triangle& t : scene.triangles)
      for (const Vec3f& v : {t.v0, t.v1, t.v2})
        for (int axis = 0; axis < 3; ++axis)
          if (!(std::fabs(v[axis]) <= kMaxSceneCoordinate)) fuzz_finding("a vertex beyond the supported range");
    const Bvh bvh = build_bvh(scene);
    if (bvh.tris.size() != static_cast<size_t>(scene.size())) fuzz_finding("the BVH lost triangles");
  } catch (const SceneError&) {
  }
}

}  // namespace vbsim::fuzz
