// HwConfig: every knob of the cycle-level model (docs/config.md documents each:
// unit, default, meaning). Read from the `hw` object of a configuration file,
// on top of a preset (model/hw/presets/NAME.json); errors name the JSON field.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "datapath/ray.h"
#include "hw/core/tester_timing.h"
#include "hw/memory/memory_config.h"

namespace vbsim::hw {

/// `count` identical pipelines of one kind in each group of `share` cores: a
/// group's pipelines take the operations of all its cores (share 1, the
/// default: every core has its own). Cores `g*share .. g*share + share - 1`
/// form group g; the last group may have fewer cores.
struct UnitConfig {
  uint32_t count = 1;           ///< pipelines of this kind per group of `share` cores
  uint32_t latency = 1;         ///< cycles from issue to result
  uint32_t issue_interval = 1;  ///< cycles between two issues into one pipeline
  uint32_t share = 1;           ///< cores served by one group of `count` pipelines
};

/// Groups of `u.share` cores among `cores`: the instances of the unit kind.
inline uint32_t unit_groups(const UnitConfig& u, uint32_t cores) { return (cores + u.share - 1) / u.share; }

/// What the ray source does with a child whose parent is not among the rays
/// of the parent window before it: stop with an error naming the child's line,
/// or replay it as an independent ray (counted, with a warning).
enum class MissingParents { Error, Independent };
const char* missing_parents_name(MissingParents m);

/// The ray source: the ray-emission interface in front of the dispatcher.
struct SourceConfig {
  uint32_t issue_interval = 1;      ///< cycles one emission lane takes per ray, at least
  uint32_t sign_bit_cycles = 1;     ///< extra cycles when the trace omits a child's sign bit
  uint32_t emission_op_cycles = 4;  ///< extra cycles per emission-time method acting on a ray (no emission unit)
  /// The emission unit (0: none, emission_op_cycles per method): operations it
  /// starts per cycle on a lane's ray; a ray's n emission-time operations
  /// (method_costs.h, emission_ops_for, the sign bit aside) occupy its lane
  /// ceil(n / emission_width) cycles instead, and the unit's depth delays the
  /// ray by emission_depth cycles more without occupying the lane (pipelined).
  uint32_t emission_width = 0;
  uint32_t emission_depth = 0;  ///< the emission unit's pipeline depth (latency), cycles
  uint32_t rays_per_cycle = 1;      ///< emission lanes: rays that may start emission in one cycle
  /// Rays the ray-emission buffer looks ahead beyond the oldest unfinished one.
  uint32_t window = 4096;
  /// A child ray waits for its parent's result (plus the shading latency);
  /// false: every ray independent, as a trace of unrelated queries.
  bool dependencies = true;
  MissingParents missing_parents = MissingParents::Error;
  /// Consecutive trace rays with the same parent and origin go through one
  /// bundle call of the emission API (the patent's "emit a bundle of rays").
  bool bundles = false;
  uint32_t bundle_cycles = 0;       ///< a bundle call's own cycles, on top of its rays'
  uint32_t bundle_max = 8;          ///< rays in one bundle at most
};

/// The shaders that emit child rays (outside the accelerator).
struct ShaderConfig {
  /// Cycles from a parent ray's result reaching the result sink to its
  /// children being ready for emission.
  uint32_t latency_cycles = 200;
  static constexpr uint32_t kUnset = ~uint32_t{0};
  /// The same by the kind of the parent ray (RayKind order), where given
  /// (`latency_by_kind`); kUnset: latency_cycles.
  std::array<uint32_t, kRayKindCount> by_kind{kUnset, kUnset, kUnset, kUnset, kUnset};
  /// The latency after a result of a ray of kind `parent`.
  uint32_t latency_for(RayKind parent) const {
    const uint32_t k = by_kind[static_cast<size_t>(parent)];
    return k == kUnset ? latency_cycles : k;
  }
  bool any_by_kind() const {
    for (const uint32_t k : by_kind)
      if (k != kUnset) return true;
    return false;
  }
  /// The shader cores that run the software methods' emission-time arithmetic
  /// (hw/source/shader_core_pool.h), as a GPU's SIMD cores do before a ray
  /// reaches the emission API: `cores` cores of `simd_lanes` lanes, each lane
  /// `ops_per_lane_cycle` operations a cycle, a ray's operations on one lane
  /// with `pipeline_latency` cycles after its last. 0 cores: none, the
  /// arithmetic is the emission path's (source.emission_width, emission_op_cycles).
  uint32_t cores = 0;
  uint32_t simd_lanes = 64;
  uint32_t ops_per_lane_cycle = 1;
  uint32_t pipeline_latency = 4;
};

/// `{"latency_cycles": N, "cores": ..., "simd_lanes": ..., "ops_per_lane_cycle":
/// ..., "pipeline_latency": ...}`, with `latency_by_kind` (the kinds given) when any is.
nlohmann::json shader_config_json(const ShaderConfig& s);

/// Each core's traversal controller: every step of a slot (after dispatch,
/// after a node's box test, a leaf's tests, a stack refill) passes through it
/// before the next begins (its read, or the result). `count` controllers per
/// core, each taking a step every `issue_interval` cycles, a step leaving
/// `latency` cycles after one takes it; count 0 (the default): none, a step
/// follows the previous one at once (docs/hw-model.md, "Timing of each step").
/// A step kind's own timing at the controller.
struct ControllerStepTiming {
  bool set = false;  ///< false: the controller's latency and issue interval
  uint32_t latency = 0;
  uint32_t issue_interval = 1;
  bool operator==(const ControllerStepTiming& o) const {
    return set == o.set && (!set || (latency == o.latency && issue_interval == o.issue_interval));
  }
};

struct ControllerConfig {
  uint32_t count = 0;
  uint32_t latency = 0;
  uint32_t issue_interval = 1;
  /// The kind of step that has ended and passes the controller: the ray's
  /// start (dispatch and root box), a node's box test, a leaf's triangles, a
  /// stack refill. Each may take its own latency and issue interval (a
  /// controller that spends more cycles on a triangle's result than on a box
  /// test's, as rtcore-systemc's traversal controller does); unset ones take
  /// the controller's.
  enum Step : uint8_t { Start, Node, Leaf, Refill, kSteps };
  ControllerStepTiming by_step[kSteps];
  uint32_t step_latency(Step k) const { return by_step[k].set ? by_step[k].latency : latency; }
  uint32_t step_interval(Step k) const { return by_step[k].set ? by_step[k].issue_interval : issue_interval; }
};
const char* controller_step_name(ControllerConfig::Step k);  ///< "start", "node", "leaf", "refill"

enum class DispatchPolicy { RoundRobin, LeastLoaded };
const char* dispatch_policy_name(DispatchPolicy p);

struct HwConfig {
  std::string preset = "small";  ///< the preset these values started from
  double clock_mhz = 500;
  uint32_t cores = 4;
  uint32_t slots_per_core = 16;
  uint32_t stack_depth = 16;     ///< on-chip traversal stack entries per slot
  DispatchPolicy dispatch = DispatchPolicy::LeastLoaded;
  uint64_t address_base = 0;     ///< byte address of node 0 (multiple of 64)
  SourceConfig source;
  ShaderConfig shader;
  UnitConfig box{1, 8, 1};
  /// The low-precision box pool (count 0: none, the default): with nodes of
  /// two precisions (bvh.low_precision), a node whose two children are both
  /// low-precision is tested here, any other by `box`; without marked nodes
  /// it stays idle.
  UnitConfig box_low{0, 8, 1};
  UnitConfig triangle{1, 20, 1};
  /// With triangle_timing.derive, triangle.latency and issue_interval follow the
  /// tester of the run (for_tester); the values above hold until then.
  TriangleTiming triangle_timing;
  UnitConfig avoidance{1, 6, 1};
  ControllerConfig controller;
  /// Each ray's search starts with a test of the root's box, latched with the
  /// ray (true); false: with the root node's fetch, as rtcore-systemc's does.
  bool root_box_test = true;
  /// A popped stack entry beyond the closest hit so far is skipped (true), or
  /// visited all the same (false, as rtcore-systemc's traversal does).
  bool pop_culling = true;
  /// How a leaf's triangles are read: one read of the whole leaf, then its
  /// tests (false, the default); or each triangle read on its own, its test
  /// issued when it arrives and the next triangle's read
  /// `triangle_fetch_cycles` after its result (true: `triangle_fetch`
  /// "triangle", as rtcore-systemc's intersection controller reads them).
  bool per_triangle_fetch = false;
  uint32_t triangle_fetch_cycles = 0;
  MemoryConfig memory;
  uint32_t quantum_cycles = 256;        ///< sim: most cycles the engine runs ahead of SystemC time
  uint32_t latency_bucket_cycles = 32;  ///< sim: width of a latency histogram bucket
  uint32_t latency_buckets = 64;        ///< sim: buckets (the last one also counts longer latencies)
  /// sim: the statistics in `hw.measured` start after the warm-up: once this
  /// many rays have finished, or at this cycle (at most one non-zero; 0: none).
  uint64_t warmup_rays = 0, warmup_cycles = 0;
  uint64_t interval_cycles = 1000;  ///< sim: cycles per row of the interval statistics (--interval-stats)
};

/// Names of the committed presets.
std::vector<std::string> preset_names();
/// The preset `name` (small, large, rtcore). Throws ConfigError naming `origin` and the
/// preset when it is unknown or its file is broken.
HwConfig load_preset(const std::string& name, const std::string& origin);

/// Applies the fields present in `j` (an `hw` object) onto `cfg`; a `preset`
/// field first resets `cfg` to that preset. Throws ConfigError "FILE: field
/// 'hw.x': reason" on a wrong type, unknown field or out-of-range value.
void apply_hw_config(const nlohmann::json& j, const std::string& file, HwConfig& cfg);

/// The hardware configuration for a run: preset `preset` (empty: the `hw.preset`
/// of the file, else small), then the `hw` object of the config file `path` (may be empty).
HwConfig resolve_hw_config(const std::string& path, const std::string& preset);

/// `cfg` for a run with tester `kind`: with triangle_timing.derive, the triangle
/// unit's latency and issue interval derived from the tester's arithmetic
/// (hw/core/tester_timing.h); otherwise `cfg` as it is.
HwConfig for_tester(HwConfig cfg, TesterKind kind);

/// The configuration as JSON, every field (the form presets and `config.hw` use).
nlohmann::json hw_config_json(const HwConfig& cfg);

}  // namespace vbsim::hw
