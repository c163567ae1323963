// Replay configuration file: the JSON layer (every field optional, the same
// names as the `config` object echoed into stats files) and its validation into
// ReplayOptions. Errors name the file and the field.
#pragma once
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "replay/replay_options.h"

namespace vbsim {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Applies the fields present in `j` onto `opt` (absent fields keep their
/// values). Throws ConfigError "FILE: field 'a.b': reason" on a wrong type,
/// an unknown name or an out-of-range value; unknown fields are errors too.
/// The fields a stats file's config derives or records (bits_per_ray,
/// cost_ops, trace, scene, triangles, size, light) are accepted and ignored.
void apply_replay_config(const nlohmann::json& j, const std::string& file, ReplayOptions& opt);

/// Reads a JSON config file; ConfigError when it cannot be read or parsed. A
/// stats file (an object with a `config` object) gives its `config` block, so a
/// run's statistics can configure the next run.
nlohmann::json read_config_json(const std::string& path);

/// Reads and applies a JSON config file.
void load_replay_config(const std::string& path, ReplayOptions& opt);

/// Checks ranges of an assembled configuration (also after command-line
/// overrides); throws ConfigError naming the field.
void validate_replay_options(const ReplayOptions& opt, const std::string& origin);

}  // namespace vbsim
