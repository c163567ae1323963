// The hardware configuration: presets load, fields apply, and every bad value
// is an error naming its JSON field.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "hw/hw_config.h"
#include "replay/replay_config.h"
#include "replay/replay_stats.h"

using namespace vbsim;
using namespace vbsim::hw;

TEST_CASE("presets load and round-trip through their JSON form", "[hwconfig]") {
  for (const std::string& name : preset_names()) {
    const HwConfig c = load_preset(name, "test");
    CHECK(c.preset == name);
    nlohmann::json j = hw_config_json(c);
    HwConfig back;
    apply_hw_config(j, "test", back);  // names the preset, then sets every field again
    CHECK(hw_config_json(back) == j);
  }
  CHECK(load_preset("large", "t").cores > load_preset("small", "t").cores);
}

TEST_CASE("hw fields apply on top of a preset", "[hwconfig]") {
  HwConfig c;
  apply_hw_config(nlohmann::json::parse(R"({"preset": "large", "cores": 3, "box": {"latency": 9},
                                            "memory": {"ideal": true, "l1": {"ways": 8}}})"),
                  "f.json", c);
  CHECK(c.preset == "large");
  CHECK(c.cores == 3);
  CHECK(c.box.latency == 9);
  CHECK(c.box.count == load_preset("large", "t").box.count);
  CHECK(c.memory.ideal);
  CHECK(c.memory.l1.ways == 8);
}

TEST_CASE("the shading latency by the parent's kind applies where given and round-trips", "[hwconfig]") {
  HwConfig c;
  apply_hw_config(nlohmann::json::parse(R"({"shader": {"latency_cycles": 100,
                                                       "latency_by_kind": {"primary": 7, "diffuse": 0}}})"),
                  "f.json", c);
  CHECK(c.shader.latency_for(RayKind::Primary) == 7);
  CHECK(c.shader.latency_for(RayKind::Diffuse) == 0);
  CHECK(c.shader.latency_for(RayKind::Reflect) == 100);
  CHECK(c.shader.latency_for(RayKind::Shadow) == 100);
  const nlohmann::json j = hw_config_json(c);
  CHECK(j["shader"] == nlohmann::json::parse(R"({"latency_cycles": 100,
                                                "latency_by_kind": {"primary": 7, "diffuse": 0},
                                                "cores": 0, "simd_lanes": 64, "ops_per_lane_cycle": 1,
                                                "pipeline_latency": 4})"));
  HwConfig back;
  apply_hw_config(j, "test", back);
  CHECK(hw_config_json(back) == j);
  CHECK(hw_config_json(load_preset("small", "t"))["shader"] ==
        nlohmann::json::parse(R"({"latency_cycles": 200, "cores": 4, "simd_lanes": 64, "ops_per_lane_cycle": 1,
                                  "pipeline_latency": 4})"));
}

TEST_CASE("the controller's timing by kind of step applies where given and round-trips", "[hwconfig]") {
  HwConfig c;
  apply_hw_config(nlohmann::json::parse(R"({"controller": {"count": 1, "latency": 10, "issue_interval": 2,
                                           "by_step": {"node": {"issue_interval": 1}, "leaf": {"latency": 4}}}})"),
                  "f.json", c);
  CHECK(c.controller.step_interval(ControllerConfig::Node) == 1);
  CHECK(c.controller.step_latency(ControllerConfig::Node) == 10);  // unset: the controller's
  CHECK(c.controller.step_interval(ControllerConfig::Leaf) == 2);
  CHECK(c.controller.step_latency(ControllerConfig::Leaf) == 4);
  CHECK(c.controller.step_latency(ControllerConfig::Start) == 10);
  CHECK(c.controller.step_interval(ControllerConfig::Refill) == 2);
  const nlohmann::json j = hw_config_json(c);
  CHECK(j["controller"]["by_step"] == nlohmann::json::parse(R"({"node": {"latency": 10, "issue_interval": 1},
                                                               "leaf": {"latency": 4, "issue_interval": 2}})"));
  HwConfig back;
  apply_hw_config(j, "test", back);
  CHECK(hw_config_json(back) == j);
  CHECK_FALSE(hw_config_json(load_preset("small", "t"))["controller"].contains("by_step"));
}

