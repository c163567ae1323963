// The energy and area model, by hand on counts chosen for the test.
#include <catch2/catch.hpp>

#include "energy/operation_energy.h"
#include "hw/observe/hw_energy.h"
#include "trace_test_support.h"

using namespace vbsim;

namespace {

/// Every operation 1 pJ and 1 mm², a register bit 0.5 pJ and 0.25 mm².
TechFile unit_tech() {
  TechFile t;
  t.path = "unit";
  t.op_pj.fill(1);
  t.op_mm2.fill(1);
  t.register_bit_pj = 0.5;
  t.register_bit_mm2 = 0.25;
  t.sram = {{1024, 4}, {4096, 16}};
  t.sram_bit_mm2 = 1e-6;
  t.dram_64bit_pj = 1000;
  t.leakage_w_per_mm2 = 0.5;
  return t;
}

SelfIntersectionMethod validity_bit() {
  SelfIntersectionMethod m;
  std::string error;
  REQUIRE(parse_method("validity-bit", m, error));
  return m;
}

}  // namespace

TEST_CASE("energy: the operations of a replay, priced by hand", "[energy]") {
  ReplayStats s;
  KindStats& k = s.by_kind[static_cast<int>(RayKind::Reflect)];  // two rays leaving a surface
  k.rays = 2;
  k.children = 2;
  KindStats& camera = s.by_kind[static_cast<int>(RayKind::Primary)];  // and a camera ray: no sign bit
  camera.rays = 1;
  k.traversal.box_tests = 5;
  k.traversal.triangle_tests = 3;
  k.traversal.stack_pushes = 1;
  k.traversal.stack_pops = 1;
  k.candidates.candidates = 2;
  k.candidates.suspects = 1;
  const OperationEnergy e = operation_energy(unit_tech(), validity_bit(), TesterKind::ThreeHalfPlane, s);
  CHECK(e.emission == 2 * 6);             // the sign bit's dot and compare per child ray
  CHECK(e.result == 0);
  CHECK(e.box == 5 * 20 + 3 * 15);        // box tests, per-ray set-ups
  CHECK(e.triangle == 3 * 63 + 3 * 9);    // triangle tests, per-ray set-ups
  CHECK(e.candidate_filter == 2 * 1);     // the sign compare
  CHECK(e.avoidance == 1 * 64);           // the default tests of one suspect
  CHECK(e.stack == (3 + 48) + (5 + 48));  // push, pop: operations and 96 bits at 0.5 pJ
  CHECK(e.ray_records == 3 * 260 * 0.5);  // each ray's 260-bit record written once
  CHECK(e.total() == 12 + 145 + 216 + 2 + 64 + 104 + 390);
  CHECK(e.method == 12 + 2 + 64 + 3 * 1 * 0.5);  // with the one extra record bit
  const nlohmann::json j = operation_energy_json(unit_tech(), e, 3);
  CHECK(j["per_ray_pj"].get<double>() == e.total() / 3);
  CHECK(j["mrays_per_j"].get<double>() == Approx(3 / (e.total() * 1e-12) / 1e6));
}

TEST_CASE("energy: unit areas from their operators, shared over the issue interval", "[energy]") {
  hw::HwConfig cfg;
  cfg.cores = 2;
  cfg.slots_per_core = 4;
  cfg.stack_depth = 2;
  cfg.box = {1, 8, 1};
  cfg.triangle = {1, 20, 2};
  cfg.avoidance = {1, 6, 1};
  cfg.memory.ideal = true;
  ReplayOptions opt;
  opt.method = validity_bit();
  const hw::HwArea a = hw::hw_area(unit_tech(), cfg, opt);
  CHECK(a.box_unit == 40 + 15);  // two boxes' operators and the set-up
  ReplayOptions wide = opt;
  wide.bvh.width = 8;
  CHECK(hw::hw_area(unit_tech(), cfg, wide).box_unit == 8 * 20 + 15);  // a wide node's eight boxes at once
  // Issue interval 2: ceil(kind / 2) operators of (three-half-plane + the sign
  // compare): fadd 11, fmul 10, fdiv 2, fcmp 8, fsel 1, iadd 1; set-up 9.
  CHECK(a.triangle_tester == 11 + 10 + 2 + 8 + 1 + 1 + 9);
  CHECK(a.avoidance_unit == 64);
  CHECK(a.emission_unit == 6);
  CHECK(a.ray_records == 4 * 260 * 0.25);
  CHECK(a.method_record_bits == 4 * 1 * 0.25);
  CHECK(a.stack == 4 * 2 * 96 * 0.25);
  CHECK(a.l1_cache == 0);
  CHECK(a.chip() == 2 * 55 + 2 * 42 + 2 * 64 + 6 + 2 * (260 + 192));
  // A method without the avoidance unit has none.
  opt.method = SelfIntersectionMethod{};
  CHECK(hw::hw_area(unit_tech(), cfg, opt).avoidance_units == 0);
}

