// vbsim convert: between the text and binary trace forms, and from rtcore ray files.
#include <fmt/format.h>

#include "commands.h"
#include "io/output_paths.h"
#include "trace/rtcore_ray_import.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim::cli {

namespace {

struct ConvertArgs {
  std::string in, out, from = "vbsim", scene;
};

void run_convert(const ConvertArgs& a) {
  check_output_paths({{"input", a.in}, {"option '--scene'", a.scene}}, {{"option '--out'", a.out}});
  std::unique_ptr<TraceSource> source;
  if (a.from == "vbsim") {
    source = open_trace(a.in);
  } else if (a.from == "rtcore") {
    if (a.scene.empty()) throw std::runtime_error("option '--scene': required with --from rtcore");
    source = std::make_unique<RtcoreRayReader>(a.in, a.scene);
  } else {
    throw std::runtime_error(fmt::format("option '--from': unknown format '{}'; formats: vbsim, rtcore", a.from));
  }
  check_output_paths({{"scene", source->header().scene_path}}, {{"option '--out'", a.out}});
  TraceHeader header = source->header();
  header.scene = scene_relative_to(header.scene_path, a.out);  // the output may live elsewhere
  auto sink = create_trace_writer(a.out, header);
  const int64_t n = copy_trace(*source, *sink);
  sink->close();
  fmt::print("vbsim convert: {} rays {} -> {}\n", n, a.in, a.out);
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand("convert", "convert a trace: .jsonl <-> .vbt, or import rtcore rays");
  cmd->add_option("input", args->in, "input file")->required();
  cmd->add_option("-o,--out", args->out, "output trace: .vbt is binary, anything else text")->required();
  cmd->add_option("--from", args->from, "input format: vbsim (text or binary) or rtcore")->capture_default_str();
  cmd->add_option("--scene", args->scene, "with --from rtcore: the mesh the rays go with (header 'scene')");
  cmd->callback([args] { run_convert(*args); });
}

}  // namespace vbsim::cli