TEST_CASE("bad hw values are errors naming the field", "[hwconfig]") {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"cores": 0})", "field 'hw.cores'"},
      {R"({"cores": 2.5})", "field 'hw.cores'"},
      {R"({"clock_mhz": -1})", "field 'hw.clock_mhz'"},
      {R"({"stack_depth": 129})", "field 'hw.stack_depth'"},
      {R"({"dispatch": "random"})", "field 'hw.dispatch'"},
      {R"({"preset": "huge"})", "field 'hw.preset'"},
      {R"({"address_base": 100})", "field 'hw.address_base'"},
      {R"({"box": {"latency": "x"}})", "field 'hw.box.latency'"},
      {R"({"shader": {"latency_by_kind": {"bounce": 5}}})", "field 'hw.shader.latency_by_kind.bounce'"},
      {R"({"box_low": {"count": -1}})", "field 'hw.box_low.count'"},
      {R"({"box_low": {"latency": 0}})", "field 'hw.box_low.latency'"},
      {R"({"triangle_fetch": "each"})", "field 'hw.triangle_fetch'"},
      {R"({"pop_culling": 1})", "field 'hw.pop_culling'"},
      {R"({"controller": {"by_step": {"box": {"latency": 1}}}})", "field 'hw.controller.by_step.box'"},
      {R"({"memory": {"objects": {"nodes": {"entries": 1}}}})", "field 'hw.memory.objects.nodes'"},
      {R"({"memory": {"objects": {"node": {"entries": -1}}}})", "field 'hw.memory.objects.node.entries'"},
      {R"({"memory": {"ideal": true, "objects": {}}})", "field 'hw.memory.objects'"},
      {R"({"controller": {"by_step": {"node": {"issue_interval": 0}}}})",
       "field 'hw.controller.by_step.node.issue_interval'"},
      {R"({"shader": {"latency_by_kind": {"diffuse": -1}}})", "field 'hw.shader.latency_by_kind.diffuse'"},
      {R"({"shader": {"latency_by_kind": [1]}})", "field 'hw.shader.latency_by_kind'"},
      {R"({"triangle": {"count": 0}})", "field 'hw.triangle.count'"},
      {R"({"avoidance": {"issue_interval": 0}})", "field 'hw.avoidance.issue_interval'"},
      {R"({"avoidance": {"share": 0}})", "field 'hw.avoidance.share'"},
      {R"({"cores": 4, "avoidance": {"share": 5}})", "field 'hw.avoidance.share'"},
      {R"({"cores": 2, "box": {"share": 2}, "triangle": {"share": 3}})", "field 'hw.triangle.share'"},
      {R"({"source": {"speed": 1}})", "field 'hw.source.speed'"},
      {R"({"memory": {"ideal": 1}})", "field 'hw.memory.ideal'"},
      {R"({"memory": {"l1": {"line_bytes": 48}}})", "field 'hw.memory.l1.line_bytes'"},
      {R"({"memory": {"l2": {"size_bytes": 1000}}})", "field 'hw.memory.l2.size_bytes'"},
      {R"({"memory": {"l1": {"ways": "half"}}})", "field 'hw.memory.l1.ways'"},
      {R"({"memory": {"l1": {"ways": 65537}}})", "field 'hw.memory.l1.ways'"},
      {R"({"memory": {"l2": {"ways": "full", "size_bytes": 8388608}}})", "field 'hw.memory.l2.ways'"},
      {R"({"memory": {"dram_bytes_per_cycle": 0}})", "field 'hw.memory.dram_bytes_per_cycle'"},
      {R"({"memory": {"l3": {}}})", "field 'hw.memory.l3'"},
      {R"({"memory": {"dram_latency_per_byte": -0.5}})", "field 'hw.memory.dram_latency_per_byte'"},
      {R"({"memory": {"l1": {"ports": 65}}})", "field 'hw.memory.l1.ports'"},
      {R"({"memory": {"l1": {"port_cycles": 0}}})", "field 'hw.memory.l1.port_cycles'"},
      {R"({"memory": {"l2": {"ports": 2}}})", "field 'hw.memory.l2.ports'"},
      {R"({"sim": {"quantum_cycles": 0}})", "field 'hw.sim.quantum_cycles'"},
      {R"({"cores": 4096, "slots_per_core": 4096})", "field 'hw.slots_per_core'"},
      {R"({"bogus": true})", "field 'hw.bogus'"},
  };
  for (const auto& [text, field] : cases) {
    INFO(text);
    HwConfig c;
    CHECK_THROWS_WITH(apply_hw_config(nlohmann::json::parse(text), "cfg.json", c),
                      Catch::StartsWith("cfg.json: ") && Catch::Contains(field));
  }
}

