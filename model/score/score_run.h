// Score run: every trace of every scenario family replayed with every
// configuration (method x tester), in-process, the configurations of a block of
// rays shared among worker threads. Results come in a fixed order (family,
// method, tester) whatever the thread count.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "replay/replay_stats.h"
#include "score/method_spec.h"

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
  ReplayStats stats;      ///< summed over the traces; wall_s: this configuration's replay time
  int traces = 0;
};

/// Told the number of rays of a block just replayed with every configuration.
using ScoreProgress = std::function<void(uint64_t rays)>;

/// Replays every family with every configuration using `threads` threads (>= 1),
/// parents looked up among the last `parent_window` rays (ParentRayStore).
/// Cells are ordered family, then configuration. Throws TraceError naming the
/// trace on bad input, ConservationError when a configuration's statistics do
/// not count every ray read. `progress` (may be empty) is called after every block.
std::vector<ScoreCell> run_score(const std::vector<ScoreFamily>& families,
                                 const std::vector<ScoreConfig>& configs, int threads,
                                 const ScoreProgress& progress = {},
                                 int64_t parent_window = ParentRayStore::kDefaultWindow);

}  // namespace vbsim
