#include "replay/replay_config.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include "io/json_document.h"
#include "replay/config_fields.h"
#include "scene/bvh_precision.h"

namespace vbsim {

namespace {

using config_fields::fail;
using config_fields::Fields;

/// "none, tmin, ..." and how to combine them, for the error on an unknown method.
std::string method_choices() {
  std::string s;
  for (const std::string& n : method_names()) s += (s.empty() ? "" : ", ") + n;
  return s + " (or several joined by '+')";
}

}  // namespace

void apply_replay_config(const nlohmann::json& j, const std::string& file, ReplayOptions& opt) {
  SelfIntersectionMethod& m = opt.method;
  Fields f(j, file, "");
  f.name(
      "method",
      [&](const std::string& s) {
        SelfIntersectionMethod fresh = m;
        fresh.tmin = fresh.primid = fresh.offset_normal = fresh.offset_direction = false;
        fresh.offset_adaptive = fresh.offset_errbound = fresh.validity_bit = false;
        fresh.shading_position = fresh.shading_position_always = fresh.reverse_shadow = false;
        std::string err;
        if (!parse_method(s, fresh, err)) return false;
        m = fresh;
        return true;
      },
      method_choices());
  f.name("tester", [&](const std::string& s) { return parse_tester(s, opt.tester); },
         "three-half-plane, moller-trumbore, pbrt-watertight");
  f.name("hitpoint", [&](const std::string& s) { return parse_hit_point_mode(s, opt.hit_point); },
         "given, ray, barycentric");
  f.boolean("shadow_any_hit", opt.any_hit_for_shadow);
  if (const auto* b = f.get("bvh")) {
    Fields fb(*b, file, "bvh");
    fb.name("builder", [&](const std::string& s) { return parse_bvh_builder(s, opt.bvh.builder); },
            "embree, sweep-sah");
    fb.name("quality", [&](const std::string& s) { return parse_bvh_quality(s, opt.bvh.quality); },
            "low, medium, high");
    fb.integer("max_leaf_size", opt.bvh.max_leaf_size);
    fb.number("traversal_cost", opt.bvh.traversal_cost);
    fb.integer("sah_block_size", opt.bvh.sah_block_size);
    fb.integer("width", opt.bvh.width);
    if (opt.bvh.width != 2 && opt.bvh.width != 4 && opt.bvh.width != 8)
      fail(file, "bvh.width", fmt::format("must be 2, 4 or 8, got {}", opt.bvh.width));
    if (!(opt.bvh.traversal_cost > 0 && opt.bvh.traversal_cost <= kMaxBvhTraversalCost))
      fail(file, "bvh.traversal_cost",
           fmt::format("must be in (0, {}], got {}", kMaxBvhTraversalCost, opt.bvh.traversal_cost));
    if (!valid_sah_block_size(opt.bvh.sah_block_size))
      fail(file, "bvh.sah_block_size",
           fmt::format("must be 1, 2, 4, 8 or 16 (a power of two up to {}), got {}", kMaxBvhSahBlockSize,
                       opt.bvh.sah_block_size));
    if (opt.bvh.max_leaf_size < 1 || opt.bvh.max_leaf_size > kMaxBvhLeafSize)
      fail(file, "bvh.max_leaf_size", fmt::format("must be 1 to {}, got {}", kMaxBvhLeafSize, opt.bvh.max_leaf_size));
    if (const auto* lp = fb.get("low_precision")) {  // present: nodes of two precisions (scene/bvh_precision.h)
      Fields fl(*lp, file, "bvh.low_precision");
      BvhPrecisionMarking& mark = opt.bvh.low_precision;
      mark.enabled = true;
      fl.integer("mantissa_bits", mark.mantissa_bits);
      fl.number("t_trav_high", mark.t_trav_high);
      fl.number("t_trav_low", mark.t_trav_low);
      fl.boolean("narrow_arithmetic", mark.narrow_arithmetic);
      if (opt.bvh.width != 2)
        fail(file, "bvh.low_precision", fmt::format("takes bvh.width 2 (nodes of two precisions are binary), got {}",
                                                    opt.bvh.width));
      try {
        check_bvh_precision(mark);
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();  // "bvh.low_precision.FIELD must be ..."
        const size_t space = what.find(' ');
        fail(file, what.substr(0, space), what.substr(space + 1));
      }
    }
  }
  f.number("tmin_eps", m.tmin_eps);
  f.number("offset_normal_eps", m.offset_normal_eps);
  f.number("offset_direction_eps", m.offset_direction_eps);
  f.get("bits_per_ray");  // derived; accepted so a stats file's config can be fed back
  f.get("cost_ops");      // derived, likewise
  f.get("hw");  // the cycle-level model's settings: read by hw/hw_config.h in cycle mode
  // What a stats file's config records about the run's inputs: accepted so the
  // block can be fed back, and ignored (the command line names the inputs).
  for (const char* descriptive :
       {"trace", "scene", "triangles", "size", "light", "integrator", "children_from", "samples", "bounces", "seed"})
    f.get(descriptive);
  if (const auto* a = f.get("adaptive")) {
    Fields fa(*a, file, "adaptive");
    fa.number("origin", m.adaptive.origin);
    fa.number("float_scale", m.adaptive.float_scale);
    fa.number("int_scale", m.adaptive.int_scale);
  }
  if (const auto* vb = f.get("validity_bit")) {
    AvoidanceConfig& c = m.avoidance;
    Fields fv(*vb, file, "validity_bit");
    fv.name("policy", [&](const std::string& s) { return parse_avoidance_policy(s, c.policy); },
            "all, vote, sign-only");
    fv.name("eps_mode", [&](const std::string& s) { return parse_epsilon_mode(s, c.eps_mode); },
            "fixed, exponent");
    fv.number("eps", c.eps);
    fv.integer("guard_bits", c.guard_bits);
    fv.integer("min_exponent", c.min_exponent);
    fv.number("component_scale", c.component_scale);
    if (const auto* t = fv.get("tests")) {
      Fields ft(*t, file, "validity_bit.tests");
      ft.boolean("normal", c.test_normal);
      ft.boolean("ray", c.test_ray);
      ft.boolean("component", c.test_component);
    }
    if (const auto* w = fv.get("weights")) {
      Fields fw(*w, file, "validity_bit.weights");
      fw.integer("normal", c.weight_normal);
      fw.integer("ray", c.weight_ray);
      fw.integer("component", c.weight_component);
    }
  }
  validate_replay_options(opt, file);
}

nlohmann::json read_config_json(const std::string& path) {
  // A pipe (/dev/stdin, <(...)) can be read once: its content is kept for the
  // second reader of the same run (the method and the hw settings).
  static std::mutex mutex;
  static std::map<std::string, nlohmann::json> pipes;
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(path, ec);
  const std::lock_guard<std::mutex> lock(mutex);
  if (!regular) {
    const auto it = pipes.find(path);
    if (it != pipes.end()) return it->second;
  }
  nlohmann::json j;
  try {
    // At most kMaxJsonDocumentBytes; bounded nesting, no repeated key, numbers
    // within double (io/json_document.h).
    j = parse_json_document(read_json_text(path), path);
  } catch (const JsonDocumentError& e) {
    throw ConfigError(e.what());
  }
  // A whole stats file: its `config` block is the configuration.
  if (j.is_object() && j.contains("config") && j["config"].is_object()) j = j["config"];
  if (!regular) pipes[path] = j;
  return j;
}

void load_replay_config(const std::string& path, ReplayOptions& opt) {
  apply_replay_config(read_config_json(path), path, opt);
}

void validate_replay_options(const ReplayOptions& opt, const std::string& origin) {
  const SelfIntersectionMethod& m = opt.method;
  const AvoidanceConfig& a = m.avoidance;
  if (!(m.tmin_eps >= 0)) fail(origin, "tmin_eps", "must be >= 0");
  if (!(m.offset_normal_eps >= 0)) fail(origin, "offset_normal_eps", "must be >= 0");
  if (!(m.offset_direction_eps >= 0)) fail(origin, "offset_direction_eps", "must be >= 0");
  if (!(m.adaptive.origin >= 0)) fail(origin, "adaptive.origin", "must be >= 0");
  if (!(m.adaptive.float_scale >= 0)) fail(origin, "adaptive.float_scale", "must be >= 0");
  if (!(m.adaptive.int_scale >= 0 && m.adaptive.int_scale < 1e6f))
    fail(origin, "adaptive.int_scale", "must be in [0, 1e6)");
  if (!(a.eps >= 0)) fail(origin, "validity_bit.eps", "must be >= 0");
  if (a.guard_bits < 0 || a.guard_bits > 23) fail(origin, "validity_bit.guard_bits", "must be in 0..23");
  if (a.min_exponent < 1 || a.min_exponent > 254)
    fail(origin, "validity_bit.min_exponent", "must be a biased float32 exponent in 1..254");
  if (!(a.component_scale > 0)) fail(origin, "validity_bit.component_scale", "must be > 0");
  if (a.weight_normal < 0 || a.weight_ray < 0 || a.weight_component < 0)
    fail(origin, "validity_bit.weights", "must be >= 0");
}

}  // namespace vbsim