TEST_CASE("caches of any number of sets, and fully associative ones", "[hwconfig]") {
  HwConfig c;
  // 3 sets of 4 ways of 64 bytes; 5 sets of 1 way.
  apply_hw_config(nlohmann::json::parse(R"({"memory": {"l1": {"size_bytes": 768, "ways": 4},
                                            "l2": {"size_bytes": 320, "ways": 1}}})"),
                  "f.json", c);
  CHECK(c.memory.l1.size_bytes / (c.memory.l1.ways * c.memory.l1.line_bytes) == 3);
  CHECK(c.memory.l2.size_bytes / (c.memory.l2.ways * c.memory.l2.line_bytes) == 5);
  // "full": one set holding every line, whatever the order of the fields; the
  // echo is the number of ways, which reads back to the same cache.
  HwConfig f;
  apply_hw_config(nlohmann::json::parse(R"({"memory": {"l1": {"ways": "full", "size_bytes": 1024, "line_bytes": 32}}})"),
                  "f.json", f);
  CHECK(f.memory.l1.ways == 32);
  CHECK(hw_config_json(f)["memory"]["l1"]["ways"] == 32);
  // The largest fully associative cache: 65,536 lines.
  apply_hw_config(nlohmann::json::parse(R"({"memory": {"l2": {"ways": "full", "size_bytes": 4194304}}})"), "f.json", f);
  CHECK(f.memory.l2.ways == 65536);
}

TEST_CASE("a replay config file may carry an hw object", "[hwconfig]") {
  ReplayOptions opt;
  CHECK_NOTHROW(apply_replay_config(nlohmann::json::parse(R"({"method": "primid", "hw": {"cores": 2}})"), "f", opt));
  CHECK(opt.method.primid);
}

