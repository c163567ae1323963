// Command-line options of the self-intersection method, tester and hit point,
// shared by `replay`, `bench` and `render`. Command-line values override a
// --config file.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "replay/replay_options.h"

namespace vbsim::cli {

struct MethodOptions {
  std::string default_method = "none";  ///< used when neither --method nor --config names one
  std::string method, tester, hitpoint;  ///< empty: not given
  std::string config;
  // Parameters: set only when given, so they override the config file. The
  // float32 fields are read as double and checked as the configuration field
  // they set is (a value that overflows or rounds to 0 in float32 is refused).
  std::optional<double> tmin_eps, offset_normal_eps, offset_direction_eps;
  std::optional<double> adaptive_origin, adaptive_float_scale, adaptive_int_scale;
  std::optional<std::string> vb_policy, vb_eps_mode, vb_tests;
  std::optional<double> vb_eps, vb_component_scale;
  std::optional<int> vb_guard_bits, vb_min_exponent;
  std::optional<std::string> bvh_builder, bvh_quality;
  std::optional<int> bvh_leaf_size, bvh_width;
  std::optional<double> bvh_traversal_cost;
  std::optional<int> bvh_sah_block;
  int64_t parent_window = ParentRayStore::kDefaultWindow;  ///< --parent-window
  bool score_incomplete = false;  ///< --score-incomplete
};

/// Registers the options on `app`, storing into `o`.
void add_method_options(CLI::App& app, MethodOptions& o, const std::string& default_method);

/// The effective ReplayOptions: defaults, then --config, then the options given
/// (--method may carry `vbsim score`'s METHOD:KEY=VALUE parameters). Throws
/// ConfigError naming the file and field for a bad --config file (a runtime
/// error), UsageError naming the option for a bad command-line value.
ReplayOptions resolve_method_options(const MethodOptions& o);

/// Registers --score-incomplete (score rays marked `incomplete`) on `cmd`.
void add_score_incomplete_option(CLI::App& cmd, bool& score_incomplete);

/// A `--testers` comma list; throws UsageError naming an unknown tester or an empty list.
std::vector<TesterKind> parse_tester_list(const std::string& list, const std::string& option = "--testers");

/// Throws UsageError unless `preset` is empty or a hardware preset's name.
void check_preset_name(const std::string& preset);

}  // namespace vbsim::cli
