// --tech FILE: the technology file that prices energy and area (docs/energy.md),
// shared by `replay`, `score` and `hw`.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "energy/tech_file.h"

namespace vbsim::cli {

inline void add_tech_option(CLI::App& app, std::string& path) {
  app.add_option("--tech", path,
                 "technology file (JSON) pricing energy and area [model/energy/tech/45nm.json]");
}

/// The file `path` names, or the shipped default when it is empty; a bad file
/// is a ConfigError naming the file and field.
inline TechFile resolve_tech(const std::string& path) {
  return load_tech_file(path.empty() ? default_tech_path() : path);
}

}  // namespace vbsim::cli
