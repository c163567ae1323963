// The output directory of `vbsim gen`: gen owns only the files it wrote there,
// listed in DIR/.vbsim-gen.json. Before writing, it removes the files an
// earlier gen listed, and it refuses a directory holding trace files (.jsonl,
// .vbt) it did not write, since `vbsim score DIR` would include them. Other
// files (notes, markers) are left alone. The list is written before the cases
// with "complete": false and rewritten with true at the end, so an
// interrupted gen is cleaned up by the next one and never looks finished.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vbsim::cli {

constexpr const char* kGenManifestName = ".vbsim-gen.json";

/// Checks `dir` (may not exist yet) and removes what an earlier gen wrote there.
/// Throws std::runtime_error naming the foreign trace files.
void prepare_gen_directory(const std::string& dir);

/// Writes the list of `files` (paths inside `dir`) with `provenance`.
void write_gen_manifest(const std::string& dir, const std::vector<std::string>& files, bool complete,
                        const nlohmann::json& provenance);

}  // namespace vbsim::cli
