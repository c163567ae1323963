// vbsim fit: the smallest epsilon, guard band and offset scale that give no
// self_hit and no missed ray on the given traces (model/fit/).
#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "fit/fit_report.h"
#include "replay/replay_config.h"
#include "score/score_run.h"
#include "trace/trace_file.h"

namespace vbsim::cli {

namespace {

struct FitArgs {
  std::vector<std::string> paths;
  std::string params, tester = "three-half-plane", hitpoint = "given", vb_policy = "all";
  int vb_min_exponent = 1;
  std::string json;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool quiet = false;
};

FitSettings fit_settings(const FitArgs& a) {
  FitSettings s;
  if (!parse_tester(a.tester, s.tester))
    throw UsageError(fmt::format("option '--tester': unknown tester '{}'; testers: three-half-plane, moller-trumbore, pbrt-watertight", a.tester));
  if (!parse_hit_point_mode(a.hitpoint, s.hit_point))
    throw UsageError(fmt::format("option '--hitpoint': unknown hit point '{}'; hit points: given, ray, barycentric", a.hitpoint));
  if (!parse_avoidance_policy(a.vb_policy, s.vb_policy))
    throw UsageError(fmt::format("option '--vb-policy': unknown policy '{}'; policies: all, vote, sign-only", a.vb_policy));
  if (a.vb_min_exponent < 1 || a.vb_min_exponent > 254)
    throw UsageError("option '--vb-min-exponent': must be a biased float32 exponent in 1..254");
  s.vb_min_exponent = a.vb_min_exponent;
  return s;
}

std::vector<std::string> parameter_keys(const std::string& list) {
  if (list.empty()) return fit_parameter_keys();
  std::vector<std::string> out;
  std::stringstream in(list);
  std::string key;
  while (std::getline(in, key, ',')) out.push_back(key);
  return out;
}

void run_fit_command(const FitArgs& a) {
  if (a.threads < 1) throw UsageError("option '--threads': must be >= 1");
  const FitSettings settings = fit_settings(a);
  std::vector<FitParameter> params;
  try {
    for (const std::string& key : parameter_keys(a.params)) params.push_back(make_fit_parameter(key, settings));
  } catch (const ConfigError& e) {  // an unknown parameter key
    throw UsageError(e.what());
  }

  const std::vector<ScoreFamily> families = collect_score_families(a.paths);
  // Before any work: the JSON output may not overwrite a trace or its scene.
  std::vector<NamedPath> read;
  for (const ScoreFamily& fam : families)
    for (const std::string& path : fam.traces) {
      read.push_back({"trace", path});
      read.push_back({"scene of " + path, open_trace(path)->header().scene_path});
    }
  check_output_paths(read, {{"option '--json'", a.json}});

  std::vector<FitTrace> traces;
  for (const ScoreFamily& fam : families)
    for (const std::string& path : fam.traces) traces.push_back(load_fit_trace(path));
  size_t scored = 0;
  for (const FitTrace& t : traces)
    for (const TraceRay& r : t.rays()) scored += r.has_expect;
  if (scored == 0) throw std::runtime_error("no ray has `expect`: fill it in with `vbsim oracle` first");

  nlohmann::json report = {{"traces", nlohmann::json::array()},
                           {"tester", tester_name(settings.tester)},
                           {"hitpoint", hit_point_mode_name(settings.hit_point)},
                           {"fits", nlohmann::json::array()}};
  std::vector<std::string> inputs;
  for (const FitTrace& t : traces) {
    report["traces"].push_back(t.path);
    inputs.push_back(t.path);
  }
  if (!a.quiet)
    fmt::print("vbsim fit: {} trace(s), {} scored rays, tester {}, hit point {}; smallest values with no "
               "self_hit and no missed ray\n",
               traces.size(), scored, tester_name(settings.tester), hit_point_mode_name(settings.hit_point));
  for (const FitParameter& p : params) {
    const FitResult r = fit_parameter(p, traces, a.threads);
    report["fits"].push_back(fit_json(r));
    if (!a.quiet) fmt::print("{}", fit_text(r));
  }
  if (!a.json.empty()) {
    report["provenance"] = provenance_json(inputs);
    write_output_file(a.json, report.dump(2) + "\n", "fit JSON");
  }
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* cmd = app.add_subcommand(
      "fit", "smallest epsilon, guard band and offset scale with no self_hit and no missed ray on traces");
  cmd->add_option("paths", args->paths, "traces with expect, or directories of them")->required();
  std::string keys;
  for (const std::string& k : fit_parameter_keys()) keys += (keys.empty() ? "" : ",") + k;
  cmd->add_option("--params", args->params, "comma list of parameters to fit [" + keys + "]");
  cmd->add_option("--tester", args->tester, "three-half-plane, moller-trumbore or pbrt-watertight")->capture_default_str();
  cmd->add_option("--hitpoint", args->hitpoint, "given, ray or barycentric")->capture_default_str();
  cmd->add_option("--vb-policy", args->vb_policy, "validity-bit policy: all, vote or sign-only")->capture_default_str();
  cmd->add_option("--vb-min-exponent", args->vb_min_exponent,
                  "guard-band fit: minimum biased exponent of the epsilon (1: no clamp)")
      ->capture_default_str();
  cmd->add_option("--json", args->json, "write the results as JSON here");
  cmd->add_option("--threads", args->threads, "worker threads")->capture_default_str();
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_fit_command(*args); });
}

}  // namespace vbsim::cli
