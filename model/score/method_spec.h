// Method specs: one entry of a method list (`vbsim score --methods`), a method
// or composition with optional parameters, written
//     METHOD[+METHOD...][:KEY=VALUE[:KEY=VALUE...]]
// e.g. `validity-bit:vb-eps-mode=fixed:vb-eps=1e-4` or `tmin:tmin-eps=1e-3`.
// KEYs are the long options of `vbsim replay` without their dashes (tmin-eps,
// offset-normal-eps, offset-direction-eps, adaptive-origin, adaptive-float-scale,
// adaptive-int-scale, vb-policy, vb-eps-mode, vb-eps, vb-guard-bits,
// vb-min-exponent, vb-component-scale, vb-tests, hitpoint); vb-tests takes its
// tests joined by '+' (`vb-tests=normal+ray+component`). A list is entries
// separated by ','. Every other parameter keeps its default.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "replay/replay_options.h"

namespace vbsim {

/// The entry that scores the trace's reference answers (the capturing
/// renderer's own) instead of a method: a capture's `renderer` row.
constexpr const char* kRendererMethod = "renderer";

struct MethodSpec {
  std::string label;  ///< the entry as written: the row label of a score table
  ReplayOptions options;
};

/// One entry as the configuration fields it sets (`method` and its KEYs'
/// fields, as in a config file), not yet validated; throws ConfigError naming
/// the entry on a malformed KEY=VALUE or an unknown key.
nlohmann::json method_spec_json(const std::string& entry);

/// Parses one entry; throws ConfigError naming the entry and the bad key or value.
MethodSpec parse_method_spec(const std::string& entry);

/// Parses a ','-separated list of entries (empty entries are errors).
std::vector<MethodSpec> parse_method_list(const std::string& list);


/// The methods `vbsim score` compares when no list is given: every method and
/// the compositions and parameter variants renderers and the patent use.
const std::vector<std::string>& default_score_methods();
/// The same joined by ',', as --methods takes them.
std::string default_score_method_list();

}  // namespace vbsim
