// The main job's trade-off table: after the validity-bit replay, every method
// of `vbsim score` on the bundled trace, scored and timed in one run
// (model/score/): secondary-ray errors per million, camera rays missed, cycles
// per ray on the small preset, bits per ray in flight.
#include <fmt/format.h>

#include <thread>

#include "commands.h"
#include "score/score_run.h"
#include "score/score_table.h"
#include "score/tradeoff_table.h"

namespace vbsim::cli {

void print_tradeoff_table(const std::string& trace) {
  std::vector<ScoreConfig> configs;
  for (const MethodSpec& m : parse_method_list(default_score_method_list())) configs.push_back({m.label, m.options});
  // pbrt-v4's offset with pbrt-v4's own tester, the pair its published zero is for.
  ScoreConfig pbrt{"offset-errbound", parse_method_spec("offset-errbound").options};
  pbrt.options.tester = TesterKind::PbrtWatertight;
  configs.push_back(pbrt);

  ScoreRunOptions run;
  run.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run.cycle = true;
  run.hw = hw::resolve_hw_config("", "small");
  run.cycle_testers = {TesterKind::ThreeHalfPlane, TesterKind::PbrtWatertight};
  const std::vector<ScoreFamily> families = collect_score_families({trace});
  const nlohmann::json score = score_json(families, run_score(families, configs, run), "");
  fmt::print("\nevery method on this trace (secondary rays: the {} rays that leave a surface; 95% Wilson "
             "intervals; cycles on the small preset; pJ/ray: the operations' energy at the shipped 45 nm figures, "
             "no memory, docs/energy.md):\n{}",
             tradeoff_rows(score).front().secondary_scored, tradeoff_text(tradeoff_rows(score)));
}

}  // namespace vbsim::cli
