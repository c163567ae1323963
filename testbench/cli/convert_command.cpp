// vbsim convert: between the text and binary trace forms, from rtcore ray
// files, and to rtcore ray files (with the scene as a PLY mesh for rtcore-systemc).
#include <fmt/format.h>

#include <filesystem>

#include "commands.h"
#include "progress/work_progress.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "scene/ply_scene_writer.h"
#include "scene/scene.h"
#include "trace/checked_trace_source.h"
#include "trace/rtcore_ray_import.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim::cli {

namespace {

struct ConvertArgs {
  std::string in, out, from = "vbsim", to = "vbsim", scene, scene_out;
  bool quiet = false;
};

std::unique_ptr<TraceSource> open_input(const ConvertArgs& a) {
  if (a.from == "vbsim") return open_trace(a.in);
  if (a.from == "rtcore") {
    if (a.scene.empty()) throw UsageError("option '--scene': required with --from rtcore");
    return std::make_unique<RtcoreRayReader>(a.in, a.scene);
  }
  throw UsageError(fmt::format("option '--from': unknown format '{}'; formats: vbsim, rtcore", a.from));
}

std::unique_ptr<TraceSink> create_output(const ConvertArgs& a, const TraceHeader& in_header) {
  if (a.to == "rtcore") return std::make_unique<RtcoreRayWriter>(a.out);
  if (!a.scene_out.empty()) throw UsageError("option '--scene-out': only with --to rtcore");
  TraceHeader header = in_header;
  header.scene = scene_relative_to(header.scene_path, a.out);  // the output may live elsewhere
  // The output's provenance replaces the input's: it names the input by checksum.
  header.provenance = provenance_line({a.in});  // the scene is named, not read
  return create_trace_writer(a.out, header);
}

void run_convert(const ConvertArgs& a) {
  if (a.to != "vbsim" && a.to != "rtcore")
    throw UsageError(fmt::format("option '--to': unknown format '{}'; formats: vbsim, rtcore", a.to));
  check_output_paths({{"input", a.in}, {"option '--scene'", a.scene}},
                     {{"option '--out'", a.out}, {"option '--scene-out'", a.scene_out}});
  std::unique_ptr<TraceSource> file = open_input(a);
  check_output_paths({{"scene", file->header().scene_path}}, {{"option '--out'", a.out}, {"option '--scene-out'", a.scene_out}});
  // The checks that need no scene (the scene is not loaded to convert a trace).
  CheckedTraceSource source(*file, TraceConsistencyChecker::Options{});
  auto sink = create_output(a, source.header());
  // Every writer names its file only once complete (AtomicOutputFile): a run
  // stopped by an error leaves no output, even a headerless rtcore file.
  const int64_t n = copy_trace(source, *sink);
  sink->close();
  if (!a.scene_out.empty()) {
    // rtcore-systemc reads a mesh, not vbsim's header: the scene as a replay
    // loads it (with the header's transform), one PLY triangle per triangle id.
    MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
    const Scene scene = load_scene(source.header().scene_path, source.header().transform, &loading);
    loading.finish();
    write_ply_scene(a.scene_out, scene.triangles, {},
                    "vbsim-provenance " + provenance_line({a.in, source.header().scene_path}));
  }
  fmt::print(stderr, "{}", source.warning_lines("vbsim convert", false));
  if (!a.quiet)
    fmt::print(stderr, "vbsim convert: {} rays {} -> {}{}\n", n, a.in, a.out,
               a.scene_out.empty() ? "" : fmt::format(" (scene -> {})", a.scene_out));
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "convert a trace: .jsonl <-> .vbt, or from and to rtcore-systemc ray files");
  cmd->add_option("input", args->in, "input file")->required();
  cmd->add_option("-o,--out", args->out,
                  "output: a trace (.vbt is binary, anything else text), or with --to rtcore a ray file")
      ->required();
  cmd->add_option("--from", args->from, "input format: vbsim (text or binary) or rtcore")->capture_default_str();
  cmd->add_option("--to", args->to, "output format: vbsim (text or binary by name) or rtcore")->capture_default_str();
  cmd->add_option("--scene", args->scene, "with --from rtcore: the mesh the rays go with (header 'scene')");
  cmd->add_option("--scene-out", args->scene_out,
                  "with --to rtcore: also write the trace's scene (transform applied) as a binary PLY mesh");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_convert(*args); });
}

}  // namespace vbsim::cli
