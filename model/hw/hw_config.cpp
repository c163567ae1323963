#include "hw/hw_config.h"

#include <fmt/format.h>

#include "io/data_dir.h"
#include "replay/config_fields.h"

namespace vbsim::hw {

namespace {

using config_fields::fail;
using config_fields::Fields;

constexpr uint32_t kMaxCount = 1u << 20;

nlohmann::json triangle_json(const HwConfig& c) {
  nlohmann::json j{{"count", c.triangle.count}, {"latency", c.triangle.latency},
                   {"issue_interval", c.triangle.issue_interval}, {"share", c.triangle.share}};
  if (c.triangle_timing.derive) {
    j["derive"] = true;
    j["operators"] = c.triangle_timing.operators;
    j["operator_latency"] = operator_latencies_json(c.triangle_timing.op);
  }
  return j;
}

std::string preset_path(const std::string& name) { return presets_dir() + "/" + name + ".json"; }

void read_unit(Fields& parent, const std::string& key, UnitConfig& u) {
  if (const auto* v = parent.get(key)) {
    Fields f(*v, parent.file(), parent.path(key));
    f.integer("count", u.count, 1, 64);
    f.integer("latency", u.latency, 1, 100000);
    f.integer("issue_interval", u.issue_interval, 1, 100000);
    f.integer("share", u.share, 1, 4096);
  }
}

void read_cache(Fields& parent, const std::string& key, CacheConfig& c, bool has_ports) {
  if (const auto* v = parent.get(key)) {
    Fields f(*v, parent.file(), parent.path(key));
    f.integer("size_bytes", c.size_bytes, 64, 1u << 31);
    // "full": one set of every line (a fully associative cache), resolved once
    // the size and line size are known; echoed as that number of ways.
    const nlohmann::json* ways = f.get("ways");
    const bool full = ways && ways->is_string();
    if (full && *ways != "full") fail(f.file(), f.path("ways"), "must be an integer or \"full\"");
    if (!full) f.integer("ways", c.ways, 1, kMaxCacheWays);
    f.integer("line_bytes", c.line_bytes, 16, 4096);
    f.integer("hit_latency", c.hit_latency, 0, 100000);
    f.integer("mshrs", c.mshrs, 1, 4096);
    f.boolean("merge_misses", c.merge_misses);
    if (has_ports) {
      f.integer("ports", c.ports, 0, 64);
      f.integer("port_cycles", c.port_cycles, 1, 100000);
    }
    if (full) {
      if (c.size_bytes % c.line_bytes != 0)
        fail(f.file(), f.path("ways"), "\"full\" needs size_bytes to be a whole number of lines");
      if (c.size_bytes / c.line_bytes > kMaxCacheWays)
        fail(f.file(), f.path("ways"),
             fmt::format("\"full\" would give {} ways; a cache has at most {}", c.size_bytes / c.line_bytes,
                         kMaxCacheWays));
      c.ways = c.size_bytes / c.line_bytes;
    }
  }
}

void check_cache(const std::string& file, const std::string& field, const CacheConfig& c) {
  const auto pow2 = [](uint32_t x) { return x != 0 && (x & (x - 1)) == 0; };
  if (!pow2(c.line_bytes)) fail(file, field + ".line_bytes", "must be a power of two");
  if (c.size_bytes % (static_cast<uint64_t>(c.ways) * c.line_bytes) != 0)
    fail(file, field + ".size_bytes", "must be a multiple of ways * line_bytes");
}

void read_memory(Fields& parent, MemoryConfig& m) {
  const auto* v = parent.get("memory");
  if (!v) return;
  const std::string field = parent.path("memory");
  Fields f(*v, parent.file(), field);
  f.boolean("ideal", m.ideal);
  f.integer("ideal_latency", m.ideal_latency, 1, 100000);
  read_cache(f, "l1", m.l1, true);
  read_cache(f, "l2", m.l2, false);
  f.integer("dram_latency", m.dram_latency, 1, 1000000);
  f.number("dram_latency_per_byte", m.dram_latency_per_byte);
  if (!(m.dram_latency_per_byte >= 0 && m.dram_latency_per_byte <= 1000))
    fail(parent.file(), field + ".dram_latency_per_byte", "must be in [0, 1000]");
  f.number("dram_bytes_per_cycle", m.dram_bytes_per_cycle);
  if (!(m.dram_bytes_per_cycle > 0 && m.dram_bytes_per_cycle <= 4096))
    fail(parent.file(), field + ".dram_bytes_per_cycle", "must be in (0, 4096]");
  f.integer("dram_max_outstanding", m.dram_max_outstanding, 1, 65536);
  f.name("tlm", [&](const std::string& s) {
    if (s == "lt") m.tlm = TlmStyle::LooselyTimed;
    else if (s == "at") m.tlm = TlmStyle::ApproximatelyTimed;
    else return false;
    return true;
  });
  f.integer("at_lookahead_cycles", m.at_lookahead_cycles, 1, 1000000);
  f.boolean("l2_lookups_in_time_order", m.l2_lookups_in_time_order);
  if (const auto* o = f.get("objects")) {  // present: object caches (hw/memory/object_caches.h)
    Fields fo(*o, parent.file(), field + ".objects");
    ObjectCachesConfig& oc = m.objects;
    oc.enabled = true;
    for (int k = 0; k < ObjectCachesConfig::kKinds; ++k) {
      const auto kind = static_cast<ObjectCachesConfig::Kind>(k);
      if (const auto* c = fo.get(object_cache_name(kind))) {
        Fields fc(*c, parent.file(), field + ".objects." + object_cache_name(kind));
        fc.integer("entries", oc.cache[k].entries, 0, 1u << 24);
        fc.integer("bytes", oc.cache[k].bytes, 0, 1u << 16);
      }
    }
    fo.integer("hit_latency", oc.hit_latency, 1, 100000);
    fo.integer("port_cycles", oc.port_cycles, 1, 100000);
    fo.integer("responses_per_cycle", oc.responses_per_cycle, 0, 1024);
    if (m.ideal) fail(parent.file(), field + ".objects", "takes memory.ideal false (the object caches are a memory of their own)");
  }
  check_cache(parent.file(), field + ".l1", m.l1);
  check_cache(parent.file(), field + ".l2", m.l2);
}

nlohmann::json controller_json(const ControllerConfig& c) {
  nlohmann::json j = {{"count", c.count}, {"latency", c.latency}, {"issue_interval", c.issue_interval}};
  for (int k = 0; k < ControllerConfig::kSteps; ++k)
    if (c.by_step[k].set)
      j["by_step"][controller_step_name(static_cast<ControllerConfig::Step>(k))] = {
          {"latency", c.by_step[k].latency}, {"issue_interval", c.by_step[k].issue_interval}};
  return j;
}

bool parse_dispatch(const std::string& s, DispatchPolicy& out) {
  if (s == "round-robin") out = DispatchPolicy::RoundRobin;
  else if (s == "least-loaded") out = DispatchPolicy::LeastLoaded;
  else return false;
  return true;
}

bool parse_missing_parents(const std::string& s, MissingParents& out) {
  if (s == "error") out = MissingParents::Error;
  else if (s == "independent") out = MissingParents::Independent;
  else return false;
  return true;
}

}  // namespace

const char* missing_parents_name(MissingParents m) {
  return m == MissingParents::Independent ? "independent" : "error";
}

const char* dispatch_policy_name(DispatchPolicy p) {
  return p == DispatchPolicy::RoundRobin ? "round-robin" : "least-loaded";
}

std::vector<std::string> preset_names() { return {"small", "large", "rtcore"}; }

HwConfig load_preset(const std::string& name, const std::string& origin) {
  bool known = false;
  for (const std::string& n : preset_names()) known |= n == name;
  if (!known) fail(origin, "hw.preset", "unknown preset '" + name + "' (presets: small, large, rtcore)");
  const std::string path = preset_path(name);
  HwConfig cfg;
  nlohmann::json j = read_config_json(path);
  if (j.is_object()) j.erase("preset");  // a preset file names itself; no recursion
  apply_hw_config(j, path, cfg);
  cfg.preset = name;
  return cfg;
}

void apply_hw_config(const nlohmann::json& j, const std::string& file, HwConfig& cfg) {
  Fields f(j, file, "hw");
  if (const auto* p = f.get("preset")) {
    if (!p->is_string()) fail(file, "hw.preset", "must be a string");
    cfg = load_preset(p->get<std::string>(), file);
  }
  f.number("clock_mhz", cfg.clock_mhz);
  if (!(cfg.clock_mhz >= 1 && cfg.clock_mhz <= 100000)) fail(file, "hw.clock_mhz", "must be in [1, 100000] MHz");
  f.integer("cores", cfg.cores, 1, 4096);
  f.integer("slots_per_core", cfg.slots_per_core, 1, 4096);
  if (static_cast<uint64_t>(cfg.cores) * cfg.slots_per_core > kMaxCount)
    fail(file, "hw.slots_per_core", "cores * slots_per_core must be at most 1048576");
  f.integer("stack_depth", cfg.stack_depth, 1, 128);
  f.name("dispatch", [&](const std::string& s) { return parse_dispatch(s, cfg.dispatch); });
  if (const auto* a = f.get("address_base")) {
    if (!a->is_number_unsigned() || a->get<uint64_t>() % 64 != 0 || a->get<uint64_t>() >= (1ull << 48))
      fail(file, "hw.address_base", "must be a multiple of 64 below 2^48");
    cfg.address_base = a->get<uint64_t>();
  }
  if (const auto* s = f.get("source")) {
    Fields fs(*s, file, "hw.source");
    fs.integer("issue_interval", cfg.source.issue_interval, 1, 100000);
    fs.integer("sign_bit_cycles", cfg.source.sign_bit_cycles, 0, 100000);
    fs.integer("emission_op_cycles", cfg.source.emission_op_cycles, 0, 100000);
    fs.integer("emission_width", cfg.source.emission_width, 0, 1024);
    fs.integer("emission_depth", cfg.source.emission_depth, 0, 100000);
    fs.integer("rays_per_cycle", cfg.source.rays_per_cycle, 1, 64);
    fs.integer("window", cfg.source.window, 0, 1u << 20);
    fs.boolean("dependencies", cfg.source.dependencies);
    fs.name("missing_parents", [&](const std::string& s) { return parse_missing_parents(s, cfg.source.missing_parents); },
            "error, independent");
    fs.boolean("bundles", cfg.source.bundles);
    fs.integer("bundle_cycles", cfg.source.bundle_cycles, 0, 100000);
    fs.integer("bundle_max", cfg.source.bundle_max, 1, 64);
  }
  if (const auto* s = f.get("shader")) {
    Fields fs(*s, file, "hw.shader");
    fs.integer("latency_cycles", cfg.shader.latency_cycles, 0, 1000000);
    fs.integer("cores", cfg.shader.cores, 0, 4096);
    fs.integer("simd_lanes", cfg.shader.simd_lanes, 1, 1024);
    fs.integer("ops_per_lane_cycle", cfg.shader.ops_per_lane_cycle, 1, 64);
    fs.integer("pipeline_latency", cfg.shader.pipeline_latency, 0, 100000);
    if (const auto* k = fs.get("latency_by_kind")) {
      Fields fk(*k, file, "hw.shader.latency_by_kind");
      for (int kind = 0; kind < kRayKindCount; ++kind) {
        uint32_t cycles = ShaderConfig::kUnset;
        fk.integer(ray_kind_name(static_cast<RayKind>(kind)), cycles, 0, 1000000);
        if (cycles != ShaderConfig::kUnset) cfg.shader.by_kind[static_cast<size_t>(kind)] = cycles;
      }
    }
  }
  read_unit(f, "box", cfg.box);
  if (const auto* v = f.get("box_low")) {  // as a unit, but a count of 0 (none) is allowed
    Fields fl(*v, file, "hw.box_low");
    fl.integer("count", cfg.box_low.count, 0, 64);
    fl.integer("latency", cfg.box_low.latency, 1, 100000);
    fl.integer("issue_interval", cfg.box_low.issue_interval, 1, 100000);
    fl.integer("share", cfg.box_low.share, 1, 4096);
  }
  if (const auto* v = f.get("triangle")) {
    // A latency or issue interval given without `derive` fixes the unit's timing
    // (an override of a preset's derivation); with `derive: true` they are
    // recomputed for each run's tester.
    Fields ft(*v, file, "hw.triangle");
    ft.integer("count", cfg.triangle.count, 1, 64);
    const bool fixed = ft.get("latency") || ft.get("issue_interval");
    ft.integer("latency", cfg.triangle.latency, 1, 100000);
    ft.integer("issue_interval", cfg.triangle.issue_interval, 1, 100000);
    ft.integer("share", cfg.triangle.share, 1, 4096);
    if (fixed) cfg.triangle_timing.derive = false;
    ft.boolean("derive", cfg.triangle_timing.derive);
    ft.integer("operators", cfg.triangle_timing.operators, 0, 100000);
    if (const auto* o = ft.get("operator_latency"))
      read_operator_latencies(*o, file, "hw.triangle.operator_latency", cfg.triangle_timing.op);
  }
  read_unit(f, "avoidance", cfg.avoidance);
  f.boolean("root_box_test", cfg.root_box_test);
  f.boolean("pop_culling", cfg.pop_culling);
  f.name("triangle_fetch", [&](const std::string& s) {
    if (s != "leaf" && s != "triangle") return false;
    cfg.per_triangle_fetch = s == "triangle";
    return true;
  }, "leaf, triangle");
  f.integer("triangle_fetch_cycles", cfg.triangle_fetch_cycles, 0, 100000);
  if (const auto* v = f.get("controller")) {
    Fields fc(*v, file, "hw.controller");
    fc.integer("count", cfg.controller.count, 0, 64);
    fc.integer("latency", cfg.controller.latency, 0, 100000);
    fc.integer("issue_interval", cfg.controller.issue_interval, 1, 100000);
    if (const auto* b = fc.get("by_step")) {
      Fields fb(*b, file, "hw.controller.by_step");
      for (int k = 0; k < ControllerConfig::kSteps; ++k) {
        const auto step = static_cast<ControllerConfig::Step>(k);
        const auto* t = fb.get(controller_step_name(step));
        if (!t) continue;
        const std::string where = std::string("hw.controller.by_step.") + controller_step_name(step);
        Fields ft(*t, file, where.c_str());
        ControllerStepTiming& timing = cfg.controller.by_step[k];
        timing = {true, cfg.controller.latency, cfg.controller.issue_interval};
        ft.integer("latency", timing.latency, 0, 100000);
        ft.integer("issue_interval", timing.issue_interval, 1, 100000);
      }
    }
  }
  read_memory(f, cfg.memory);
  if (const auto* s = f.get("sim")) {
    Fields fs(*s, file, "hw.sim");
    fs.integer("quantum_cycles", cfg.quantum_cycles, 1, 1u << 30);
    fs.integer("latency_bucket_cycles", cfg.latency_bucket_cycles, 1, 1u << 20);
    fs.integer("latency_buckets", cfg.latency_buckets, 1, 4096);
    fs.integer("warmup_rays", cfg.warmup_rays, uint64_t{0}, uint64_t{1} << 48);
    fs.integer("warmup_cycles", cfg.warmup_cycles, uint64_t{0}, uint64_t{1} << 48);
    fs.integer("interval_cycles", cfg.interval_cycles, uint64_t{1}, uint64_t{1} << 48);
    if (cfg.warmup_rays && cfg.warmup_cycles)
      throw ConfigError(file + ": field 'hw.sim.warmup_cycles': a warm-up by rays (hw.sim.warmup_rays) and by cycles "
                        "at once: set one of them");
  }
  const std::pair<const char*, const UnitConfig*> shared[] = {
      {"box", &cfg.box}, {"box_low", &cfg.box_low}, {"triangle", &cfg.triangle}, {"avoidance", &cfg.avoidance}};
  for (const auto& [key, unit] : shared)
    if (unit->share > cfg.cores)
      fail(file, std::string("hw.") + key + ".share",
           fmt::format("{} cores share one unit, but the accelerator has {} (hw.cores)", unit->share, cfg.cores));
}

HwConfig for_tester(HwConfig cfg, TesterKind kind) {
  if (cfg.triangle_timing.derive) {
    cfg.triangle.latency = derived_triangle_latency(kind, cfg.triangle_timing.op);
    cfg.triangle.issue_interval = derived_triangle_issue_interval(kind, cfg.triangle_timing.operators);
  }
  return cfg;
}

HwConfig resolve_hw_config(const std::string& path, const std::string& preset) {
  nlohmann::json hw = nlohmann::json::object();
  if (!path.empty()) {
    const nlohmann::json j = read_config_json(path);
    if (j.is_object() && j.contains("hw")) hw = j["hw"];
  }
  if (!preset.empty() && hw.is_object()) hw.erase("preset");  // the command line wins
  HwConfig cfg = load_preset(preset.empty() ? "small" : preset, "command line: option '--preset'");
  const std::string origin = path.empty() ? "command line" : path;
  apply_hw_config(hw, origin, cfg);
  // The memory's checks across fields, here where the file can be named (the
  // accelerator repeats them for a configuration built in code).
  try {
    check_memory_config(cfg.memory, static_cast<int>(cfg.cores));
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();  // "memory.l1.hit_latency: must be ..."
    const std::size_t colon = what.find(": ");
    fail(origin, "hw." + what.substr(0, colon), colon == std::string::npos ? what : what.substr(colon + 2));
  }
  return cfg;
}

nlohmann::json shader_config_json(const ShaderConfig& s) {
  nlohmann::json j = {{"latency_cycles", s.latency_cycles},
                      {"cores", s.cores},
                      {"simd_lanes", s.simd_lanes},
                      {"ops_per_lane_cycle", s.ops_per_lane_cycle},
                      {"pipeline_latency", s.pipeline_latency}};
  if (!s.any_by_kind()) return j;
  nlohmann::json& k = j["latency_by_kind"];
  for (int kind = 0; kind < kRayKindCount; ++kind)
    if (s.by_kind[static_cast<size_t>(kind)] != ShaderConfig::kUnset)
      k[ray_kind_name(static_cast<RayKind>(kind))] = s.by_kind[static_cast<size_t>(kind)];
  return j;
}

const char* controller_step_name(ControllerConfig::Step k) {
  switch (k) {
    case ControllerConfig::Start: return "start";
    case ControllerConfig::Node: return "node";
    case ControllerConfig::Leaf: return "leaf";
    case ControllerConfig::Refill: return "refill";
    default: return "?";
  }
}

nlohmann::json hw_config_json(const HwConfig& c) {
  const auto unit = [](const UnitConfig& u) {
    return nlohmann::json{
        {"count", u.count}, {"latency", u.latency}, {"issue_interval", u.issue_interval}, {"share", u.share}};
  };
  const auto cache = [](const CacheConfig& k) {
    return nlohmann::json{{"size_bytes", k.size_bytes}, {"ways", k.ways},   {"line_bytes", k.line_bytes},
                          {"hit_latency", k.hit_latency}, {"mshrs", k.mshrs},
                          {"merge_misses", k.merge_misses}};
  };
  const auto with_ports = [](nlohmann::json j, const CacheConfig& k) {
    j["ports"] = k.ports;
    j["port_cycles"] = k.port_cycles;
    return j;
  };
  const MemoryConfig& m = c.memory;
  nlohmann::json j = {{"preset", c.preset},
          {"clock_mhz", c.clock_mhz},
          {"cores", c.cores},
          {"slots_per_core", c.slots_per_core},
          {"stack_depth", c.stack_depth},
          {"dispatch", dispatch_policy_name(c.dispatch)},
          {"address_base", c.address_base},
          {"source",
           {{"issue_interval", c.source.issue_interval},
            {"sign_bit_cycles", c.source.sign_bit_cycles},
            {"emission_op_cycles", c.source.emission_op_cycles},
            {"emission_width", c.source.emission_width},
            {"emission_depth", c.source.emission_depth},
            {"rays_per_cycle", c.source.rays_per_cycle},
            {"window", c.source.window},
            {"dependencies", c.source.dependencies},
            {"missing_parents", missing_parents_name(c.source.missing_parents)},
            {"bundles", c.source.bundles},
            {"bundle_cycles", c.source.bundle_cycles},
            {"bundle_max", c.source.bundle_max}}},
          {"shader", shader_config_json(c.shader)},
          {"box", unit(c.box)},
          {"box_low", unit(c.box_low)},
          {"triangle", triangle_json(c)},
          {"avoidance", unit(c.avoidance)},
          {"root_box_test", c.root_box_test},
          {"pop_culling", c.pop_culling},
          {"triangle_fetch", c.per_triangle_fetch ? "triangle" : "leaf"},
          {"triangle_fetch_cycles", c.triangle_fetch_cycles},
          {"controller", controller_json(c.controller)},
          {"memory",
           {{"ideal", m.ideal},
            {"ideal_latency", m.ideal_latency},
            {"l1", with_ports(cache(m.l1), m.l1)},
            {"l2", cache(m.l2)},
            {"dram_latency", m.dram_latency},
            {"dram_latency_per_byte", m.dram_latency_per_byte},
            {"dram_bytes_per_cycle", m.dram_bytes_per_cycle},
            {"dram_max_outstanding", m.dram_max_outstanding},
            {"tlm", tlm_style_name(m.tlm)},
            {"at_lookahead_cycles", m.at_lookahead_cycles},
            {"l2_lookups_in_time_order", m.l2_lookups_in_time_order}}},
          {"sim",
           {{"quantum_cycles", c.quantum_cycles},
            {"latency_bucket_cycles", c.latency_bucket_cycles},
            {"latency_buckets", c.latency_buckets},
            {"warmup_rays", c.warmup_rays},
            {"warmup_cycles", c.warmup_cycles},
            {"interval_cycles", c.interval_cycles}}}};
  if (m.objects.enabled) {
    nlohmann::json o = {{"hit_latency", m.objects.hit_latency},
                        {"port_cycles", m.objects.port_cycles},
                        {"responses_per_cycle", m.objects.responses_per_cycle}};
    for (int k = 0; k < ObjectCachesConfig::kKinds; ++k)
      o[object_cache_name(static_cast<ObjectCachesConfig::Kind>(k))] = {{"entries", m.objects.cache[k].entries},
                                                                          {"bytes", m.objects.cache[k].bytes}};
    j["memory"]["objects"] = std::move(o);
  }
  return j;
}

}  // namespace vbsim::hw
