// vbsim convert: between the text and binary trace forms, and from rtcore ray files.
#include <fmt/format.h>

#include "commands.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "trace/rtcore_ray_import.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim::cli {

namespace {

struct ConvertArgs {
  std::string in, out, from = "vbsim", scene;
  bool quiet = false;
};

void run_convert(const ConvertArgs& a) {
  std::unique_ptr<TraceSource> source;
  if (a.from == "vbsim") {
    source = open_trace(a.in);
  } else if (a.from == "rtcore") {
    if (a.scene.empty()) throw UsageError("option '--scene': required with --from rtcore");
    source = std::make_unique<RtcoreRayReader>(a.in, a.scene);
  } else {
    throw UsageError(fmt::format("option '--from': unknown format '{}'; formats: vbsim, rtcore", a.from));
  }
  TraceHeader header = source->header();
  header.scene = scene_relative_to(header.scene_path, a.out);  // the output may live elsewhere
  // The output's provenance replaces the input's: it names the input by checksum.
  header.provenance = provenance_line({a.in, header.scene_path});
  auto sink = create_trace_writer(a.out, header);
  const int64_t n = copy_trace(*source, *sink);
  sink->close();
  if (!a.quiet) fmt::print(stderr, "vbsim convert: {} rays {} -> {}\n", n, a.in, a.out);
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand("convert", "convert a trace: .jsonl <-> .vbt, or import rtcore rays");
  cmd->add_option("input", args->in, "input file")->required();
  cmd->add_option("-o,--out", args->out, "output trace: .vbt is binary, anything else text")->required();
  cmd->add_option("--from", args->from, "input format: vbsim (text or binary) or rtcore")->capture_default_str();
  cmd->add_option("--scene", args->scene, "with --from rtcore: the mesh the rays go with (header 'scene')");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_convert(*args); });
}

}  // namespace vbsim::cli