TEST_CASE("a replay config's bvh build options are read, checked and echoed", "[hwconfig][bvh-options]") {
  ReplayOptions opt;
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"quality": "low", "max_leaf_size": 16, "traversal_cost": 4}})"),
                      "f", opt);
  CHECK(opt.bvh.quality == BvhQuality::Low);
  CHECK(opt.bvh.max_leaf_size == 16);
  CHECK(opt.bvh.traversal_cost == 4.0f);
  CHECK(opt.bvh.builder == BvhBuilder::Embree);  // the default
  const nlohmann::json echo = replay_config_json(opt)["bvh"];
  CHECK(echo == nlohmann::json::parse(
                    R"({"builder": "embree", "quality": "low", "max_leaf_size": 16, "traversal_cost": 4.0, "width": 2,
                        "sah_block_size": 1})"));
  ReplayOptions back;
  apply_replay_config(nlohmann::json{{"bvh", echo}}, "f", back);
  CHECK(back.bvh == opt.bvh);
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"builder": "sweep-sah"}})"), "f", back);
  CHECK(back.bvh.builder == BvhBuilder::SweepSah);
  CHECK(replay_config_json(back)["bvh"]["builder"] == "sweep-sah");
  CHECK_FALSE(back.bvh == opt.bvh);
  // Nodes of two precisions: present means on; echoed, and read back.
  ReplayOptions marked;
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"low_precision": {"t_trav_low": 0.4}}})"), "f", marked);
  CHECK(marked.bvh.low_precision == BvhPrecisionMarking{true, 7, 0.5, 0.4});
  const nlohmann::json lp = replay_config_json(marked)["bvh"]["low_precision"];
  CHECK(lp == nlohmann::json::parse(
                  R"({"mantissa_bits": 7, "t_trav_high": 0.5, "t_trav_low": 0.4, "narrow_arithmetic": false})"));
  ReplayOptions narrow;
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"low_precision": {"narrow_arithmetic": true}}})"), "f", narrow);
  CHECK(narrow.bvh.low_precision.narrow_arithmetic);
  CHECK_FALSE(narrow.bvh == marked.bvh);
  ReplayOptions marked_back;
  apply_replay_config(nlohmann::json{{"bvh", replay_config_json(marked)["bvh"]}}, "f", marked_back);
  CHECK(marked_back.bvh == marked.bvh);
  CHECK_FALSE(replay_config_json(opt)["bvh"].contains("low_precision"));
  // The node width: read, echoed, read back.
  ReplayOptions wide;
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"width": 8}})"), "f", wide);
  CHECK(wide.bvh.width == 8);
  ReplayOptions wide_back;
  apply_replay_config(nlohmann::json{{"bvh", replay_config_json(wide)["bvh"]}}, "f", wide_back);
  CHECK(wide_back.bvh == wide.bvh);
  CHECK_FALSE(wide.bvh == opt.bvh);
  // The SAH's block: read, echoed, read back.
  ReplayOptions blocks;
  apply_replay_config(nlohmann::json::parse(R"({"bvh": {"sah_block_size": 4}})"), "f", blocks);
  CHECK(blocks.bvh.sah_block_size == 4);
  CHECK(replay_config_json(blocks)["bvh"]["sah_block_size"] == 4);
  ReplayOptions blocks_back;
  apply_replay_config(nlohmann::json{{"bvh", replay_config_json(blocks)["bvh"]}}, "f", blocks_back);
  CHECK(blocks_back.bvh == blocks.bvh);
  CHECK_FALSE(blocks.bvh == ReplayOptions{}.bvh);
  for (const char* bad : {R"({"bvh": {"quality": "best"}})", R"({"bvh": {"max_leaf_size": 33}})",
                          R"({"bvh": {"traversal_cost": 0}})", R"({"bvh": {"leaves": 2}})",
                          R"({"bvh": {"builder": "sah"}})", R"({"bvh": {"low_precision": {"mantissa_bits": 23}}})",
                          R"({"bvh": {"low_precision": {"t_trav_low": -1}}})",
                          R"({"bvh": {"low_precision": {"bits": 7}}})", R"({"bvh": {"width": 3}})",
                          R"({"bvh": {"width": 16}})", R"({"bvh": {"width": 4, "low_precision": {}}})",
                          R"({"bvh": {"sah_block_size": 3}})", R"({"bvh": {"sah_block_size": 0}})",
                          R"({"bvh": {"sah_block_size": 32}})", R"({"bvh": {"sah_block_size": 4.5}})"}) {
    INFO(bad);
    ReplayOptions o;
    CHECK_THROWS_WITH(apply_replay_config(nlohmann::json::parse(bad), "cfg.json", o),
                      Catch::StartsWith("cfg.json: field 'bvh."));
  }
}

TEST_CASE("a unit's sharing: read, written back, and the groups it makes", "[hwconfig][share]") {
  HwConfig c;
  apply_hw_config(nlohmann::json::parse(R"({"cores": 10, "avoidance": {"share": 4}, "box_low": {"count": 1, "share": 10}})"),
                  "cfg.json", c);
  CHECK(c.avoidance.share == 4);
  CHECK(unit_groups(c.avoidance, c.cores) == 3);  // cores 0-3, 4-7, 8-9
  CHECK(unit_groups(c.box_low, c.cores) == 1);
  CHECK(unit_groups(c.box, c.cores) == 10);
  const nlohmann::json j = hw_config_json(c);
  CHECK(j["avoidance"]["share"] == 4);
  CHECK(j["box"]["share"] == 1);
  HwConfig back;
  apply_hw_config(j, "back.json", back);
  CHECK(back.avoidance.share == 4);
  CHECK(back.box_low.share == 10);
}
