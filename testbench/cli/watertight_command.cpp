// vbsim watertight: lost rays and double hits per tester on rays aimed exactly
// at shared edges and vertices of closed meshes (see docs/testers.md): the
// standard meshes, or mesh files of the user's own (an open mesh is measured
// at its interior edges and vertices).
#include <fmt/format.h>

#include <sstream>

#include "commands.h"
#include "datapath/watertightness.h"
#include "exit_codes.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "method_options.h"
#include "provenance/provenance.h"
#include "scene/scene.h"

namespace vbsim::cli {

namespace {

struct WatertightArgs {
  std::vector<std::string> meshes;
  std::string testers = "three-half-plane,moller-trumbore";
  int outside = 4, inside = 4;
  uint32_t seed = 2013;
  std::string json;
  bool quiet = false;
};

nlohmann::json rows_json(const std::vector<WatertightnessRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const WatertightnessRow& row : rows) {
    const WatertightnessCounts& c = row.counts;
    out.push_back({{"mesh", row.mesh},         {"triangles", row.triangles},    {"tester", tester_name(row.tester)},
                   {"rays", c.rays},           {"hit", c.hit},                  {"lost", c.lost},
                   {"holes", c.holes},         {"double_hits", c.double_hits}, {"exact_aim", c.exact_aim},
                   {"skipped", c.skipped},     {"open_edges", c.open_edges}});
  }
  return out;
}

void run_watertight(const WatertightArgs& a) {
  const std::vector<TesterKind> testers = parse_tester_list(a.testers);
  if (a.outside < 0 || a.inside < 0 || a.outside + a.inside == 0)
    throw UsageError("options '--outside' and '--inside': need >= 0 origins each and at least one in all");
  if (a.meshes.empty() && (a.outside != 4 || a.inside != 4 || a.seed != 2013))
    throw UsageError("options '--outside', '--inside' and '--seed' apply to meshes given on the command line");
  std::vector<NamedPath> inputs;
  for (const std::string& path : a.meshes) inputs.push_back({"mesh", path});
  check_output_paths(inputs, {{"option '--json'", a.json}});
  std::vector<WatertightnessRow> rows;
  if (a.meshes.empty()) {
    rows = standard_watertightness_rows(testers);
  } else {
    for (const std::string& path : a.meshes) {
      const Scene scene = load_scene(path);
      const std::vector<Vec3f> origins = watertightness_origins(scene.triangles, a.outside, a.inside, a.seed);
      for (TesterKind kind : testers) {
        WatertightnessCounts counts;
        try {
          counts = measure_watertightness(scene.triangles, kind, origins, /*allow_open=*/true);
        } catch (const std::invalid_argument& e) {  // inconsistent winding, degenerate triangles
          throw std::runtime_error(fmt::format("{}: {}", path, e.what()));
        }
        rows.push_back({path, scene.size(), kind, counts});
      }
    }
  }
  if (!a.json.empty()) {
    const nlohmann::json j = {{"origins", {{"outside", a.outside}, {"inside", a.inside}, {"seed", a.seed}}},
                              {"rows", rows_json(rows)},
                              {"provenance", provenance_json(a.meshes)}};
    write_output_file(a.json, j.dump(2) + "\n", "watertightness JSON");
  }
  if (a.quiet) return;
  fmt::print("{}", format_watertightness_table(rows));
  for (size_t i = 0; i < rows.size(); i += testers.size())
    if (rows[i].counts.open_edges > 0)
      fmt::print("{}: {} boundary edges (in one triangle only); they and their vertices are no target\n",
                 rows[i].mesh, rows[i].counts.open_edges);
}

}  // namespace

void add_watertight_command(CLI::App& app) {
  auto args = std::make_shared<WatertightArgs>();
  CLI::App* cmd = app.add_subcommand(
      "watertight", "measure each tester's lost rays and double hits at shared edges and vertices");
  cmd->add_option("meshes", args->meshes,
                  "mesh files to measure (any scene the loader reads; open meshes at their interior edges) "
                  "[the standard icosphere and box, near the origin and far from it]");
  cmd->add_option("--testers", args->testers, "comma list of testers")->capture_default_str();
  cmd->add_option("--outside", args->outside, "origins on a sphere around a mesh of your own")->capture_default_str();
  cmd->add_option("--inside", args->inside, "origins near the centre of a mesh of your own")->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the origins of a mesh of your own")->capture_default_str();
  cmd->add_option("--json", args->json, "write the rows as JSON here");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_watertight(*args); });
}

}  // namespace vbsim::cli
