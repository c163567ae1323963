// merge_capture: turns the capture shim's raw files into a trace directory:
//   scene.ply          the traced scene's captured triangles (binary PLY, exact float32),
//                      triangle id = first_triangle(geomID) + primID (capture.json lists them)
//   trace.jsonl|.vbt   every ray of that scene, linked into trees, ids ascending
//   embree_hits.jsonl  Embree's own answer for every ray of the trace, by id
//   capture.json       calls and rays per Embree function, what was not captured and
//                      why, links made and rays left unlinked, kinds, tolerances
// Outputs are written under temporary names and renamed at the end, capture.json last.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "capture/parent_linker.h"

namespace vbsim::capture {

struct MergeOptions {
  LinkRules rules;
  bool binary = false;               ///< trace.vbt instead of trace.jsonl
  /// Children start at their parent's hit point (org + t dir in float32) with
  /// tmin 0, as the trace format defines `o`; by default origins and tmin are
  /// the application's, its own offsets included.
  bool strip_offsets = false;
  std::vector<std::string> command;  ///< the application's command line, for the header and report
  /// What wrote the outputs (provenance_line()): the trace header's `provenance`
  /// and scene.ply's `vbsim-provenance` comment; empty: none.
  std::string provenance;
};

struct MergeResult {
  nlohmann::json report;  ///< what capture.json holds
  std::string summary;    ///< a few lines for the terminal
  std::string trace_path;
  int64_t incomplete_rays = 0;  ///< rays marked `incomplete` (incomplete_rays.h)
};

/// Merges the files in `raw_dir` into `out_dir`. Throws std::runtime_error
/// with a clear message when nothing was captured, a process did not finish,
/// or a file is damaged.
MergeResult merge_capture(const std::string& raw_dir, const std::string& out_dir, const MergeOptions& options);

}  // namespace vbsim::capture
