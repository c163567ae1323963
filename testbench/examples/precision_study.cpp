// The reduced-precision study (reduced_precision/precision_study.h) on a trace:
// the built-in units, then the box unit and the triangle tester with fewer
// mantissa bits, one line each (docs/hw-model.md, "Reduced precision").
//
//   precision_study [TRACE] [METHOD] [PRESET]
//     (default: the bundled trace when built with the project, validity-bit,
//     the small preset; built against the installed package, TRACE is needed)
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include <systemc>

#include "datapath/self_intersection_method.h"
#include "reduced_precision/precision_study.h"

#include "example_main.h"

namespace {

double percent(uint64_t v, uint64_t base) {
  return base ? 100.0 * (static_cast<double>(v) - static_cast<double>(base)) / static_cast<double>(base) : 0.0;
}

int run(int argc, char** argv) {
#ifdef VBSIM_SOURCE_DIR
  const std::string trace = argc > 1 ? argv[1] : std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
#else
  if (argc < 2) throw std::invalid_argument("usage: precision_study TRACE [METHOD] [PRESET]");
  const std::string trace = argv[1];
#endif
  const std::string method = argc > 2 ? argv[2] : "validity-bit";
  const std::string preset = argc > 3 ? argv[3] : "small";
  vbsim::ReplayOptions opt;
  std::string error;
  if (!vbsim::parse_method(method, opt.method, error)) throw std::invalid_argument(error);
  const vbsim::hw::HwConfig cfg = vbsim::hw::load_preset(preset, "precision_study");
  const auto runs = vbsim::hw::precision_study(trace, cfg, opt, {4, 8, 12, 16, 20}, {8, 12, 16, 20});
  const vbsim::hw::PrecisionRun& base = runs.front();
  std::printf("%s, method %s, preset %s, %llu rays\n", trace.c_str(), method.c_str(), preset.c_str(),
              static_cast<unsigned long long>(base.rays));
  std::printf("%-18s %12s %8s %12s %8s %10s %8s %8s %10s\n", "units", "box_tests", "+%", "tri_tests", "+%", "cycles",
              "+%", "changed", "self_hits");
  for (const vbsim::hw::PrecisionRun& r : runs)
    std::printf("%-18s %12llu %+7.2f%% %12llu %+7.2f%% %10llu %+7.2f%% %8llu %10llu\n", r.units.c_str(),
                static_cast<unsigned long long>(r.box_tests), percent(r.box_tests, base.box_tests),
                static_cast<unsigned long long>(r.triangle_tests), percent(r.triangle_tests, base.triangle_tests),
                static_cast<unsigned long long>(r.cycles), percent(r.cycles, base.cycles),
                static_cast<unsigned long long>(r.changed), static_cast<unsigned long long>(r.self_hits));
  return 0;
}

}  // namespace

int sc_main(int argc, char** argv) { return vbsim_examples::run_example("precision_study", run, argc, argv); }
