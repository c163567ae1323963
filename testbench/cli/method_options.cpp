#include "method_options.h"

#include <fmt/format.h>

#include <sstream>

#include "commands.h"
#include "exit_codes.h"
#include "hw/hw_config.h"
#include "replay/replay_config.h"
#include "score/method_spec.h"

namespace vbsim::cli {

void add_method_options(CLI::App& app, MethodOptions& o, const std::string& default_method) {
  o.default_method = default_method;
  app.add_option("--method,-m", o.method,
                 "self-intersection method(s), joined by '+': none, tmin, primid, offset-normal, "
                 "offset-direction, offset-adaptive, offset-errbound, validity-bit, sign-only, "
                 "shading-position, shading-position-always, reverse-shadow; parameters may follow "
                 "as in vbsim score, METHOD:KEY=VALUE... (validity-bit:vb-eps-mode=fixed:vb-eps=1e-4) [" +
                     default_method + "]");
  app.add_option("--tester", o.tester, "ray/triangle tester: three-half-plane, moller-trumbore or pbrt-watertight (three-half-plane with pbrt-v4's conservative t check) [three-half-plane]");
  app.add_option("--hitpoint", o.hitpoint,
                 "child origin before the method acts: given (the trace's o), ray (parent o + t d) "
                 "or barycentric (parent_uv) [given]");
  app.add_option("--config", o.config, "JSON configuration file (fields as in the stats 'config')");
  app.add_option("--tmin-eps", o.tmin_eps, "tmin: distance in scene units (tmin = eps/|d|) [1e-4]");
  app.add_option("--offset-normal-eps", o.offset_normal_eps, "offset-normal: scene units [1e-4]");
  app.add_option("--offset-direction-eps", o.offset_direction_eps, "offset-direction: scene units [1e-4]");
  app.add_option("--adaptive-origin", o.adaptive_origin, "offset-adaptive: origin() [1/32]");
  app.add_option("--adaptive-float-scale", o.adaptive_float_scale, "offset-adaptive: float_scale() [1/65536]");
  app.add_option("--adaptive-int-scale", o.adaptive_int_scale, "offset-adaptive: int_scale() [256]");
  app.add_option("--vb-policy", o.vb_policy, "validity-bit: all, vote or sign-only [all]");
  app.add_option("--vb-eps-mode", o.vb_eps_mode, "validity-bit: fixed or exponent [exponent]");
  app.add_option("--vb-eps", o.vb_eps, "validity-bit: fixed epsilon, scene units [1e-4]");
  app.add_option("--vb-guard-bits", o.vb_guard_bits, "validity-bit: exponent guard band, bits [5]");
  app.add_option("--vb-min-exponent", o.vb_min_exponent, "validity-bit: minimum biased exponent [110]");
  app.add_option("--vb-tests", o.vb_tests, "validity-bit: epsilon tests, comma list of normal,ray,component [normal,ray]");
  app.add_option("--vb-component-scale", o.vb_component_scale, "validity-bit: component test multiplier [0.577]");
  app.add_option("--bvh-builder", o.bvh_builder,
                 "the BVH's builder: embree (rtcBuildBVH, of --bvh-quality) or sweep-sah (vbsim's full-sweep SAH; "
                 "no quality); hits do not depend on it, the work does [embree]");
  app.add_option("--bvh-quality", o.bvh_quality,
                 "the BVH's build: Embree's low (Morton), medium or high (binned SAH) quality; hits do not depend "
                 "on it, the work does [high]");
  app.add_option("--bvh-leaf-size", o.bvh_leaf_size,
                 fmt::format("the BVH's largest leaf, 1 to {} triangles [4]", kMaxBvhLeafSize));
  app.add_option("--bvh-width", o.bvh_width,
                 "children per BVH node the traversal reads: 2, or 4 or 8 (the binary tree collapsed, every child "
                 "box of a node tested in one operation); hits do not depend on it, the work does [2]");
  app.add_option("--bvh-traversal-cost", o.bvh_traversal_cost,
                 "the BVH builder's cost of a node step against a triangle test's 1: larger gives larger leaves [1]");
  app.add_option("--bvh-sah-block", o.bvh_sah_block,
                 "triangles the BVH builder's SAH prices as one test (1, 2, 4, 8 or 16): 4 builds leaves for a "
                 "four-lane triangle test, as Embree prices its Triangle4 leaves; 1 for the model's triangle unit, "
                 "one triangle an operation [1]");
  add_parent_window_option(app, o.parent_window);
  add_score_incomplete_option(app, o.score_incomplete);
}

void add_score_incomplete_option(CLI::App& cmd, bool& score_incomplete) {
  cmd.add_flag("--score-incomplete", score_incomplete,
               "also score rays marked `incomplete` (their renderer's answer involved geometry or filter functions "
               "the trace does not hold); by default they are replayed but left unscored");
}

void add_parent_window_option(CLI::App& cmd, int64_t& window, const std::string& names) {
  cmd.add_option(names, window,
                 "rays kept for children to look their parent up in (about 40 bytes each); a child whose parent "
                 "lies further back is an error")
      ->check(CLI::Range(int64_t{1}, ParentRayStore::kMaxWindow))
      ->capture_default_str();
}

namespace {

/// The float32 parameters: each option and the configuration field it sets.
struct FloatParameter {
  const char* option;
  std::optional<double> MethodOptions::*value;
  const char* field;     ///< top-level field, or the block of `subfield`
  const char* subfield;  ///< nullptr: `field` itself
};
constexpr FloatParameter kFloatParameters[] = {
    {"--tmin-eps", &MethodOptions::tmin_eps, "tmin_eps", nullptr},
    {"--offset-normal-eps", &MethodOptions::offset_normal_eps, "offset_normal_eps", nullptr},
    {"--offset-direction-eps", &MethodOptions::offset_direction_eps, "offset_direction_eps", nullptr},
    {"--adaptive-origin", &MethodOptions::adaptive_origin, "adaptive", "origin"},
    {"--adaptive-float-scale", &MethodOptions::adaptive_float_scale, "adaptive", "float_scale"},
    {"--adaptive-int-scale", &MethodOptions::adaptive_int_scale, "adaptive", "int_scale"},
    {"--vb-eps", &MethodOptions::vb_eps, "validity_bit", "eps"},
    {"--vb-component-scale", &MethodOptions::vb_component_scale, "validity_bit", "component_scale"},
    {"--bvh-traversal-cost", &MethodOptions::bvh_traversal_cost, "bvh", "traversal_cost"},
};

/// Applies the options given on the command line onto `opt` (after --config).
/// `--method` may carry KEY=VALUE parameters as `vbsim score`'s entries do.
void apply_command_line(const MethodOptions& o, ReplayOptions& opt) {
  // empty when only --config is given
  nlohmann::json j = o.method.empty() ? nlohmann::json::object() : method_spec_json(o.method);
  if (o.method.empty() && o.config.empty()) j["method"] = o.default_method;
  if (!o.tester.empty()) j["tester"] = o.tester;
  if (!o.hitpoint.empty()) j["hitpoint"] = o.hitpoint;
  for (const FloatParameter& p : kFloatParameters) {
    const std::optional<double>& v = o.*p.value;
    if (!v) continue;
    nlohmann::json one = nlohmann::json::object();
    nlohmann::json& slot = p.subfield ? one[p.field][p.subfield] : one[p.field];
    slot = *v;
    // Alone first, so that an error names the option: the checks of a
    // configuration file's field, float32 range and rounding included.
    ReplayOptions scratch;
    apply_replay_config(one, fmt::format("option '{}'", p.option), scratch);
    if (p.subfield)
      j[p.field][p.subfield] = *v;
    else
      j[p.field] = *v;
  }
  if (o.vb_policy) j["validity_bit"]["policy"] = *o.vb_policy;
  if (o.vb_eps_mode) j["validity_bit"]["eps_mode"] = *o.vb_eps_mode;
  if (o.vb_guard_bits) j["validity_bit"]["guard_bits"] = *o.vb_guard_bits;
  if (o.vb_min_exponent) j["validity_bit"]["min_exponent"] = *o.vb_min_exponent;
  if (o.bvh_builder) j["bvh"]["builder"] = *o.bvh_builder;
  if (o.bvh_quality) j["bvh"]["quality"] = *o.bvh_quality;
  if (o.bvh_leaf_size) j["bvh"]["max_leaf_size"] = *o.bvh_leaf_size;
  if (o.bvh_sah_block) j["bvh"]["sah_block_size"] = *o.bvh_sah_block;
  if (o.bvh_width) j["bvh"]["width"] = *o.bvh_width;
  if (o.vb_tests) {
    nlohmann::json tests = {{"normal", false}, {"ray", false}, {"component", false}};
    std::stringstream in(*o.vb_tests);
    std::string t;
    while (std::getline(in, t, ',')) {
      if (!tests.contains(t))
        throw ConfigError("option '--vb-tests': unknown test '" + t + "'; tests: normal, ray, component");
      tests[t] = true;
    }
    j["validity_bit"]["tests"] = tests;
  }
  apply_replay_config(j, "command line", opt);
}

}  // namespace

ReplayOptions resolve_method_options(const MethodOptions& o) {
  ReplayOptions opt;
  if (!o.config.empty()) load_replay_config(o.config, opt);  // a bad file: a runtime error
  try {
    apply_command_line(o, opt);
  } catch (const ConfigError& e) {
    throw UsageError(e.what());
  }
  opt.parent_window = o.parent_window;
  opt.score_incomplete = o.score_incomplete;
  return opt;
}

std::vector<TesterKind> parse_tester_list(const std::string& list, const std::string& option) {
  std::vector<TesterKind> out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    TesterKind t;
    if (!parse_tester(name, t))
      throw UsageError(fmt::format(
          "option '{}': unknown tester '{}'; testers: three-half-plane, moller-trumbore, pbrt-watertight", option,
          name));
    out.push_back(t);
  }
  if (out.empty()) throw UsageError(fmt::format("option '{}': empty list", option));
  return out;
}

void check_preset_name(const std::string& preset) {
  if (preset.empty()) return;
  std::string names;
  for (const std::string& n : hw::preset_names()) {
    if (n == preset) return;
    names += (names.empty() ? "" : ", ") + n;
  }
  throw UsageError(fmt::format("option '--preset': unknown preset '{}' (presets: {})", preset, names));
}

}  // namespace vbsim::cli
