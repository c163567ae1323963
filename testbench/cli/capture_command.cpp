// vbsim capture: runs an unmodified Embree 3 application under the capture
// shim and writes its rays and scene as a trace directory (docs/capture.md).
#include <fmt/format.h>

#include <unistd.h>

#include <filesystem>

#include "capture/application_launch.h"
#include "capture/static_embree_check.h"
#include "capture/capture_merge.h"
#include "capture/raw_capture_files.h"
#include "commands.h"
#include "exit_codes.h"
#include "io/stale_temporaries.h"
#include "provenance/provenance.h"

namespace vbsim::cli {

namespace {

struct CaptureArgs {
  std::string out;
  std::vector<std::string> command;
  bool binary = false, keep_raw = false, strip_offsets = false, allow_partial = false;
  capture::LinkRules rules;
};

/// Gives the shim's files of this run the name OUT/raw (replacing an earlier run's).
void settle_raw(const std::filesystem::path& files, const std::filesystem::path& raw) {
  std::filesystem::remove_all(raw);
  std::filesystem::rename(files, raw);
}

void run_capture(const CaptureArgs& a) {
  namespace fs = std::filesystem;
  // A program with Embree linked into it is refused before it runs.
  if (const std::string why = capture::embree_defined_by_program(a.command); !why.empty())
    throw std::runtime_error(fmt::format("cannot capture {}: {}", a.command.front(), why));
  const fs::path raw = fs::path(a.out) / "raw";
  // The shim writes into a directory of this run's own (two captures into one
  // OUT do not mix), named as every temporary is (NAME.partial-PID-N), so
  // that the leftovers of a killed capture are removed by the next one.
  remove_stale_temporaries(raw.string());
  const fs::path files = fs::path(a.out) / fmt::format("raw.partial-{}-0", ::getpid());
  fs::remove_all(files);
  fs::create_directories(files);
  const std::string shim = capture::capture_shim_path();
  const capture::LaunchResult run = capture::run_under_shim(a.command, shim, fs::absolute(files).string());
  if (run.interrupted) {  // Ctrl-C or SIGTERM: no trace, the shim's files kept only with --keep-raw
    if (a.keep_raw) settle_raw(files, raw);
    else fs::remove_all(files);
    fmt::print(stderr, "vbsim: interrupted\n");
    throw CLI::RuntimeError(kExitInterrupted);
  }
  // The shim refused an Embree out of its reach (dlmopen, Embree 4): it ended
  // the application before it traced there, or wrote why at its exit.
  if (const std::string refused = capture::read_refusals(files.string()); !refused.empty()) {
    settle_raw(files, raw);
    throw std::runtime_error(fmt::format("cannot capture {}: {}; no trace written (the shim's files are in {})",
                                         a.command[0], refused, raw.string()));
  }
  if (!run.exited_normally()) {
    settle_raw(files, raw);
    throw std::runtime_error(fmt::format("{} {}: no trace written (the shim's files are in {})", a.command[0],
                                         run.describe(), raw.string()));
  }
  capture::MergeOptions opt;
  opt.rules = a.rules;
  opt.binary = a.binary;
  opt.strip_offsets = a.strip_offsets;
  opt.command = a.command;
  opt.provenance = provenance_line({});  // the application's scene comes from memory, not a file
  capture::MergeResult merged;
  try {
    merged = capture::merge_capture(files.string(), a.out, opt);
  } catch (const std::exception&) {
    settle_raw(files, raw);  // what the shim wrote, for a look at what went wrong
    throw;
  }
  if (a.keep_raw) settle_raw(files, raw);
  else {
    fs::remove_all(files);
    fs::remove_all(raw);  // an earlier run's: not the files of this trace
  }
  fmt::print("{}", merged.summary);
  if (merged.incomplete_rays > 0 && !a.allow_partial)
    throw std::runtime_error(fmt::format(
        "{} rays of {} are incomplete: the trace cannot reproduce what Embree answered for them (counted by reason "
        "above and in capture.json). The trace is written with those rays marked; give --allow-partial to accept it",
        merged.incomplete_rays, merged.trace_path));
  fmt::print("  next: vbsim oracle {} -o scored{}, then vbsim replay or vbsim score; vbsim compare-reference compares "
             "a replay's --hits with embree_hits.jsonl\n", merged.trace_path, a.binary ? ".vbt" : ".jsonl");
}

}  // namespace

void add_capture_command(CLI::App& app) {
  auto args = std::make_shared<CaptureArgs>();
  CLI::App* cmd = app.add_subcommand(
      "capture", "run an Embree 3 application under a preloaded shim and write its rays and scene as a trace");
  cmd->add_option("-o,--out", args->out, "output directory (trace, scene.ply, embree_hits.jsonl, capture.json)")
      ->required();
  cmd->add_flag("--binary", args->binary, "write trace.vbt instead of trace.jsonl");
  cmd->add_option("--link-ulps", args->rules.ulps,
                  "a child's origin may differ from its parent's hit point by this many ulps per axis (ulps of the "
                  "largest coordinate of the point, the parent's t d and the hit triangle's vertices)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--link-rejected-ulps", args->rules.rejected_ulps,
                  "a ray whose filter functions rejected one primitive links to a recent hit on it within this many "
                  "ulps (same unit)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--link-offset", args->rules.normal_offset,
                  "largest origin offset along the hit's normal, as a fraction of the hit point's size (0: none)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--link-history", args->rules.history, "recent hits of a thread searched for a parent")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 16))
      ->capture_default_str();
  cmd->add_flag("--strip-offsets", args->strip_offsets,
                "children start at their parent's hit point with tmin 0 (the application's own offsets removed)");
  cmd->add_flag("--allow-partial", args->allow_partial,
                "exit 0 even when rays are incomplete (their answers involve geometry or filter functions the "
                "trace does not hold; they stay marked and unscored)");
  cmd->add_flag("--keep-raw", args->keep_raw, "keep the shim's raw files in OUT/raw");
  cmd->add_option("command", args->command, "the application and its arguments, after `--`")->required();
  cmd->callback([args] { run_capture(*args); });
}

}  // namespace vbsim::cli