TEST_CASE("energy: memory, leakage and per-instance energy of a cycle-level run, by hand", "[energy]") {
  hw::HwConfig cfg;
  cfg.cores = 1;
  cfg.slots_per_core = 1;
  cfg.stack_depth = 1;
  cfg.clock_mhz = 1000;
  cfg.memory.l1 = {1024, 4, 64, 2, 8};
  cfg.memory.l2 = {4096, 8, 64, 14, 32};
  ReplayOptions opt;  // method none, three-half-plane
  ReplayStats s;
  s.by_kind[static_cast<int>(RayKind::Primary)].rays = 1;
  hw::HwCounters c;
  c.rays = 1;
  c.cycles = 1000;  // 1 microsecond
  c.spills = 1;
  const nlohmann::json memory = {{"l1", {{"accesses", 3}, {"misses", 1}}},
                                 {"l2", {{"accesses", 1}, {"misses", 1}}},
                                 {"dram", {{"bytes", 64}}}};
  const TechFile t = unit_tech();
  const nlohmann::json e = hw::hw_energy_json(t, cfg, opt, s, c, memory);
  // L1 (1 KiB, 4 pJ per 64 bits): 4 line accesses x 8 words; L2 (4 KiB, 16 pJ): 2 x 8.
  CHECK(e["dynamic_pj"]["l1"].get<double>() == 4 * 8 * 4);
  CHECK(e["dynamic_pj"]["l2"].get<double>() == 2 * 8 * 16);
  CHECK(e["dynamic_pj"]["dram"].get<double>() == 8 * 1000);
  CHECK(e["dynamic_pj"]["stack_spills"].get<double>() == 2 * 4);  // 16 bytes through the L1
  const double ops = 15 + 9 + 259 * 0.5;                              // set-ups and the record
  CHECK(e["dynamic_total_pj"].get<double>() == Approx(ops + 128 + 256 + 8000 + 8));
  // Leakage: 0.5 W/mm² over the chip's area for 1 µs, in pJ.
  const double chip = hw::hw_area(t, cfg, opt).chip();
  CHECK(e["static_pj"].get<double>() == Approx(chip * 0.5 * 1e-6 * 1e12));
  CHECK(e["per_unit_instance_pj"]["l2_cache"].get<double>() ==
        Approx(256 + 4096 * 8 * 1e-6 * 0.5 * 1e-6 * 1e12));
}

TEST_CASE("energy: an emission unit's operators are shared over the cycles its width gives a ray", "[energy]") {
  hw::HwConfig cfg;
  cfg.memory.ideal = true;
  ReplayOptions opt;
  std::string error;
  REQUIRE(parse_method("tmin", opt.method, error));
  // tmin: |d| = sqrt(dot(d, d)), eps / |d|: fmul 3, fadd 2, fsqrt 1, fdiv 1 (7 operations).
  cfg.source.emission_width = 0;  // no unit: one operator per operation
  CHECK(hw::hw_area(unit_tech(), cfg, opt).emission_unit == 7);
  cfg.source.emission_width = 8;  // 7 operations in one cycle: still one operator each
  CHECK(hw::hw_area(unit_tech(), cfg, opt).emission_unit == 7);
  cfg.source.emission_width = 2;  // ceil(7 / 2) = 4 cycles a ray: one operator of each kind
  CHECK(hw::hw_area(unit_tech(), cfg, opt).emission_unit == 4);
}
