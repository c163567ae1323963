#include "hw/observe/hw_energy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "datapath/bvh_stepper.h"
#include "datapath/datapath_ops.h"
#include "datapath/method_costs.h"
#include "datapath/ray.h"
#include "energy/operation_energy.h"

namespace vbsim::hw {

namespace {

/// The operators of a pipeline that takes an operation every `interval` cycles.
OpCounts shared_over(const OpCounts& c, uint32_t interval) {
  const int k = static_cast<int>(interval < 1 ? 1 : interval);
  const auto up = [k](int n) { return (n + k - 1) / k; };
  OpCounts s;
  s.fadd = up(c.fadd), s.fmul = up(c.fmul), s.fma = up(c.fma), s.fdiv = up(c.fdiv), s.fsqrt = up(c.fsqrt);
  s.fcmp = up(c.fcmp), s.fsel = up(c.fsel), s.iadd = up(c.iadd), s.ishift = up(c.ishift), s.cvt = up(c.cvt);
  return s;
}

double cache_bits(const CacheConfig& c) { return 8.0 * c.size_bytes; }

/// Bytes of one object cache (memory.objects): entries x object bytes (a
/// cache whose objects are the reads' own priced at 64 bytes an entry).
double object_cache_bytes(const ObjectCacheConfig& c) { return double(c.entries) * (c.bytes ? c.bytes : 64); }

const ReplacedUnit* find_unit(const ReplacedUnits& replaced, const char* unit) {
  for (const ReplacedUnit& r : replaced)
    if (r.unit == unit) return &r;
  return nullptr;
}

/// The declared inventory of a replaced unit that is priced, else null.
const UnitInventory* inventory_of(const ReplacedUnit* r) { return r && r->priced() ? &*r->inventory : nullptr; }

nlohmann::json replaced_json(const ReplacedUnits& replaced) {
  nlohmann::json list = nlohmann::json::array();
  for (const ReplacedUnit& r : replaced)
    list.push_back({{"unit", r.unit}, {"instance", r.instance}, {"priced", r.priced()}});
  return list;
}

bool all_priced(const ReplacedUnits& replaced) {
  for (const ReplacedUnit& r : replaced)
    if (!r.priced()) return false;
  return true;
}

}  // namespace

double HwArea::chip() const {
  return box_unit * box_units + triangle_tester * triangle_testers + avoidance_unit * avoidance_units +
         emission_unit * emission_lanes + (ray_records + stack + l1_cache) * cores + l2_cache;
}

HwArea hw_area(const TechFile& t, const HwConfig& given, const ReplayOptions& opt, const ReplacedUnits& replaced) {
  const HwConfig cfg = for_tester(given, opt.tester);  // the tester's own issue interval
  const MethodOps mo = method_ops(opt.method);
  HwArea a;
  a.cores = cfg.cores;
  // A low-precision pool's units are priced as full-precision ones (an upper bound).
  a.box_units = unit_groups(cfg.box, cfg.cores) * cfg.box.count + unit_groups(cfg.box_low, cfg.cores) * cfg.box_low.count;
  a.triangle_testers = unit_groups(cfg.triangle, cfg.cores) * cfg.triangle.count;
  a.avoidance_units =
      opt.method.validity_bit && mo.suspect.total() > 0 ? unit_groups(cfg.avoidance, cfg.cores) * cfg.avoidance.count : 0;
  a.emission_lanes = mo.emission.total() > 0 ? cfg.source.rays_per_cycle : 0;
  // A box unit tests every child box of a node in one operation: 2, 4 or 8 (bvh.width).
  a.box_unit = t.area_mm2(shared_over(opt.bvh.width * box_test_ops(), cfg.box.issue_interval)) +
               t.area_mm2(box_setup_ops());
  a.triangle_tester = t.area_mm2(shared_over(triangle_test_ops(opt.tester) + mo.candidate, cfg.triangle.issue_interval)) +
                      t.area_mm2(triangle_setup_ops(opt.tester));
  a.avoidance_unit = a.avoidance_units ? t.area_mm2(shared_over(mo.suspect, cfg.avoidance.issue_interval)) : 0.0;
  // Replaced units: their declared operators and register bits, or nothing.
  if (const ReplacedUnit* r = find_unit(replaced, "box_unit")) {
    const UnitInventory* i = inventory_of(r);
    a.box_unit = i ? t.area_mm2(shared_over(opt.bvh.width * i->per_operation, cfg.box.issue_interval)) +
                         t.area_mm2(i->per_ray) + i->storage_bits * t.register_bit_mm2
                   : 0.0;
  }
  if (const ReplacedUnit* r = find_unit(replaced, "triangle_tester")) {
    const UnitInventory* i = inventory_of(r);
    a.triangle_tester = i ? t.area_mm2(shared_over(i->per_operation + mo.candidate, cfg.triangle.issue_interval)) +
                                t.area_mm2(i->per_ray) + i->storage_bits * t.register_bit_mm2
                          : 0.0;
  }
  if (const ReplacedUnit* r = find_unit(replaced, "avoidance_unit")) {
    const UnitInventory* i = inventory_of(r);
    a.avoidance_unit = i && a.avoidance_units ? t.area_mm2(shared_over(i->per_operation, cfg.avoidance.issue_interval)) +
                                                    i->storage_bits * t.register_bit_mm2
                                              : 0.0;
  }
  // An emission unit of `emission_width` starts that many operations a cycle, so a
  // ray's n operations share each operator kind over ceil(n / width) cycles; with
  // no unit, one operator per operation (a fully pipelined lane).
  const uint32_t width = cfg.source.emission_width;
  const int n = mo.emission.total();
  const uint32_t interval = width > 0 && n > 0 ? (static_cast<uint32_t>(n) + width - 1) / width : 1;
  a.emission_unit = t.area_mm2(shared_over(mo.emission, interval)) + t.area_mm2(mo.result);
  if (find_unit(replaced, "ray_source")) a.emission_unit = 0;
  const double slots = cfg.slots_per_core;
  a.ray_records = slots * opt.method.bits_per_ray() * t.register_bit_mm2;
  a.method_record_bits = slots * (opt.method.bits_per_ray() - kBaseRayBits) * t.register_bit_mm2;
  a.stack = slots * cfg.stack_depth * kStackEntryBits * t.register_bit_mm2;
  if (cfg.memory.objects.enabled && !cfg.memory.ideal) {  // a core's object caches stand in its L1's place; no L2
    double bytes = 0;
    for (const ObjectCacheConfig& c : cfg.memory.objects.cache) bytes += object_cache_bytes(c);
    a.l1_cache = 8.0 * bytes * t.sram_bit_mm2;
  } else if (!cfg.memory.ideal) {
    a.l1_cache = cache_bits(cfg.memory.l1) * t.sram_bit_mm2;
    a.l2_cache = cache_bits(cfg.memory.l2) * t.sram_bit_mm2;
  }
  if (find_unit(replaced, "l1_cache")) a.l1_cache = 0;
  if (find_unit(replaced, "l2_cache")) a.l2_cache = 0;
  return a;
}

nlohmann::json hw_area_json(const TechFile& t, const HwArea& a, const ReplacedUnits& replaced) {
  nlohmann::json j = {{"tech", t.path},
          {"per_instance_mm2",
           {{"box_unit", a.box_unit},
            {"triangle_tester", a.triangle_tester},
            {"avoidance_unit", a.avoidance_unit},
            {"emission_lane", a.emission_unit},
            {"ray_records_per_core", a.ray_records},
            {"stack_per_core", a.stack},
            {"l1_cache", a.l1_cache},
            {"l2_cache", a.l2_cache}}},
          {"instances",
           {{"box_unit", a.box_units},
            {"triangle_tester", a.triangle_testers},
            {"avoidance_unit", a.avoidance_units},
            {"emission_lane", a.emission_lanes},
            {"core", a.cores},
            {"l2_cache", a.l2_cache > 0 ? 1 : 0}}},
          {"chip_mm2", a.chip()},
          {"avoidance_units_mm2", a.avoidance_units_chip()},
          {"ray_record_bits_mm2", a.ray_records * a.cores},
          {"method_record_bits_mm2", a.method_record_bits_chip()}};
  if (!replaced.empty()) {
    j["replaced_units"] = replaced_json(replaced);
    j["priced"] = all_priced(replaced);
  }
  return j;
}

std::string hw_area_table(const TechFile& t, const HwArea& a) {
  std::string s = fmt::format("area ({}: {})\n", t.path, t.name);
  s += fmt::format("  {:<22} {:>10} {:>6} {:>12}\n", "instance", "mm2 each", "count", "mm2 total");
  const auto row = [&s](const char* name, double each, uint32_t n) {
    s += fmt::format("  {:<22} {:>10.5f} {:>6} {:>12.5f}\n", name, each, n, each * n);
  };
  row("box_unit", a.box_unit, a.box_units);
  row("triangle_tester", a.triangle_tester, a.triangle_testers);
  row("avoidance_unit", a.avoidance_unit, a.avoidance_units);
  row("emission_lane", a.emission_unit, a.emission_lanes);
  row("ray_records (core)", a.ray_records, a.cores);
  row("stack (core)", a.stack, a.cores);
  row("l1_cache", a.l1_cache, a.cores);
  row("l2_cache", a.l2_cache, a.l2_cache > 0 ? 1 : 0);
  s += fmt::format("  chip {:.4f} mm2; the avoidance units {:.5f} mm2, the method's ray-record bits {:.5f} mm2\n",
                   a.chip(), a.avoidance_units_chip(), a.method_record_bits_chip());
  return s;
}

namespace {

std::string size_text(double bytes) {
  if (bytes >= 1048576 && std::fmod(bytes, 1048576) == 0) return fmt::format("{:g} MB", bytes / 1048576);
  if (bytes >= 1024 && std::fmod(bytes, 1024) == 0) return fmt::format("{:g} KB", bytes / 1024);
  return fmt::format("{:g} bytes", bytes);
}

}  // namespace

std::string sram_range_lines(const TechFile& t, const HwConfig& cfg) {
  if (cfg.memory.ideal || t.sram.empty()) return "";
  // The arrays hw_energy_json prices, at the sizes it prices them at.
  std::vector<std::pair<std::string, double>> arrays;
  if (cfg.memory.objects.enabled) {
    for (int k = 0; k < ObjectCachesConfig::kKinds; ++k)
      arrays.emplace_back(fmt::format("{} object cache", object_cache_name(static_cast<ObjectCachesConfig::Kind>(k))),
                          std::max(64.0, object_cache_bytes(cfg.memory.objects.cache[k])));
  } else {
    arrays.emplace_back("L1", static_cast<double>(cfg.memory.l1.size_bytes));
    arrays.emplace_back("L2", static_cast<double>(cfg.memory.l2.size_bytes));
  }
  const double lo = t.sram.front().bytes, hi = t.sram.back().bytes;
  std::string s;
  for (const auto& [name, bytes] : arrays) {
    bool outside = false;
    t.sram_64bit_pj(bytes, &outside);
    if (!outside) continue;
    s += fmt::format("  warning: the {} ({}) is {} the SRAM table of {} ({} to {}): its access energy is {}\n", name,
                     size_text(bytes), bytes < lo ? "below" : "above", t.path, size_text(lo), size_text(hi),
                     t.sram.size() == 1 ? "the table's one figure" : "extrapolated along the nearest segment's power law");
  }
  return s;
}

nlohmann::json hw_energy_json(const TechFile& t, const HwConfig& cfg, const ReplayOptions& opt, const ReplayStats& stats,
                              const HwCounters& c, const nlohmann::json& memory, const ReplacedUnits& replaced) {
  OperationEnergy ops = operation_energy(t, opt.method, opt.tester, stats);
  const HwArea area = hw_area(t, cfg, opt, replaced);
  {
    // Replaced units: their declared operations, or nothing.
    const KindStats k = stats.total();
    const double rays = static_cast<double>(k.rays);
    if (const ReplacedUnit* r = find_unit(replaced, "box_unit")) {
      const UnitInventory* i = inventory_of(r);
      ops.box = i ? k.traversal.box_tests * t.energy_pj(i->per_operation) + rays * t.energy_pj(i->per_ray) : 0.0;
    }
    if (const ReplacedUnit* r = find_unit(replaced, "triangle_tester")) {
      const UnitInventory* i = inventory_of(r);
      ops.triangle =
          i ? k.traversal.triangle_tests * t.energy_pj(i->per_operation) + rays * t.energy_pj(i->per_ray) : 0.0;
    }
    if (const ReplacedUnit* r = find_unit(replaced, "avoidance_unit")) {
      const UnitInventory* i = inventory_of(r);
      const double avoidance = i ? k.candidates.suspects * t.energy_pj(i->per_operation) : 0.0;
      ops.method += avoidance - ops.avoidance;
      ops.avoidance = avoidance;
    }
    if (find_unit(replaced, "ray_source")) {
      ops.method -= ops.emission + ops.result;
      ops.emission = ops.result = 0;
    }
  }
  // Memory: every L1 access reads a line, every miss writes one (a fill,
  // priced as an access); likewise the L2; DRAM per 64 bits moved; a stack
  // spill writes one 16-byte entry through the L1.
  double l1 = 0, l2 = 0, dram = 0, spills = 0;
  bool extrapolated = false;
  if (cfg.memory.objects.enabled && memory.contains("objects")) {
    // Every lookup reads an object, every miss writes one (its fill), each from
    // an SRAM of its cache's size; DRAM per 64 bits moved.
    for (int k = 0; k < ObjectCachesConfig::kKinds; ++k) {
      const ObjectCacheConfig& oc = cfg.memory.objects.cache[k];
      const nlohmann::json& m = memory["objects"][object_cache_name(static_cast<ObjectCachesConfig::Kind>(k))];
      bool e = false;
      const double w = (oc.bytes ? oc.bytes : 64) / 8.0 * t.sram_64bit_pj(std::max(64.0, object_cache_bytes(oc)), &e);
      extrapolated = extrapolated || e;
      l1 += (m["lookups"].get<double>() + m["misses"].get<double>()) * w;
    }
    dram = memory["dram"]["bytes"].get<double>() / 8.0 * t.dram_64bit_pj;
  } else if (!cfg.memory.ideal && memory.contains("l1")) {
    bool e1 = false, e2 = false;
    const double w1 = cfg.memory.l1.line_bytes / 8.0 * t.sram_64bit_pj(cfg.memory.l1.size_bytes, &e1);
    const double w2 = cfg.memory.l2.line_bytes / 8.0 * t.sram_64bit_pj(cfg.memory.l2.size_bytes, &e2);
    extrapolated = e1 || e2;
    l1 = (memory["l1"]["accesses"].get<double>() + memory["l1"]["misses"].get<double>()) * w1;
    l2 = (memory["l2"]["accesses"].get<double>() + memory["l2"]["misses"].get<double>()) * w2;
    if (memory["dram"].contains("bytes")) dram = memory["dram"]["bytes"].get<double>() / 8.0 * t.dram_64bit_pj;
    else dram = memory["dram"]["reads"].get<double>() * cfg.memory.l2.line_bytes / 8.0 * t.dram_64bit_pj;
    spills = static_cast<double>(c.spills) * (BvhStepper<ThreeHalfPlaneTester>::kEntryBytes / 8.0) *
             t.sram_64bit_pj(cfg.memory.l1.size_bytes);
  }
  if (find_unit(replaced, "l1_cache")) l1 = spills = 0;
  if (find_unit(replaced, "l2_cache")) l2 = dram = 0;  // the replacement is the L2 and the memory behind it
  const double dynamic = ops.total() + l1 + l2 + dram + spills;
  const double seconds = static_cast<double>(c.cycles) / (cfg.clock_mhz * 1e6);
  const double leak_pj_per_mm2 = t.leakage_w_per_mm2 * seconds * 1e12;
  const double stat = area.chip() * leak_pj_per_mm2;
  const double total = dynamic + stat;
  const uint64_t rays = c.rays;
  // Per instance: its share of its kind's dynamic energy and its own leakage.
  const auto instance = [&](double dyn, uint32_t n, double mm2) {
    return n ? dyn / n + mm2 * leak_pj_per_mm2 : 0.0;
  };
  nlohmann::json j;
  j["tech"] = t.path;
  j["memory_model"] = cfg.memory.ideal            ? "ideal memory: not priced"
                      : cfg.memory.objects.enabled ? "object caches: SRAM per object read or written, DRAM per 64 bits"
                                                   : "SRAM per 64-bit access, DRAM per 64 bits";
  if (extrapolated) j["sram_size_extrapolated"] = true;
  if (!replaced.empty()) {
    j["replaced_units"] = replaced_json(replaced);
    j["priced"] = all_priced(replaced);
  }
  j["dynamic_pj"] = operation_parts_json(ops);
  j["dynamic_pj"]["l1"] = l1;
  j["dynamic_pj"]["l2"] = l2;
  j["dynamic_pj"]["dram"] = dram;
  j["dynamic_pj"]["stack_spills"] = spills;
  j["dynamic_total_pj"] = dynamic;
  j["static_pj"] = stat;
  j["total_pj"] = total;
  j["per_ray_pj"] = per_ray(total, rays);
  j["dynamic_per_ray_pj"] = per_ray(dynamic, rays);
  j["static_per_ray_pj"] = per_ray(stat, rays);
  j["method_per_ray_pj"] = per_ray(ops.method, rays);
  j["mrays_per_j"] = mrays_per_joule(total, rays);
  j["seconds"] = seconds;
  j["power_w"] = seconds > 0 ? total * 1e-12 / seconds : 0.0;
  j["per_unit_instance_pj"] = {
      {"box_unit", instance(ops.box, area.box_units, area.box_unit)},
      {"triangle_tester", instance(ops.triangle + ops.candidate_filter, area.triangle_testers, area.triangle_tester)},
      {"avoidance_unit", instance(ops.avoidance, area.avoidance_units, area.avoidance_unit)},
      {"emission_lane", instance(ops.emission + ops.result, area.emission_lanes, area.emission_unit)},
      {"l1_cache", instance(l1 + spills, cfg.memory.ideal ? 0 : cfg.cores, area.l1_cache)},
      {"l2_cache", instance(l2, cfg.memory.hierarchy() ? 1 : 0, area.l2_cache)}};
  return j;
}

std::string hw_energy_lines(const nlohmann::json& e, const nlohmann::json& a) {
  std::string unpriced;
  if (e.contains("replaced_units"))
    for (const auto& r : e["replaced_units"])
      if (!r["priced"].get<bool>()) {
        const std::string unit = r["unit"].get<std::string>();
        const bool declarable = unit == "box_unit" || unit == "triangle_tester" || unit == "avoidance_unit";
        unpriced += fmt::format("  not priced: {} (a replaced {} {}; its energy and area are left out)\n",
                                r["instance"].get<std::string>(), unit,
                                declarable ? "that declares no operation inventory"
                                           : "(only a box unit, triangle tester or avoidance unit is priced from the "
                                             "operations it declares)");
      }
  return unpriced + fmt::format("  energy {:.4g} pJ/ray ({:.4g} dynamic, {:.4g} static; the method {:.4g} pJ/ray)   {:.4g} Mrays/J   "
                     "{:.4g} W\n  area {:.4f} mm2 (avoidance units {:.5f} mm2, the method's ray-record bits {:.5f} mm2)\n",
                     e["per_ray_pj"].get<double>(), e["dynamic_per_ray_pj"].get<double>(),
                     e["static_per_ray_pj"].get<double>(), e["method_per_ray_pj"].get<double>(),
                     e["mrays_per_j"].get<double>(), e["power_w"].get<double>(), a["chip_mm2"].get<double>(),
                     a["avoidance_units_mm2"].get<double>(), a["method_record_bits_mm2"].get<double>());
}

}  // namespace vbsim::hw
