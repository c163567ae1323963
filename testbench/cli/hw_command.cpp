// vbsim hw: the cycle-level model's elaborated module hierarchy (every
// instance with its class, parameters and port bindings) and the statistics
// each kind of module declares, for a preset or a configuration file.
#include <fmt/format.h>

#include <memory>

#include "commands.h"
#include "hw/accelerator.h"
#include "hw/observe/hierarchy_report.h"
#include "hw/observe/hw_energy.h"
#include "hw/simulation_context.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "method_options.h"
#include "tech_option.h"

namespace vbsim::cli {

namespace {

struct HwArgs {
  bool hierarchy = false, statistics = false, area = false;
  std::string preset, json, tech;
  MethodOptions method;
};

void run_hw(const HwArgs& a) {
  const ReplayOptions opt = resolve_method_options(a.method);
  check_output_paths({{"option '--config'", a.method.config}, {"option '--tech'", a.tech}},
                     {{"option '--json'", a.json}});
  const hw::HwConfig cfg = hw::resolve_hw_config(a.method.config, a.preset);
  const TechFile tech = resolve_tech(a.tech);
  const hw::HwArea area = hw::hw_area(tech, cfg, opt);
  const hw::SimulationContext context;
  const Scene scene;
  const Bvh bvh;
  auto acc = std::make_unique<hw::Accelerator>("accelerator", cfg, scene, bvh, opt);
  sc_core::sc_get_curr_simcontext()->elaborate();  // binds the ports; nothing is simulated
  const bool all = !a.hierarchy && !a.statistics && !a.area;
  if (a.hierarchy || all) fmt::print("{}", hw::hierarchy_text(*acc));
  if (all) fmt::print("\n");
  if (a.statistics || all) fmt::print("{}", hw::statistics_text(*acc));
  if (all) fmt::print("\n");
  if (a.area || all) fmt::print("{}{}", hw::hw_area_table(tech, area), hw::sram_range_lines(tech, cfg));
  if (!a.json.empty()) {
    const nlohmann::json j = {{"hierarchy", hw::hierarchy_json(*acc)},
                              {"statistics", hw::statistics_json(*acc)},
                              {"config", hw::hw_config_json(hw::for_tester(cfg, opt.tester))},
                              {"area", hw::hw_area_json(tech, area)}};
    write_output_file(a.json, j.dump(2) + "\n", "hw JSON");
  }
  acc.reset();
}

}  // namespace

void add_hw_command(CLI::App& app) {
  auto args = std::make_shared<HwArgs>();
  CLI::App* cmd = app.add_subcommand("hw", "show the cycle-level model's module hierarchy and its statistics");
  cmd->add_flag("--hierarchy", args->hierarchy,
                "print the elaborated module tree: every instance with its class, parameters and port bindings");
  cmd->add_flag("--statistics", args->statistics, "print the statistics each kind of module declares");
  cmd->add_flag("--area", args->area,
                "print the area of every unit instance and of the chip, priced by the technology file (--tech)");
  add_tech_option(*cmd, args->tech);
  cmd->add_option("--preset", args->preset, "hardware preset, small, large or rtcore [the config's hw.preset, else small]");
  cmd->add_option("--json", args->json, "also write the hierarchy, statistics and configuration as JSON here");
  add_method_options(*cmd, args->method, "validity-bit");
  cmd->callback([args] { run_hw(*args); });
}

}  // namespace vbsim::cli
