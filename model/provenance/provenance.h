// Provenance of an output file: which vbsim (version and git revision, fixed at
// build time), which command line, and the SHA-256 of every input file, so a
// result can be traced to what made it. Every file vbsim writes records it:
// JSON outputs as a top-level "provenance" object, traces in their header's
// "provenance" field, PLY scenes as a comment line, PNG images as a tEXt chunk,
// markdown as an HTML comment, VCD files as a $comment.
//
//   {"program": "vbsim", "version": "0.1.0", "revision": "fb7af8c...",
//    "command": ["vbsim", "replay", ...],
//    "inputs": [{"path": "traces/bunny/paths.jsonl", "bytes": 123, "sha256": "..."}]}
//
// Not thread-safe: call from the main thread (checksums are cached per path).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vbsim {

/// The version ("0.1.0") and revision (`git describe --always --dirty`, or
/// "unknown" for a build without git history) this binary was built from.
const char* vbsim_version();
const char* vbsim_revision();
/// "vbsim 0.1.0 (revision ...)", the text of `vbsim --version`.
std::string vbsim_version_line();

/// Records the process's command line (main() calls it once).
void set_command_line(int argc, const char* const* argv);
const std::vector<std::string>& command_line();
/// Drops `OPTION VALUE` and `OPTION=VALUE` from the recorded command line, for
/// an option that changes no output (--threads): outputs are then
/// byte-identical, provenance included, whatever the option is set to.
void omit_from_command_line(const std::string& option);

/// The provenance object for an output made from `inputs` (file paths; empty
/// ones are skipped, repeated ones listed once). Throws std::runtime_error
/// naming a file that cannot be read.
nlohmann::json provenance_json(const std::vector<std::string>& inputs);

/// The same object as one line of compact JSON, for comments in non-JSON files.
std::string provenance_line(const std::vector<std::string>& inputs);

}  // namespace vbsim
