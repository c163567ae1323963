// Scenarios: generators of a scene and a trace that reproduce one known
// self-intersection situation, selected by name (`vbsim gen SCENARIO`). A
// scenario returns one or more cases; each case is written as its own scene
// (binary PLY, exact) and trace, with `expect` filled in by the exact oracle
// on the scene exactly as a replay loads it. Same settings and seed, same files.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "datapath/triangle.h"
#include "trace/trace_record.h"

namespace vbsim {

/// The settings of one generation: ray count, seed, and `--set key=value`
/// parameters read through typed getters that name the key on a bad value.
class ScenarioSettings {
 public:
  /// Throws std::runtime_error ("option '--rays': must be > 0") unless rays > 0.
  ScenarioSettings(int64_t rays, uint64_t seed, std::map<std::string, std::string> values);
  int64_t rays() const { return rays_; }
  uint64_t seed() const {
    seed_read_ = true;
    return seed_;
  }
  /// Whether the scenario asked for the seed (a scenario that is the same for
  /// every seed, such as random-triangles protocol=pbrt-v4, never does).
  bool seed_read() const { return seed_read_; }
  /// The value of `key` as a finite number, or `fallback` when not set.
  double number(const std::string& key, double fallback) const;
  /// The value of `key` as an integer, or `fallback` when not set.
  int64_t integer(const std::string& key, int64_t fallback) const;
  /// The value of `key`, or `fallback` when not set.
  std::string text(const std::string& key, const std::string& fallback) const;
  /// Throws when a key was set that the scenario never read (a typo).
  void check_all_read(const std::string& scenario) const;

 private:
  const std::string* find(const std::string& key) const;
  int64_t rays_;
  uint64_t seed_;
  std::map<std::string, std::string> values_;
  mutable std::set<std::string> read_;
  mutable bool seed_read_ = false;
};

/// One scene and its rays.
struct ScenarioCase {
  std::string name;        ///< file stem of the case's scene and trace
  std::string scene_file;  ///< an existing scene to reference; empty: write `triangles`
  std::vector<Triangle> triangles;
  std::vector<std::array<Vec3f, 3>> normals;  ///< per-corner shading normals, or empty
  std::optional<Vec3f> light;
  std::optional<std::array<float, 16>> transform;
  std::string description;
  std::vector<TraceRay> rays;  ///< parents before children; `expect` is filled when written
};

struct Scenario {
  const char* name;
  const char* summary;
  std::vector<ScenarioCase> (*generate)(const ScenarioSettings&);
};

/// Every scenario, in a fixed order.
const std::vector<Scenario>& scenarios();
/// The scenario called `name`, or null.
const Scenario* find_scenario(const std::string& name);

/// What write_scenario_case records and reports besides the case itself.
struct CaseWriteOptions {
  std::string provenance;  ///< JSON object for the trace header and the PLY comment (empty: none)
  std::function<void(uint64_t rays)> on_rays;  ///< told of every kOracleProgressRays rays filled in, and the rest
  std::vector<std::string>* written = nullptr;  ///< gets the paths of the files written
};
constexpr uint64_t kOracleProgressRays = 256;

/// Writes `c` into `dir`: NAME.ply (unless it references a scene file) and
/// NAME.jsonl with `expect` from the oracle; returns the trace's path.
std::string write_scenario_case(const ScenarioCase& c, const std::string& dir, const std::string& generator,
                                const CaseWriteOptions& options = {});

}  // namespace vbsim
