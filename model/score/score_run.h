// Score run: every trace of every scenario family replayed with every
// configuration (method x tester), in-process, the configurations of a block of
// rays shared among worker threads. Results come in a fixed order (family,
// method, tester) whatever the thread count.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "energy/tech_file.h"
#include "hw/hw_config.h"
#include "replay/replay_stats.h"
#include "score/method_spec.h"
#include "trace/parent_ray_store.h"

namespace vbsim {

/// A scenario family: the traces of one directory (or one trace file).
struct ScoreFamily {
  std::string name;                 ///< the directory's name, or the file's stem
  std::vector<std::string> traces;  ///< sorted by name
  std::string generator;            ///< the first trace's header `generator` (may be empty)
};

/// Families from command-line paths: a directory gives its `.jsonl` and `.vbt`
/// files (sorted; an error when it has none), a file is a family of its own.
/// Throws std::runtime_error on a missing path, an empty directory or two
/// families with the same name.
std::vector<ScoreFamily> collect_score_families(const std::vector<std::string>& paths);

/// One configuration of a score run.
struct ScoreConfig {
  std::string method;  ///< the method entry's label
  ReplayOptions options;
};

/// The configurations: every method with every tester, methods outermost.
std::vector<ScoreConfig> score_configs(const std::vector<MethodSpec>& methods,
                                       const std::vector<TesterKind>& testers);

/// What one configuration counted over one family's traces.
struct ScoreCell {
  std::string family;
  std::string method;
  TesterKind tester = TesterKind::ThreeHalfPlane;
  nlohmann::json config;  ///< the effective configuration (replay_config_json)
  ReplayOptions options;  ///< the same, as options (the energy model prices its method and tester)
  ReplayStats stats;      ///< summed over the traces; wall_s: this configuration's replay time
  int traces = 0;
  bool has_cycles = false;   ///< measured by the cycle-level model (cycle mode)
  uint64_t cycle_rays = 0;   ///< rays the cycle-level replays finished
  uint64_t cycles = 0;       ///< summed over the traces, each replayed on its own
  std::string cycle_preset;  ///< the hardware preset the cycles were measured on
  double cycle_total_pj = 0;  ///< the cycle-level runs' energy (operations, memory, leakage), summed
  double chip_mm2 = 0;        ///< the chip's area for this configuration
};

/// Told the number of rays of a block just replayed with every configuration.
using ScoreProgress = std::function<void(uint64_t rays)>;

/// How a score run replays.
struct ScoreRunOptions {
  int threads = 1;  ///< functional replays in parallel (>= 1)
  /// Cycle mode: every configuration whose tester is in cycle_testers is also
  /// replayed by the cycle-level model of `hw`, trace by trace, one at a
  /// time; its verdicts must equal the functional ones.
  bool cycle = false;
  hw::HwConfig hw;
  std::vector<TesterKind> cycle_testers;
  /// Prices the cycle-level runs' energy and area (null: the shipped default).
  const TechFile* tech = nullptr;
  ScoreProgress progress;  ///< called after every block (may be empty)
  /// Parents are looked up among the last `parent_window` rays (ParentRayStore).
  int64_t parent_window = ParentRayStore::kDefaultWindow;
};

/// Replays every family with every configuration. Cells are ordered family,
/// then configuration. Throws TraceError naming the trace on bad input, and
/// std::runtime_error when a cycle-level replay's verdicts differ from the
/// functional replay's, ConservationError when a configuration's statistics do
/// not count every ray read.
std::vector<ScoreCell> run_score(const std::vector<ScoreFamily>& families,
                                 const std::vector<ScoreConfig>& configs, const ScoreRunOptions& options);

}  // namespace vbsim
